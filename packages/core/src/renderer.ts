import type { PassTextureBinding, TextureDescriptor, TextureFormat } from './gpu/backend.js';
import type { Scene } from './scene/scene.js';
import type { UniformField, UniformLayout, UniformValues } from './uniforms/layout.js';
import type { ParamSpecs } from './validation/params.js';

/** A kernel in both shading languages; the context prepends the shared chunks and the prelude. */
export interface KernelSource {
  glsl: string;
  wgsl: string;
}

/**
 * A renderer plugin, declared rather than driven: the RenderContext runs its three
 * kernels as full-screen passes (docs/design.md, "The pipeline"):
 *
 *  - generate:  textures `volume` (3D, compact format: gpu/volume-format.ts; read through sampleVolume()) and `transferFunction`
 *               (2D rgba32float, tfSize x tfHeight: 1 row for a 1D TF, 256 for a 2D one),
 *               plus the gradient textures when needed (see `needsGradient`)
 *               → `frameFormats` (the new sample). Kernels read the TF through the
 *               shared `transferAt(p)`, which works for 1D and 2D alike.
 *  - integrate: textures `frame0..` and `accum0..` (the previous accumulation) →
 *               `accumulationFormats`. With `u.iteration == 0` it must ignore `accum*`
 *               (that is how reset works: nothing is cleared, the first sample overwrites).
 *  - render:    textures `accum0..` → one rgba32float HDR image (linear RGB, a = coverage).
 *
 * All three see the same uniform block: SCENE_UNIFORM_FIELDS followed by `paramFields`.
 * `u.iteration` is the index of the sample being generated/integrated (0-based); a kernel draws
 * its random numbers for sample `u.iteration + u.sampleBase` (rngInit), where `u.sampleBase` is 0
 * but under temporal reuse, whose views continue one sample sequence.
 */
export interface Renderer {
  readonly name: string;
  readonly frameFormats: readonly TextureFormat[];
  readonly accumulationFormats: readonly TextureFormat[];
  readonly kernels: {
    readonly generate: KernelSource;
    readonly integrate: KernelSource;
    readonly render: KernelSource;
  };
  readonly paramFields: readonly UniformField[];
  /**
   * Bumped whenever a parameter that changes the image changes; the context resets
   * accumulation when it sees a new version.
   */
  readonly version: number;
  paramValues(scene: Scene): UniformValues;
  /** Compile-time feature flags derived from the scene: one kernel variant per distinct set. */
  features(scene: Scene): Record<string, boolean | number>;
  /**
   * Extra textures the generate pass reads (majorant grid, environment CDFs…), derived
   * from the scene. The context binds each under `name`, builds it with `create()` only
   * when its `key` changes (so a camera move rebuilds nothing), frees it when it is no
   * longer listed, and rebuilds all of them after a context loss.
   */
  auxiliaryTextures?(scene: Scene, volume: VolumeBinding): readonly AuxiliaryTexture[];
  /**
   * Indices into `accumulationFormats` of two textures holding the running means of the
   * even and of the odd iterations. When present, `RenderContext.estimateError()` reports
   * the live error of the full estimate from their difference.
   */
  readonly halfAccumulations?: readonly [number, number];
  /**
   * Set when the generate kernel reads the gradient magnitude. The context then builds
   * the volume's gradient-magnitude texture once (on the GPU), binds it as
   * `gradientMagnitude` + `gradientMax`, defines VPT_GRADIENT and includes the chunk with
   * `sampleGradientMagnitude(p)` / `normalizedGradientAt(p)`. A 2D transfer function
   * does the same on its own (and defines VPT_TF_2D), whatever this flag says.
   */
  readonly needsGradient?: boolean;
  /**
   * Set when the generate kernel draws a scene's `slicePlane` (scene/slice-plane.ts) under
   * `#if VPT_SLICE_PLANE`: the context then defines it for a scene that has one, includes the
   * shared chunk's slicePlaneHit() / slicePlaneColor() and their uniforms, and binds the colour
   * map as `slicePlaneColormap`. A renderer without it ignores the field.
   */
  readonly drawsSlicePlane?: boolean;
  /**
   * Draws a scene's `labels` (scene/labels.ts) under `#if VPT_LABELS`: the context then defines
   * it for a scene that has labels, includes the shared chunk's labelIdAt() / labelAt() and the
   * image + labels transferAt(), the `labelScale` uniform, and binds `labelVolume` and
   * `labelTable` (the render pass binds `labelTable` too). A renderer without it ignores the field.
   */
  readonly drawsLabels?: boolean;
  /**
   * Set when the generate kernel writes the denoiser guides (docs/architecture.md, "Denoising"):
   * while a post step uses them the context defines VPT_GUIDES, includes the helpers
   * `guideNormalDepth(p, t)` / `guideAlbedo(rgb)` and appends two rgba32float outputs after
   * `frameFormats`, which the kernel fills with those helpers' values at its pixel's
   * representative point (zeros where the ray hits nothing).
   */
  readonly writesGuides?: boolean;
  /**
   * false: temporal reuse leaves out its normal test (TemporalOptions.normalCos) for this
   * renderer, whose guide normal is no surface's: EAM's is the gradient at one sample's mean
   * termination depth inside a semi-transparent medium, MCRT's at one sample's first collision;
   * both turn from sample to sample, so the test rejected history taps at random (docs/benchmarks.md, "Orbit: a sharper and
   * decorrelated history"). Without it a tap fails only at a depth or hit/miss edge, so the
   * history of a footprint the tests cut counts by the share that passed. Default true.
   */
  readonly temporalNormalTest?: boolean;
  /**
   * Temporal reuse's history length for this renderer where TemporalOptions.maxHistory is not
   * given (default: that option's default, 12). A renderer nearly noise-free at a few samples
   * (EAM) gains less from a long history than the reprojection's error adds to it, step after
   * step (docs/benchmarks.md, "Orbit: a sharper and decorrelated history").
   */
  readonly temporalMaxHistory?: number;
  /**
   * The renderer's parameters and their ranges (core's validateParams): unknown keys and
   * out-of-range values are refused by the constructor and setParams; 'step' parameters are
   * checked against the scene's voxel size by RenderContext.setScene.
   */
  readonly paramSpecs?: ParamSpecs;
  /**
   * The renderer's rules that depend on the scene (a layer index past the volume's last
   * layer, say): run by RenderContext.setScene (validateSceneForDevice);
   * throws a VptError naming the parameter, and the context keeps what it had.
   */
  validateScene?(scene: Scene): void;
  /** The current parameter values (as given, defaults not filled in). */
  getParams?(): object;
  /**
   * What the renderer chose for the current scene, as short labelled strings (MCRT: its
   * estimator choices and why); RenderContext.stats.renderer passes it on and the viewer
   * shows it.
   */
  stats?(): Record<string, string>;
}

export interface AuxiliaryTexture {
  name: string;
  dimension: '2d' | '3d';
  /** Changes exactly when the content changes (e.g. a hash of the inputs). */
  key: string;
  /** Content made on the CPU and uploaded. Give this or `render`. */
  create?(): TextureDescriptor;
  /** Content made on the GPU by one full-screen pass (dimension '2d'): no CPU work and no read-back. */
  render?: AuxiliaryPass;
  /** Bound to the generate pass (default true); false for an input of a later AuxiliaryPass only. */
  bind?: boolean;
}

/**
 * How the bound volume texture reads: texel → normalized value v = clamp(texel · valueScale +
 * valueOffset, 0, 1) (gpu/volume-format.ts), for auxiliary passes that read texels with
 * texelFetch; `key` changes exactly when the texture or the mapping does.
 */
export interface VolumeBinding {
  valueScale: number;
  valueOffset: number;
  format: string;
  key: string;
  /**
   * Set when the volume is bricked (bricking/): the `volume` texture is then a brick atlas,
   * not the voxel grid, so a pass must not read its texels as voxels. Instead this gives, per
   * cell of a grid of `cells` over the box, the [min, max] of the normalized values the
   * kernels can read there — resident bricks' own data, a coarser level's bounds where a
   * brick is not resident yet. `key` changes whenever it does.
   */
  cellRanges?: (cells: readonly [number, number, number]) => {
    cells: [number, number, number];
    vmin: Float32Array;
    vmax: Float32Array;
  };
  /**
   * With `cellRanges`, for a channel scene: the same ranges per drawn channel (in order), each
   * normalized by that channel's range (a multichannel brick atlas keeps them per component).
   */
  channelCellRanges?: (cells: readonly [number, number, number]) => {
    cells: [number, number, number];
    vmin: Float32Array;
    vmax: Float32Array;
  }[];
}

/**
 * A full-screen pass whose single output becomes an auxiliary texture. It runs when the
 * texture's key changes, after the scene's volume and transfer function are uploaded, so
 * it can read them (`volume`, `transferFunction`) and any auxiliary texture listed before
 * it in `auxiliaryTextures()`.
 */
export interface AuxiliaryPass {
  label: string;
  width: number;
  height: number;
  format: TextureFormat;
  /** Fragment sources as for GpuBackend.createPass (prelude, `u.` uniforms, vpt_out0 / VptOut). */
  glsl: string;
  wgsl: string;
  uniforms: UniformLayout;
  values: UniformValues;
  inputs: readonly PassTextureBinding[];
}
