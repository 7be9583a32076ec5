import { VptError } from '../errors.js';
import { createBackend } from '../gpu/create-backend.js';
import type { GpuBackend, GpuPass, GpuTexture, PassDescriptor, RenderTarget } from '../gpu/backend.js';
import type { PostStep } from '../post-step.js';
import type { Renderer } from '../renderer.js';
import type { Scene } from '../scene/scene.js';
import { validateScene } from '../scene/scene.js';
import { TF_RESOLUTION } from '../scene/transfer-function.js';
import { BYTES_PER_TEXEL } from '../gpu/backend.js';
import { commonChunks, PASS_CHUNKS, type CommonChunkOptions } from '../shaders/common.js';
import { preprocess } from '../shaders/preprocess.js';
import { validateGradientAtlasForDevice, validateSceneForDevice } from '../validation/device.js';
import { SCENE_UNIFORM_FIELDS, sceneUniformValues } from '../shaders/scene-uniforms.js';
import { CLIP_UNIFORM_FIELDS, clipUniformValues, hasClip } from '../scene/clip.js';
import { CHANNEL_UNIFORM_FIELDS, LABEL_UNIFORM_FIELDS } from '../shaders/scene-uniforms.js';
import { labelSupport } from '../scene/label-support.js';
import { enabledChannels } from '../scene/channels.js';
import { SLICE_PLANE_UNIFORM_FIELDS, slicePlaneFlags, slicePlaneUniformValues } from '../scene/slice-plane.js';
import { UniformLayout, type UniformField } from '../uniforms/layout.js';
import { GUIDES } from '../shaders/guides.js';
import { GUIDE_FRAME_FORMATS, GuideBuffers } from './guide-buffers.js';
import { PostChain } from './post-chain.js';
import { PRESENT_PASS } from './present-pass.js';
import { checkGpuBudget, checkRenderSize, checkVolumeOptions, type RenderContextOptions } from './context-options.js';
import { ProgressiveLoop } from './progressive-loop.js';
import type { TemporalOptions, TemporalReuse } from './temporal-reuse.js';
import { SceneResources } from './scene-resources.js';
import { VolumeFit, maxRenderPixels, volumeBudgetBytes, type RenderWarning } from './volume-fit.js';
import type { BrickingStats } from '../bricking/bricked-volume.js';
import type { MultiscaleSource } from '../bricking/source.js';

/** GPU memory the context holds, in bytes (texture sizes × bytes per texel, as allocated). */
export interface GpuBytes {
  /** The volume texture. */
  volume: number;
  /** The gradient-magnitude atlas and its maximum, when a scene needs them. */
  gradient: number;
  /** The transfer function and the renderer's auxiliary textures (majorant grid, environment…). */
  auxiliary: number;
  /** Frame, accumulation, HDR and post-chain targets. */
  targets: number;
  total: number;
}

export interface RenderStats {
  /** Iterations accumulated since the last reset. */
  iterations: number;
  /** Samples per pixel (one path per pixel per iteration). */
  samplesPerPixel: number;
  /** Mean wall-clock ms per iteration over the last measured batch (GPU synchronised). */
  msPerIteration: number;
  /**
   * The progressive loop's ms per frame for the render pass, the post chain and the present,
   * learned apart from the iterations (0 before the loop ran): a denoiser costs once per frame.
   */
  msPostPerFrame: number;
  /** GPU memory held now. */
  gpuBytes: GpuBytes;
  /** The brick cache's state when the volume is bricked, else null. */
  bricking: BrickingStats | null;
  /** The renderer's own choices for the current scene (Renderer.stats; empty when it has none). */
  renderer: Record<string, string>;
  /** Volumes written into the texture of the previous one (same dims and format: a time series' next step) instead of a new one. */
  volumeRewrites: number;
}

type RendererPasses = { generate: GpuPass; integrate: GpuPass; render: GpuPass };

/**
 * Owns the backend, the scene's GPU resources, the renderer's buffers and the post
 * chain, and runs the progressive loop: generate → integrate per iteration, then
 * render → post → present. Resets accumulation whenever the image would change.
 */
/** An opaque surface's depth that ends camera rays (RenderContext.setDepthLimit). */
export interface DepthLimit {
  /** A depth texture of the render size on the shared WebGL 2 context (WebGLTexture) or GPUDevice (GPUTexture, depth32float). */
  texture: WebGLTexture | GPUTexture;
  /** Forward distance = a / (2d − 1 + b) for window depth d (three.js: a = P[14] / k, b = P[10]). */
  a: number;
  b: number;
  /**
   * Also accumulate the renderer's depth guide (the depth that stands for each pixel: MCRT's
   * first real collision, EAM's mean termination depth, ISO's surface), read with
   * `depthGuideGlTextures()`, so a compositor can write a representative depth rather than
   * the box entry. Renderers without guides (MIP) accumulate none. Default false.
   */
  depthGuide?: boolean;
}

/** The uniforms of the depth limit, appended to the layout only while one is set. */
/** Kernel flags that become backend defines only when set (an unset one leaves the program unchanged). */
const OPTIONAL_DEFINES = new Set(['VPT_CLIP', 'VPT_CHANNELS', 'VPT_SLICE_PLANE', 'VPT_LABELS']);

const DEPTH_LIMIT_FIELDS: readonly UniformField[] = [
  { name: 'depthA', type: 'f32' },
  { name: 'depthB', type: 'f32' },
];

export class RenderContext {
  readonly backend: GpuBackend;
  private _renderer: Renderer;
  private scene: Scene | null = null; // as rendered: its volume may be a downsampled copy (fitScene)
  private input: Scene | null = null; // as given to setScene
  private width: number;
  private height: number;
  private layout!: UniformLayout;
  private passes: RendererPasses | null = null;
  private presentPass: GpuPass | null = null;

  // Volume, transfer function, gradient and auxiliary textures, with their lifetimes.
  private readonly resources: SceneResources;
  // The budget fit of the scene's volume (downsampled or bricked) and the multiscale sources.
  private readonly volumeFit: VolumeFit;
  private readonly brickLod: boolean;
  readonly maxGpuBytes: number;
  private readonly warningListeners = new Set<(w: RenderWarning) => void>();
  private frame: RenderTarget | null = null;
  private accum: [RenderTarget, RenderTarget] | null = null;
  private hdr: RenderTarget | null = null;
  // The post steps, their passes and targets.
  private readonly postChain: PostChain;
  // Accumulated denoiser guides, while a post step uses them; the frame target then holds the guide frames too.
  private guides: GuideBuffers | null = null;
  private frameHasGuides = false;
  // Whether this estimate accumulates guides: decided at each reset (guides are means over every
  // iteration since it), so removing the denoiser keeps the samples and adding it starts over.
  private guidesActive = false;
  // Temporal reuse across camera changes (null: off), see "Temporal reuse".
  private temporal: TemporalReuse | null = null;
  private sampleStart = 0;
  // GPU work queued between the progressive loop's frames (ProgressiveLoopHooks.takeOutsideWork).
  private outsideWork = false;
  private temporalGeneration = 0;
  private temporalWanted = false;
  // The HDR image shown: the render pass's, or the temporal resolve's.
  private displayed: GpuTexture | null = null;
  private hdrRenderedAt = -1; // iteration count the render (and resolve) pass last ran at

  private iteration = 0;
  private rendererVersion = -1;
  private variantKey = '';
  /** The scene precompile() last ran for (it runs once per scene, renderer or restore). */
  private precompiledFor: Scene | null = null;
  private hdrIteration = -1; // iteration count the HDR/LDR images were last rendered at
  private imageVersion = 0; // bumped whenever renderImage() produced a new LDR image
  private presentedVersion = -1;
  private msPerIteration = 0;
  private msPostPerFrame = 0;
  private disposed = false;
  private readonly loop: ProgressiveLoop;
  private readonly listeners = new Set<(stats: RenderStats) => void>();
  private depthLimit: {
    handle: WebGLTexture | GPUTexture;
    texture: GpuTexture;
    a: number;
    b: number;
    depthGuide: boolean;
  } | null = null;

  private constructor(backend: GpuBackend, opts: RenderContextOptions) {
    this.backend = backend;
    this._renderer = opts.renderer;
    this.postChain = new PostChain(backend, opts.post ?? []);
    const volumeOptions = checkVolumeOptions(opts);
    this.resources = new SceneResources(backend, () => ({ scene: this.scene, renderer: this._renderer }), {
      sampling: volumeOptions.sampling,
      allowHalfFloat: volumeOptions.allowHalfFloat,
    });
    this.maxGpuBytes = checkGpuBudget(opts.maxGpuBytes, backend.limits);
    this.brickLod = volumeOptions.brickLod;
    this.volumeFit = new VolumeFit(volumeOptions, {
      resources: this.resources,
      maxGpuBytes: this.maxGpuBytes,
      max3D: () => this.backend.limits.maxTextureDimension3D,
      size: () => this.size,
      budgetBytes: () => this.volumeBudgetBytes,
      labels: (scene) => {
        if (!this.drawsLabels(scene)) return null;
        const support = labelSupport();
        return {
          bytesPerVoxel: support.labelBytesPerVoxel(scene.labels!.volume.type, this.backend.capabilities.norm16),
          downsample: support.downsampleLabels,
        };
      },
      warn: (w) => this.warn(w),
    });
    checkRenderSize(opts.width, opts.height, backend.limits);
    this.width = opts.width;
    this.height = opts.height;
    this.backend.resizeCanvas(this.width, this.height);
    this.loop = new ProgressiveLoop({
      ready: () => this.precompile(),
      step: (n) => this.iterate(n),
      finishFrame: () => this.present(),
      sync: () => this.backend.finish(),
      // Bricks that arrive after convergence still upload; the reset makes the loop iterate again.
      idle: () => {
        if (this.updateBricks()) this.reset();
      },
      takeOutsideWork: () => {
        const queued = this.outsideWork;
        this.outsideWork = false;
        return queued;
      },
      onStats: (ms, post) => {
        this.msPerIteration = ms;
        this.msPostPerFrame = post;
        this.emit();
      },
    });
    backend.onLost(() => this.loop.pause());
    backend.onRestored(() => this.restore());
  }

  static async create(opts: RenderContextOptions): Promise<RenderContext> {
    const backend = await createBackend({
      backend: opts.backend ?? 'auto',
      canvas: opts.canvas,
      ...(opts.gl ? { gl: opts.gl } : {}),
      ...(opts.device ? { device: opts.device } : {}),
    });
    try {
      const ctx = new RenderContext(backend, opts);
      if (opts.temporal !== undefined) await ctx.setTemporal(opts.temporal);
      return ctx;
    } catch (e) {
      backend.dispose();
      throw e;
    }
  }

  get renderer(): Renderer {
    return this._renderer;
  }
  get post(): readonly PostStep[] {
    return this.postChain.steps;
  }
  get size(): { width: number; height: number } {
    return { width: this.width, height: this.height };
  }

  get stats(): RenderStats {
    return {
      iterations: this.iteration,
      samplesPerPixel: this.iteration,
      msPerIteration: this.msPerIteration,
      msPostPerFrame: this.msPostPerFrame,
      gpuBytes: this.gpuBytes(),
      bricking: this.resources.bricked?.stats() ?? null,
      renderer: this._renderer.stats?.() ?? {},
      volumeRewrites: this.resources.volumeRewrites,
    };
  }

  /** Called when the context changes something to make a scene fit (a downsampled volume). */
  onWarning(listener: (warning: RenderWarning) => void): () => void {
    this.warningListeners.add(listener);
    return () => this.warningListeners.delete(listener);
  }

  /** GPU memory held now, by kind (textures as allocated: width × height × depth × bytes per texel). */
  gpuBytes(): GpuBytes {
    const tex = (t: GpuTexture | null | undefined) =>
      t ? t.width * t.height * t.depth * BYTES_PER_TEXEL[t.format] : 0;
    const target = (t: RenderTarget | null | undefined) => (t ? t.textures.reduce((a, x) => a + tex(x), 0) : 0);
    const res = this.resources;
    const volume = res.bricked ? res.bricked.gpuBytes() : tex(res.volumeTexture);
    const gradient = res.gradient ? target(res.gradient.atlas) + target(res.gradient.max) : 0;
    let auxiliary = tex(res.tfTexture);
    for (const a of res.auxTextures.values()) auxiliary += tex(a.texture);
    let targets =
      target(this.frame) + target(this.hdr) + (this.accum ? target(this.accum[0]) + target(this.accum[1]) : 0);
    for (const t of [
      ...this.postChain.allTargets(),
      ...(this.guides?.targets ?? []),
      ...(this.temporal?.targets ?? []),
    ])
      targets += target(t);
    return { volume, gradient, auxiliary, targets, total: volume + gradient + auxiliary + targets };
  }

  /** Called with fresh stats after each progressive batch. */
  onStats(listener: (stats: RenderStats) => void): () => void {
    this.listeners.add(listener);
    return () => this.listeners.delete(listener);
  }

  /**
   * Replace the scene. The scene is validated first: an invalid scene throws
   * VptError('invalid-scene' | 'limit-exceeded') and the context keeps the previous one.
   */
  setScene(input: Scene): void {
    this.assertAlive();
    validateScene(input);
    validateSceneForDevice(input, this.renderer, this.backend.limits);
    const scene = this.volumeFit.fitScene(input);
    if (this.wantsGradient(scene)) validateGradientAtlasForDevice(scene.volume.dims, this.backend.limits);
    const previous = { scene: this.scene, plan: this.resources.brickPlanNow() };
    // A camera change alone keeps the current image as temporal history; anything else drops it.
    if (this.temporal) {
      if (this.scene && this.input && scene.volume === this.scene.volume && this.temporal.cameraOnly(this.input, input))
        this.keepHistory();
      else this.temporal.invalidate();
    }
    this.scene = scene;
    this.resources.setBrickPlan(this.volumeFit.bricks);
    try {
      this.resources.sync();
    } catch (e) {
      // A bricked volume that cannot be held (VptError 'limit-exceeded'): keep the previous scene.
      this.scene = previous.scene;
      this.resources.setBrickPlan(previous.plan);
      this.volumeFit.forget();
      throw e;
    }
    this.input = input;
    this.reset();
  }

  /**
   * Back a volume by a multiscale source (an OME-Zarr store, say): whenever a scene's volume
   * is this object, the context bricks it from `source` (levels streamed as the view needs
   * them) instead of uploading its voxels. `standIn` is typically the source's coarsest
   * level (readLevel): CPU-side users of the scene (histograms, the viewer) read it, and
   * with a 2D transfer function or a renderer that needs the gradient volume it is rendered
   * as it is. The box is the source's level 0.
   */
  setVolumeSource(standIn: Scene['volume'], source: MultiscaleSource): void {
    this.assertAlive();
    this.volumeFit.setVolumeSource(standIn, source);
  }

  /**
   * Resolves once a bricked volume has loaded what it can (every brick resident, or the
   * atlas full of wanted ones), uploading arrived bricks itself when no loop runs; at once
   * for an unbricked volume. Rejects with the source's error.
   */
  async whenBricksSettled(): Promise<BrickingStats | null> {
    this.assertAlive();
    for (;;) {
      this.assertAlive();
      const bricked = this.resources.bricked;
      if (!bricked) return null;
      if (!this.loop.running && this.updateBricks()) this.reset();
      const stats = bricked.stats();
      if (stats.complete) return stats;
      await (this.loop.running ? new Promise((r) => setTimeout(r, 10)) : bricked.nextArrival());
    }
  }

  /** One frame's brick residency work; true when what the kernels read changed. */
  private updateBricks(): boolean {
    const bricked = this.resources.bricked;
    if (!bricked || !this.scene || this.backend.isLost) return false;
    return bricked.update({ camera: this.scene.camera, width: this.width, height: this.height, lod: this.brickLod });
  }

  /**
   * Bytes a volume (with its gradient) or a brick atlas may take at this size, renderer and
   * post chain: maxGpuBytes less the render targets and the transfer function. A caller
   * choosing a level of a multiscale source (or whether to stream it) uses this rule.
   */
  get volumeBudgetBytes(): number {
    return volumeBudgetBytes(this.maxGpuBytes, this.width, this.height, this._renderer, this.postChain.steps.length);
  }

  /**
   * The most pixels a render size may have at this renderer and post chain: the render
   * targets may take half of maxGpuBytes (the rest is the volume's). A caller sizing the
   * image to an element (the viewer) clamps to it; setSize itself does not.
   */
  get maxRenderPixels(): number {
    return maxRenderPixels(this.maxGpuBytes, this._renderer, this.postChain.steps.length, this.postChain.wantsGuides());
  }

  private warn(warning: RenderWarning): void {
    if (this.warningListeners.size === 0) console.warn(`vpt: ${warning.message}`);
    this.warningListeners.forEach((l) => l(warning));
  }

  /** Shallow-merge changes into the current scene (camera, lights, TF…) and reset. */
  updateScene(changes: Partial<Scene>): void {
    if (!this.input) throw new VptError('invalid-scene', 'updateScene() before setScene()');
    this.setScene({ ...this.input, ...changes });
  }

  getScene(): Scene | null {
    return this.scene;
  }

  setRenderer(renderer: Renderer): void {
    this.temporal?.invalidate();
    this._renderer = renderer;
    this.passes = null;
    this.destroyRendererTargets();
    this.reset();
  }

  setPost(steps: PostStep[]): void {
    this.postChain.setSteps(steps);
    this.hdrIteration = -1;
    // Guides are means over every iteration since the reset: a chain that starts using them starts over.
    if (!this.guidesActive && this.wantsGuides()) this.reset();
  }

  setSize(width: number, height: number): void {
    checkRenderSize(width, height, this.backend.limits);
    if (width === this.width && height === this.height) return;
    // The reprojection works in film coordinates: the image at the old size is history for the new one.
    this.keepHistory();
    this.width = width;
    this.height = height;
    this.backend.resizeCanvas(width, height);
    this.destroyRendererTargets();
    this.postChain.destroy();
    this.reset();
  }

  /**
   * End camera rays at an opaque surface drawn by someone else on a shared WebGL 2 context
   * (RenderContextOptions.gl), or stop doing so (null). `texture` is a depth texture of the
   * render size holding, per pixel, window depth d ∈ [0, 1] of a perspective projection; the
   * distance along the camera's forward axis in vpt's world units is a / (2d − 1 + b) (for
   * three.js's projection matrix P and a world scale k: a = P[14] / k, b = P[10]). A camera
   * ray then ends at that surface: ray marches (EAM) stop there, and MCRT treats it as an
   * opaque boundary for camera rays; in both, the image no longer includes the background:
   * rgb is the volume's radiance and a = 1 − transmittance (in expectation for MCRT), to be
   * composited over the surface's colour as rgb + (1 − a) · surface. Restarts accumulation.
   */
  setDepthLimit(limit: DepthLimit | null): void {
    this.assertAlive();
    if (limit === null) {
      const had = this.depthLimit !== null;
      this.depthLimit = null;
      if (had) {
        this.temporal?.invalidate();
        this.reset();
      }
      return;
    }
    if (!this.backend.importTexture)
      throw new VptError('no-backend', 'setDepthLimit needs a shared WebGL 2 context or GPUDevice');
    for (const [name, v] of [
      ['a', limit.a],
      ['b', limit.b],
    ] as const)
      if (!Number.isFinite(v)) throw new VptError('invalid-scene', `DepthLimit: ${name} must be finite, got ${v}`);
    const prev = this.depthLimit;
    const same =
      prev !== null &&
      prev.handle === limit.texture &&
      prev.a === limit.a &&
      prev.b === limit.b &&
      prev.depthGuide === (limit.depthGuide === true) &&
      prev.texture.width === this.width &&
      prev.texture.height === this.height;
    if (same) return;
    this.depthLimit = {
      handle: limit.texture,
      texture: this.backend.importTexture(limit.texture, this.width, this.height, 'depth limit'),
      a: limit.a,
      b: limit.b,
      depthGuide: limit.depthGuide === true,
    };
    this.temporal?.invalidate();
    this.reset();
  }

  /**
   * The accumulated depth guide of a depth limit with `depthGuide` (WebGL 2 textures of this
   * context, vpt's rows top-down): `normalDepth.a` is the mean over iterations of the guide
   * distance along the camera ray (0 where a sample had no hit) and `albedoHit.a` the share
   * of iterations with a hit, so their ratio is the mean distance of the hits. Null when none
   * is accumulated (no such limit, a renderer without guides, no iteration yet).
   */
  depthGuideGlTextures(): { normalDepth: WebGLTexture; albedoHit: WebGLTexture } | null {
    return this.backend.kind === 'webgl2'
      ? (this.depthGuideHandles() as { normalDepth: WebGLTexture; albedoHit: WebGLTexture } | null)
      : null;
  }

  /** As depthGuideGlTextures, on WebGPU (GPUTextures, rgba32float). */
  depthGuideGpuTextures(): { normalDepth: GPUTexture; albedoHit: GPUTexture } | null {
    return this.backend.kind === 'webgpu'
      ? (this.depthGuideHandles() as { normalDepth: GPUTexture; albedoHit: GPUTexture } | null)
      : null;
  }

  private depthGuideHandles(): { normalDepth: WebGLTexture | GPUTexture; albedoHit: WebGLTexture | GPUTexture } | null {
    this.assertAlive();
    if (!this.guides || !this.frameHasGuides || this.iteration === 0 || !this.backend.textureHandle) return null;
    const t = this.guides.textures();
    const normalDepth = this.backend.textureHandle(t.guideNormalDepth);
    const albedoHit = this.backend.textureHandle(t.guideAlbedo);
    return normalDepth && albedoHit ? { normalDepth, albedoHit } : null;
  }

  /**
   * The temporal state of the image shown (for tests and tools): per pixel (hit share, samples
   * it stands for, 0, 0), where samples − the iteration count is the history's weight (0 where
   * a pixel took none). Null while temporal reuse is off or not resolving.
   */
  readTemporalState(): Promise<Float32Array | null> {
    return this.readTemporalOutput(2);
  }

  /** The guide the next view reprojects through: per pixel (normal, hit depth along the camera ray), as readTemporalState. */
  readTemporalGuide(): Promise<Float32Array | null> {
    return this.readTemporalOutput(1);
  }

  private async readTemporalOutput(index: number): Promise<Float32Array | null> {
    this.assertAlive();
    if (!this.resolving() || this.iteration === 0) return null;
    this.renderHdr();
    const out = this.temporal!.output;
    return out ? ((await this.backend.readTexture(out.textures[index])) as Float32Array) : null;
  }

  /** Whether guides are accumulated from the next reset: for a post step, or for a depth limit's depth guide. */
  private wantsGuides(): boolean {
    return (
      this.postChain.wantsGuides() ||
      this.depthLimit?.depthGuide === true ||
      (this.temporal !== null && this._renderer.writesGuides === true)
    );
  }

  /**
   * Where estimates start in the sample sequence from now on (default 0): iteration i draws the
   * random numbers of sample start + i. Estimates of one scene over disjoint ranges draw
   * disjoint numbers (blue noise's per-pixel rank-1 sequence runs on), so they can be made apart
   * and averaged: a still rendered in parts, or the plain estimate a temporal view draws (its
   * views continue the sequence, TemporalReuse.sampleBase, on top of this start). An integer in
   * [0, 2^32); a change restarts accumulation.
   */
  setSampleStart(start: number): void {
    this.assertAlive();
    if (!Number.isInteger(start) || start < 0 || start > 0xffffffff)
      throw new VptError('invalid-scene', `setSampleStart needs an integer in [0, 2^32), got ${start}`);
    if (start === this.sampleStart) return;
    this.sampleStart = start;
    this.temporal?.invalidate();
    this.reset();
  }

  /**
   * Temporal reuse across camera changes (see docs/architecture.md, "Temporal reuse"): true or
   * options turn it on (for renderers that write guides: MCRT, EAM, ISO), false off. Turning it
   * on starts a new estimate (it needs the depth guide from the first sample). Its module is
   * loaded on first use (a lazy chunk of the viewer's bundle): reuse starts when the returned
   * promise resolves, which rejects with a VptError naming the field for bad options (off
   * takes effect at once).
   */
  async setTemporal(options: boolean | TemporalOptions): Promise<void> {
    this.assertAlive();
    const generation = ++this.temporalGeneration;
    this.temporalWanted = options !== false;
    this.temporal?.destroy();
    this.temporal = null;
    this.hdrRenderedAt = -1;
    this.hdrIteration = -1;
    if (options === false) return;
    const module = await import('./temporal-reuse.js');
    let checked;
    try {
      checked = module.checkTemporalOptions(options);
    } catch (e) {
      if (generation === this.temporalGeneration) this.temporalWanted = false;
      throw e;
    }
    // A later call decided otherwise while the module loaded.
    if (generation !== this.temporalGeneration || this.disposed || !checked) return;
    // A maxHistory given here holds for every renderer; else a renderer's own (Renderer.temporalMaxHistory) does.
    const ownMaxHistory = typeof options === 'object' && options.maxHistory !== undefined;
    this.temporal = new module.TemporalReuse(this.backend, checked, ownMaxHistory);
    this.hdrRenderedAt = -1;
    this.hdrIteration = -1;
    if (!this.guidesActive && this.wantsGuides()) this.reset();
  }

  /** Whether temporal reuse is on or being turned on (it acts only for renderers that write guides). */
  get temporalReuse(): boolean {
    return this.temporal !== null || this.temporalWanted;
  }

  /** Whether this estimate's images go through the temporal resolve (guides accumulated). */
  private resolving(): boolean {
    return this.temporal !== null && this.guides !== null && this.frameHasGuides;
  }

  /** The view changes: keep the image shown now (resolved to the current iteration) as history. */
  private keepHistory(): void {
    if (!this.temporal || !this.scene) return;
    if (this.iteration > 0 && this.resolving() && !this.backend.isLost) {
      // Drawn now, outside the loop's frames, unless this iteration count was resolved already:
      // the loop must not time it as its iterations'.
      if (this.hdrRenderedAt !== this.iteration || !this.displayed) this.outsideWork = true;
      this.renderHdr();
    }
    this.temporal.keep(this.scene.camera, this.width / this.height, this.iteration);
  }

  /**
   * The HDR image (rgba32float, linear radiance, a = coverage), rendered from the current
   * accumulation; on WebGL 2 as a GL texture of this context (null before any iteration),
   * for compositing on a shared context. Valid until the next iteration or resize.
   */
  hdrGlTexture(): WebGLTexture | null {
    return this.backend.kind === 'webgl2' ? (this.hdrHandle() as WebGLTexture | null) : null;
  }

  /** As hdrGlTexture, on WebGPU: the HDR image's GPUTexture (rgba32float), for compositing on a shared device. */
  hdrGpuTexture(): GPUTexture | null {
    return this.backend.kind === 'webgpu' ? (this.hdrHandle() as GPUTexture | null) : null;
  }

  private hdrHandle(): WebGLTexture | GPUTexture | null {
    this.assertAlive();
    if (!this.scene || this.backend.isLost || this.iteration === 0 || !this.backend.textureHandle) return null;
    this.renderImage();
    return this.displayed ? this.backend.textureHandle(this.displayed) : null;
  }

  /** Drop accumulated samples: the next iteration starts a new estimate. */
  reset(): void {
    this.iteration = 0;
    this.hdrIteration = -1;
    this.hdrRenderedAt = -1;
    this.guidesActive = this.wantsGuides();
  }

  /** Run n iterations (generate + integrate each). Does not wait for the GPU. */
  iterate(n = 1): void {
    this.assertAlive();
    if (!this.scene || this.backend.isLost) return;
    // A bricked volume's uploads of this frame: what the kernels read changes, so the estimate restarts.
    if (this.updateBricks()) this.reset();
    this.prepare();
    const scene = this.scene;
    const passes = this.passes!;
    const textures: Record<string, GpuTexture> = {
      volume: this.resources.volumeTexture!,
      transferFunction: this.resources.tfTexture!,
    };
    const bricked = this.resources.bricked;
    if (bricked) {
      textures.pageTable = bricked.pageTable;
      textures.brickLevels = bricked.levels;
    }
    if (this.resources.gradient && this.wantsGradient(scene)) {
      textures.gradientMagnitude = this.resources.gradient.atlas.textures[0];
      textures.gradientMax = this.resources.gradient.max.textures[0];
    }
    for (const [name, aux] of this.resources.auxTextures) if (aux.bind) textures[name] = aux.texture;
    if (this.depthLimit) textures.meshDepth = this.depthLimit.texture;
    for (let k = 0; k < n; k++) {
      const uniforms = this.uniforms(scene);
      this.backend.draw(passes.generate, { uniforms, textures, target: this.frame! });
      const [prev, next] = this.accum!;
      const integrateTextures: Record<string, GpuTexture> = {};
      this.frame!.textures.forEach((t, i) => {
        integrateTextures[`frame${i}`] = t;
      });
      prev.textures.forEach((t, i) => {
        integrateTextures[`accum${i}`] = t;
      });
      this.backend.draw(passes.integrate, { uniforms, textures: integrateTextures, target: next });
      this.accum = [next, prev];
      if (this.guides) {
        const f = this.frame!.textures;
        const n = this._renderer.frameFormats.length;
        this.guides.integrate(this.iteration, f[0], this.frameHasGuides ? [f[n], f[n + 1]] : null);
      }
      this.iteration++;
    }
  }

  /** Reset, run exactly n iterations, render and post-process, and wait for the GPU. */
  async renderIterations(n: number): Promise<void> {
    if (!Number.isInteger(n) || n < 1)
      throw new VptError('invalid-scene', `renderIterations needs a positive integer, got ${n}`);
    await this.precompile();
    this.reset();
    const t0 = performance.now();
    this.iterate(n);
    await this.backend.finish();
    this.msPerIteration = (performance.now() - t0) / n;
    this.renderImage();
    await this.backend.finish();
  }

  /** Render accumulation → HDR → post chain (skipped when nothing changed since last time). */
  renderImage(): void {
    this.assertAlive();
    if (!this.scene || this.backend.isLost || this.iteration === 0) return;
    const postKey = this.postChain.parameterKey();
    if (this.hdrIteration === this.iteration && this.postChain.madeWith(postKey)) return;
    this.postChain.remember(postKey);
    this.renderHdr();
    this.postChain.run(this.displayed!, this.guides, this.width, this.height);
    this.hdrIteration = this.iteration;
    this.imageVersion++;
  }

  /** The render pass (accumulation → HDR) and, with temporal reuse, the resolve; once per iteration count. */
  private renderHdr(): void {
    const scene = this.scene!;
    this.prepare();
    if (this.hdrRenderedAt === this.iteration && this.displayed) return;
    const uniforms = this.uniforms(scene, this.iteration - 1);
    const accTextures: Record<string, GpuTexture> = {};
    this.accum![0].textures.forEach((t, i) => {
      accTextures[`accum${i}`] = t;
    });
    if (scene.channels) accTextures.transferFunction = this.resources.tfTexture!;
    if (this.drawsLabels(scene)) accTextures.labelTable = this.resources.auxTextures.get('labelTable')!.texture;
    this.backend.draw(this.passes!.render, { uniforms, textures: accTextures, target: this.hdr! });
    this.displayed = this.resolving()
      ? this.temporal!.resolve(
          this.hdr!.textures[0],
          this.guides!.textures(),
          scene.camera,
          this.width,
          this.height,
          this.iteration,
          this._renderer.temporalNormalTest !== false,
          this._renderer.temporalMaxHistory,
        )
      : this.hdr!.textures[0];
    this.hdrRenderedAt = this.iteration;
  }

  /** Draw the current LDR image to the canvas. */
  present(): void {
    if (!this.scene || this.backend.isLost || this.iteration === 0) return;
    this.renderImage();
    if (this.presentedVersion === this.imageVersion) return;
    this.presentPass ??= this.backend.createPass(PRESENT_PASS);
    this.backend.draw(this.presentPass, {
      uniforms: PRESENT_PASS.uniforms.pack({ pad: 0 }),
      textures: { inputImage: this.postChain.ldrTexture() },
      target: 'canvas',
    });
    this.presentedVersion = this.imageVersion;
  }

  /**
   * Resolves once the current image has at least `n` samples per pixel, rendered and
   * post-processed (so readHDR/readLDR see them). While `start()` refines in the
   * background this waits for it; otherwise it runs the missing iterations itself, so it
   * never waits for work nobody will do. Rejects when the context is disposed, and when
   * the running loop's `maxIterations` stops short of `n`.
   */
  async whenSamples(n: number): Promise<RenderStats> {
    this.assertAlive();
    if (!Number.isInteger(n) || n < 1)
      throw new VptError('invalid-scene', `whenSamples needs a positive integer, got ${n}`);
    if (!this.scene)
      throw new VptError('invalid-scene', 'whenSamples: there is no scene to render; call setScene() first');
    const limit = this.loop.maxIterations;
    if (this.loop.running && limit < n)
      throw new VptError('invalid-scene', `whenSamples(${n}): the progressive loop stops at maxIterations = ${limit}`);
    for (;;) {
      this.assertAlive();
      if (this.iteration >= n) break;
      // Not refining in the background (never started, stopped): do the rest here.
      if (!this.loop.running && !this.backend.isLost) {
        await this.precompile();
        if (!this.loop.running) this.iterate(n - this.iteration);
      } else await new Promise((resolve) => setTimeout(resolve, 10));
    }
    this.renderImage();
    await this.backend.finish();
    return this.stats;
  }

  /**
   * The HDR render output (linear RGB, a = coverage), RGBA float, top row first. Right
   * after setScene()/updateScene() it waits for the first sample (see whenSamples).
   */
  async readHDR(options: { afterPost?: boolean } = {}): Promise<Float32Array> {
    if (this.scene && this.iteration === 0) await this.whenSamples(1);
    this.renderImage();
    if (!this.hdr) throw new VptError('invalid-scene', 'Nothing rendered yet: call setScene() and iterate first');
    const steps = options.afterPost ? this.radianceStepCount() : 0;
    const image = steps > 0 ? this.postChain.output(steps - 1).textures[0] : this.displayed!;
    return (await this.backend.readTexture(image)) as Float32Array;
  }

  /**
   * How many leading post steps keep linear radiance (PostStep.keepsRadiance, e.g. the
   * denoiser): readHDR({ afterPost: true }) returns the image after them, and an HDR export
   * made that way was processed by them. The last step writes the LDR image and never counts.
   */
  radianceStepCount(): number {
    return this.postChain.radianceStepCount();
  }

  /** The LDR image after the post chain, RGBA8, top row first (waits for the first sample like readHDR). */
  async readLDR(): Promise<Uint8Array> {
    if (this.scene && this.iteration === 0) await this.whenSamples(1);
    this.renderImage();
    if (!this.hdr) throw new VptError('invalid-scene', 'Nothing rendered yet: call setScene() and iterate first');
    return (await this.backend.readTexture(this.postChain.ldrTexture())) as Uint8Array;
  }

  /**
   * The sample of the most recent iteration alone (the renderer's frame buffer,
   * output `index`), RGBA float, top row first. For tests and debugging.
   */
  async readFrame(index = 0): Promise<Float32Array> {
    if (!this.frame || this.iteration === 0)
      throw new VptError('invalid-scene', 'Nothing rendered yet: call setScene() and iterate first');
    return (await this.backend.readTexture(this.frame.textures[index])) as Float32Array;
  }

  /**
   * An auxiliary texture of the renderer as its kernels see it (for tests and tools), read
   * back as floats; built first if the scene changed since the last iteration.
   */
  async readAuxiliaryTexture(name: string): Promise<Float32Array> {
    this.assertAlive();
    if (!this.scene) throw new VptError('invalid-scene', 'readAuxiliaryTexture() before setScene()');
    this.resources.syncAuxiliaryTextures();
    const aux = this.resources.auxTextures.get(name);
    if (!aux) throw new RangeError(`the renderer has no auxiliary texture "${name}" for this scene`);
    return (await this.backend.readTexture(aux.texture)) as Float32Array;
  }

  /**
   * The volume's gradient magnitude as the kernels see it (for tests and tools): |∇f| per
   * voxel in data units per spacing unit, x fastest (read back from the GPU's slice atlas),
   * and the largest value, which normalizes a 2D transfer function's gradient axis. Builds
   * the gradient volume if the scene had not needed it yet.
   */
  async readGradientVolume(): Promise<{ magnitudes: Float32Array; max: number }> {
    this.assertAlive();
    if (!this.scene) throw new VptError('invalid-scene', 'readGradientVolume() before setScene()');
    const g = this.resources.ensureGradient();
    const [atlas, max] = (await Promise.all([
      this.backend.readTexture(g.atlas.textures[0]),
      this.backend.readTexture(g.max.textures[0]),
    ])) as Float32Array[];
    const [nx, ny, nz] = this.scene.volume.dims;
    const magnitudes = new Float32Array(nx * ny * nz);
    for (let z = 0; z < nz; z++) {
      const ox = (z % g.layout.columns) * nx,
        oy = Math.floor(z / g.layout.columns) * ny;
      for (let y = 0; y < ny; y++) {
        magnitudes.set(
          atlas.subarray(ox + g.layout.width * (oy + y), ox + g.layout.width * (oy + y) + nx),
          nx * (y + ny * z),
        );
      }
    }
    return { magnitudes, max: max[0] };
  }

  /**
   * Live error estimate from the renderer's two half-accumulations (even and odd
   * iterations): for independent halves of equal size, the error of the full mean is
   * |A − B| / 2 per pixel in expectation. Returns the RMSE over RGB and the RMSE relative
   * to the image's mean, or null when the renderer keeps no halves or fewer than two
   * iterations ran.
   */
  async estimateError(): Promise<{ rmse: number; relativeRmse: number } | null> {
    const halves = this._renderer.halfAccumulations;
    if (!halves || !this.accum || this.iteration < 2) return null;
    const [a, b] = (await Promise.all(
      halves.map((i) => this.backend.readTexture(this.accum![0].textures[i])),
    )) as Float32Array[];
    let sq = 0,
      sum = 0,
      n = 0;
    for (let i = 0; i < a.length; i += 4) {
      for (let c = 0; c < 3; c++) {
        const d = (a[i + c] - b[i + c]) / 2;
        sq += d * d;
        sum += (a[i + c] + b[i + c]) / 2;
        n++;
      }
    }
    const rmse = Math.sqrt(sq / n);
    const mean = sum / n;
    return { rmse, relativeRmse: mean > 0 ? rmse / mean : 0 };
  }

  /** Start refining in the background, a time budget's worth of iterations per animation frame. */
  start(options: { frameBudgetMs?: number; maxIterations?: number } = {}): void {
    this.assertAlive();
    this.loop.start({ ...options, currentIterations: () => this.iteration });
  }

  stop(): void {
    this.loop.stop();
  }

  get running(): boolean {
    return this.loop.running;
  }

  dispose(): void {
    if (this.disposed) return;
    this.loop.stop();
    this.releaseGpuResources();
    this.backend.dispose();
    this.disposed = true;
  }

  // ——— internals ———

  private emit(): void {
    const s = this.stats;
    this.listeners.forEach((l) => l(s));
  }

  private assertAlive(): void {
    if (this.disposed) throw new VptError('disposed', 'This RenderContext was disposed');
  }

  private uniforms(scene: Scene, iteration = this.iteration): ArrayBuffer {
    const bricked = this.resources.bricked;
    return this.layout.pack({
      ...sceneUniformValues(
        scene,
        this.width,
        this.height,
        iteration,
        TF_RESOLUTION,
        this.resources.volumeMapping(scene),
        // Temporal reuse: each view continues the sample sequence where its history ended (TemporalReuse.sampleBase).
        this.sampleStart + (this.temporal?.sampleBase ?? 0),
      ),
      // The bricked sampler reads level 0's dims and the brick size from here (a streamed
      // scene's volume is a coarser stand-in); nothing else reads volumeDims when bricked.
      ...(bricked ? { volumeDims: [...bricked.geometry.levels[0].dims, bricked.geometry.brickSize] } : {}),
      ...this._renderer.paramValues(scene),
      ...(hasClip(scene.clip) ? clipUniformValues(scene.clip, scene.volume) : {}),
      ...(scene.channels ? this.resources.channelMapping(scene) : {}),
      ...(this.drawsLabels(scene)
        ? { labelScale: labelSupport().labelScaleOf(scene.labels!.volume, this.backend.capabilities) }
        : {}),
      ...(this.drawsSlicePlane(scene) ? slicePlaneUniformValues(scene.slicePlane!, scene.volume) : {}),
      ...(this.depthLimit ? { depthA: this.depthLimit.a, depthB: this.depthLimit.b } : {}),
    });
  }

  /** A 2D transfer function reads the gradient magnitude, and so does a renderer that asks for it. */
  private wantsGradient(scene: Scene): boolean {
    return this.resources.wantsGradient(scene);
  }

  /** A scene's slice plane is drawn only by a renderer that says so (Renderer.drawsSlicePlane). */
  private drawsSlicePlane(scene: Scene): boolean {
    return scene.slicePlane !== undefined && this._renderer.drawsSlicePlane === true;
  }

  /** A scene's labels are drawn only by a renderer that says so (Renderer.drawsLabels). */
  private drawsLabels(scene: Scene): boolean {
    return scene.labels !== undefined && this._renderer.drawsLabels === true;
  }

  /** Which shared chunks (and defines) the generate pass needs for this scene. */
  private chunkOptions(scene: Scene): Required<CommonChunkOptions> {
    const tf2d = !scene.channels && scene.transferFunction.dimensions === '2d';
    const plane = this.drawsSlicePlane(scene) ? slicePlaneFlags(scene.slicePlane!) : null;
    return {
      tf2d,
      gradient: this.wantsGradient(scene),
      hardwareFilter: this.resources.volumeUpload?.filter === 'linear',
      bricked: this.resources.bricked !== null,
      clip: hasClip(scene.clip),
      channels: scene.channels ? enabledChannels(scene.channels).length : 0,
      labels: this.drawsLabels(scene),
      slicePlane: plane !== null,
      slicePlaneNearest: plane?.nearest ?? false,
      slicePlaneTable: plane?.table ?? false,
    };
  }

  /**
   * The renderer's variant for the current scene: its key and, built only when asked, the
   * descriptors of its three passes. `auxBindings` are the auxiliary textures the generate
   * pass binds, in order; `writeGuides` whether it writes the denoiser's guides.
   */
  private variantOf(auxBindings: { name: string; dimension: '2d' | '3d' }[], writeGuides: boolean) {
    const r = this._renderer;
    const chunks = this.chunkOptions(this.scene!);
    // VPT_TF_2D / VPT_GRADIENT let a kernel branch at compile time on what the scene binds.
    const features = {
      ...r.features(this.scene!),
      VPT_TF_2D: chunks.tf2d,
      VPT_GRADIENT: chunks.gradient,
      VPT_GUIDES: writeGuides,
      VPT_CLIP: chunks.clip,
      VPT_DEPTH_LIMIT: this.depthLimit !== null,
      // The number of drawn channels of a channel scene (scene/channels.ts), 0 for a scalar one.
      VPT_CHANNELS: chunks.channels,
      VPT_SLICE_PLANE: chunks.slicePlane,
      // A label volume drawn by the renderer (scene/labels.ts).
      VPT_LABELS: chunks.labels,
    };
    const frameFormats = writeGuides ? [...r.frameFormats, ...GUIDE_FRAME_FORMATS] : r.frameFormats;
    const key = `${r.name}|${JSON.stringify(features)}|${chunks.slicePlaneNearest ? 'plane nearest|' : ''}${auxBindings.map((b) => b.name).join(',')}|${chunks.hardwareFilter ? 'filtered' : 'exact'}${chunks.bricked ? '|bricked' : ''}`;
    const descriptors = () => {
      // VPT_CLIP, VPT_CHANNELS and VPT_SLICE_PLANE cut the kernels' #if lines but become backend
      // defines only when set, so a variant without them is today's byte for byte.
      const defines = Object.fromEntries(Object.entries(features).filter(([k, v]) => v || !OPTIONAL_DEFINES.has(k)));
      const gradientBindings = chunks.gradient
        ? [
            { name: 'gradientMagnitude', dimension: '2d' as const },
            { name: 'gradientMax', dimension: '2d' as const },
          ]
        : [];
      // The clip uniforms, the channels', the slice plane's, then the depth limit's, come last and only in variants that use them:
      // a layout without either is unchanged.
      const layout = new UniformLayout('Params', [
        ...SCENE_UNIFORM_FIELDS,
        ...r.paramFields,
        ...(chunks.clip ? CLIP_UNIFORM_FIELDS : []),
        ...(chunks.channels ? CHANNEL_UNIFORM_FIELDS : []),
        ...(chunks.labels ? LABEL_UNIFORM_FIELDS : []),
        ...(chunks.slicePlane ? SLICE_PLANE_UNIFORM_FIELDS : []),
        ...(this.depthLimit ? DEPTH_LIMIT_FIELDS : []),
      ]);
      // The volume/TF chunks read the `volume` and `transferFunction` (and gradient) textures,
      // which only the generate pass binds; integrate and render get the texture-free chunks.
      const common = commonChunks(chunks);
      const generateChunks = writeGuides
        ? { glsl: common.glsl + GUIDES.glsl, wgsl: common.wgsl + GUIDES.wgsl }
        : common;
      const mk = (
        stage: 'generate' | 'integrate' | 'render',
        textures: PassDescriptor['textures'],
        outputs: typeof r.frameFormats,
      ): PassDescriptor => ({
        label: `${r.name}.${stage}`,
        // Kernels mark variants with #if lines on their feature flags; one preprocessor cuts both languages.
        glsl: (stage === 'generate' ? generateChunks : PASS_CHUNKS).glsl + preprocess(r.kernels[stage].glsl, features),
        wgsl: (stage === 'generate' ? generateChunks : PASS_CHUNKS).wgsl + preprocess(r.kernels[stage].wgsl, features),
        uniforms: layout,
        textures,
        outputs,
        defines,
      });
      const frameTex = r.frameFormats.map((_, i) => ({ name: `frame${i}`, dimension: '2d' as const }));
      const accTex = r.accumulationFormats.map((_, i) => ({ name: `accum${i}`, dimension: '2d' as const }));
      return {
        layout,
        generate: mk(
          'generate',
          [
            { name: 'volume', dimension: '3d', ...(chunks.hardwareFilter ? { filter: 'linear' as const } : {}) },
            { name: 'transferFunction', dimension: '2d' },
            ...(chunks.bricked
              ? [
                  { name: 'pageTable', dimension: '3d' as const },
                  { name: 'brickLevels', dimension: '2d' as const },
                ]
              : []),
            ...gradientBindings,
            ...auxBindings,
            ...(this.depthLimit ? [{ name: 'meshDepth', dimension: '2d' as const }] : []),
          ],
          frameFormats,
        ),
        integrate: mk('integrate', [...frameTex, ...accTex], r.accumulationFormats),
        // A channel variant's render pass also reads the channels' transfer functions (MIP colours its
        // per-channel maxima there).
        render: mk(
          'render',
          [
            ...accTex,
            ...(chunks.channels ? [{ name: 'transferFunction', dimension: '2d' as const }] : []),
            // A label variant's render pass reads the label table (MIP colours its label there).
            ...(chunks.labels ? [{ name: 'labelTable', dimension: '2d' as const }] : []),
          ],
          ['rgba32float'],
        ),
      };
    };
    return { key, frameFormats, descriptors };
  }

  /**
   * Compile what the next iteration and image need (the auxiliary passes, the renderer's
   * variant, the post steps) all at once, without blocking (GpuBackend.compileAhead), so the
   * driver overlaps them; iterate() then finds them compiled. The renderIterations, whenSamples
   * and the progressive loop call it; images are the same, only the wait moves.
   */
  async precompile(): Promise<void> {
    this.assertAlive();
    if (!this.scene || this.backend.isLost) return;
    const scene = this.scene;
    if (this.passes && this.precompiledFor === scene) return;
    this.precompiledFor = scene;
    const specs = this.resources.auxiliarySpecs();
    const auxBindings = specs.filter((a) => a.bind !== false).map((a) => ({ name: a.name, dimension: a.dimension }));
    const variant = this.variantOf(auxBindings, this.guidesActive && this._renderer.writesGuides === true);
    const descs: PassDescriptor[] = [
      ...this.resources.auxiliaryPassDescriptors(specs),
      ...(this.passes && variant.key === this.variantKey
        ? []
        : (({ generate, integrate, render }) => [generate, integrate, render])(variant.descriptors())),
      ...this.postChain.pendingPassDescriptors(),
    ];
    if (descs.length) await this.backend.compileAhead(descs);
  }

  /** Compile the renderer's variant for the current scene and allocate its targets. */
  private prepare(): void {
    const r = this._renderer;
    const writeGuides = this.guidesActive && r.writesGuides === true;
    if (this.frame && this.frameHasGuides !== writeGuides) this.destroyRendererTargets();
    if (r.version !== this.rendererVersion) {
      this.rendererVersion = r.version;
      this.temporal?.invalidate();
      this.reset();
    }
    this.resources.syncGradient();
    this.resources.syncAuxiliaryTextures();
    const auxBindings = [...this.resources.auxTextures]
      .filter(([, a]) => a.bind)
      .map(([name, a]) => ({ name, dimension: a.dimension }));
    const variant = this.variantOf(auxBindings, writeGuides);
    const frameFormats = variant.frameFormats;
    if (!this.passes || variant.key !== this.variantKey) {
      const d = variant.descriptors();
      this.layout = d.layout;
      this.passes = {
        generate: this.backend.createPass(d.generate),
        integrate: this.backend.createPass(d.integrate),
        render: this.backend.createPass(d.render),
      };
      this.variantKey = variant.key;
    }
    if (!this.frame) {
      this.frame = this.backend.createRenderTarget(this.width, this.height, frameFormats, `${r.name} frame`);
      this.frameHasGuides = writeGuides;
      this.accum = [
        this.backend.createRenderTarget(this.width, this.height, r.accumulationFormats, `${r.name} accumulation A`),
        this.backend.createRenderTarget(this.width, this.height, r.accumulationFormats, `${r.name} accumulation B`),
      ];
      this.hdr = this.backend.createRenderTarget(this.width, this.height, ['rgba32float'], 'HDR render');
    }
    if (this.guidesActive && !this.guides) {
      this.guides = new GuideBuffers(this.backend, this.width, this.height);
    } else if (!this.guidesActive && this.guides) {
      this.guides.destroy();
      this.guides = null;
    }
  }

  private destroyRendererTargets(): void {
    if (this.frame) this.backend.destroyRenderTarget(this.frame);
    this.accum?.forEach((t) => this.backend.destroyRenderTarget(t));
    if (this.hdr) this.backend.destroyRenderTarget(this.hdr);
    this.guides?.destroy();
    this.frame = null;
    this.accum = null;
    this.hdr = null;
    this.guides = null;
    this.displayed = null;
    this.hdrRenderedAt = -1;
  }

  private releaseGpuResources(): void {
    this.destroyRendererTargets();
    this.temporal?.destroy();
    this.postChain.destroy();
    this.resources.release();
  }

  /** After a context/device loss: every GPU object is gone; rebuild from the retained scene and continue. */
  private restore(): void {
    if (this.disposed) return;
    // The old handles belong to the lost context: forget them without calling destroy.
    this.frame = null;
    this.accum = null;
    this.hdr = null;
    this.guides = null;
    this.displayed = null;
    this.temporal?.forget();
    this.postChain.forget();
    this.presentPass = null;
    this.resources.forget();
    this.passes = null;
    this.variantKey = '';
    this.presentedVersion = -1;
    this.backend.resizeCanvas(this.width, this.height);
    if (this.scene) this.resources.sync();
    this.reset();
    this.loop.resume();
  }
}
