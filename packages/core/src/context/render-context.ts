import { VptError } from '../errors.js';
import { createBackend } from '../gpu/create-backend.js';
import type { BackendPreference, GpuBackend, GpuPass, GpuTexture, RenderTarget } from '../gpu/backend.js';
import type { PostStep } from '../post-step.js';
import type { Renderer } from '../renderer.js';
import type { Scene } from '../scene/scene.js';
import { validateScene } from '../scene/scene.js';
import { TF_RESOLUTION } from '../scene/transfer-function.js';
import { voxelCount } from '../scene/volume.js';
import { downsampleVolume, fitFactors } from '../scene/downsample.js';
import { BYTES_PER_TEXEL } from '../gpu/backend.js';
import type { VolumeSampling } from '../gpu/volume-format.js';
import { commonChunks, PASS_CHUNKS, type CommonChunkOptions } from '../shaders/common.js';
import { preprocess } from '../shaders/preprocess.js';
import { validateSceneForDevice } from '../validation/device.js';
import { SCENE_UNIFORM_FIELDS, sceneUniformValues } from '../shaders/scene-uniforms.js';
import { CLIP_UNIFORM_FIELDS, clipUniformValues, hasClip } from '../scene/clip.js';
import { sliceAtlasLayout } from '../shaders/slice-atlas.js';
import { UniformLayout } from '../uniforms/layout.js';
import { GUIDES } from '../shaders/guides.js';
import { GUIDE_FRAME_FORMATS, GUIDE_TEXTURE_NAMES, GuideBuffers } from './guide-buffers.js';
import { PRESENT_PASS } from './present-pass.js';
import { ProgressiveLoop } from './progressive-loop.js';
import { SceneResources, sameVoxels, type BrickPlan } from './scene-resources.js';
import type { BrickingStats } from '../bricking/bricked-volume.js';
import type { MultiscaleSource } from '../bricking/source.js';

export interface RenderContextOptions {
  backend?: BackendPreference;
  canvas?: HTMLCanvasElement | OffscreenCanvas;
  /** Render resolution in pixels (the canvas drawing buffer is resized to it). */
  width: number;
  height: number;
  renderer: Renderer;
  post?: PostStep[];
  /**
   * Volume sampling when the scene does not say (Scene.sampling): 'fast' (default; compact
   * texture, one hardware-filtered fetch) or 'exact' (r32float, manual trilinear).
   */
  sampling?: VolumeSampling;
  /** float32 volumes may be stored as r16float on the fast path (half the memory, ~3 significant digits). Default false. */
  allowHalfFloatVolumes?: boolean;
  /**
   * GPU memory budget in bytes for everything the context allocates. A volume that does not
   * fit (with its gradient volume, the render targets and the transfer function) is
   * downsampled to the largest resolution that does, with a warning (onWarning). Default:
   * WebGPU's maxBufferSize clamped to [1 GiB, 4 GiB]; 1 GiB where the device reports nothing
   * (WebGL 2).
   */
  maxGpuBytes?: number;
  /**
   * Volumes larger than one texture or the budget: 'off' (default) downsamples them to fit;
   * 'auto' holds them as bricks in an atlas with a page table instead (bricking/; a scene
   * with a 2D transfer function, or a renderer that needs the gradient volume, is still
   * downsampled); 'force' bricks every volume (tests, benchmarks).
   */
  bricking?: 'off' | 'auto' | 'force';
  /** Data voxels per brick side, a power of two (default 32). */
  brickSize?: number;
  /** Bricks uploaded per frame at most (default 16); each upload restarts accumulation. */
  brickUploadsPerFrame?: number;
  /**
   * Level of detail for bricked volumes: load no brick finer than the render's pixels need
   * (a voxel of the next coarser level projects to at most one pixel). Default false: every
   * visible brick at the finest level the atlas holds.
   */
  brickLod?: boolean;
}

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

/** Something the context changed to make a scene fit or could not load, reported through onWarning (and console.warn without a listener). */
export type RenderWarning = VolumeDownsampledWarning | BrickLoadWarning;

/** A brick of a streamed volume (setVolumeSource) could not be read; a coarser level keeps serving its region. */
export interface BrickLoadWarning {
  code: 'brick-load-failed';
  message: string;
}

export interface VolumeDownsampledWarning {
  code: 'volume-downsampled';
  message: string;
  /** Integer box-average factors per axis. */
  factors: [number, number, number];
  from: [number, number, number];
  to: [number, number, number];
}

/** The default budget where the device reports nothing about its memory. */
export const DEFAULT_GPU_BYTES = 1024 ** 3;
const MAX_DEFAULT_GPU_BYTES = 4 * 1024 ** 3;

export interface RenderStats {
  /** Iterations accumulated since the last reset. */
  iterations: number;
  /** Samples per pixel (one path per pixel per iteration). */
  samplesPerPixel: number;
  /** Mean wall-clock ms per iteration over the last measured batch (GPU synchronised). */
  msPerIteration: number;
  /** GPU memory held now. */
  gpuBytes: GpuBytes;
  /** The brick cache's state when the volume is bricked, else null. */
  bricking: BrickingStats | null;
  /** The renderer's own choices for the current scene (Renderer.stats; empty when it has none). */
  renderer: Record<string, string>;
}

type RendererPasses = { generate: GpuPass; integrate: GpuPass; render: GpuPass };

/**
 * Owns the backend, the scene's GPU resources, the renderer's buffers and the post
 * chain, and runs the progressive loop: generate → integrate per iteration, then
 * render → post → present. Resets accumulation whenever the image would change.
 */
export class RenderContext {
  readonly backend: GpuBackend;
  private _renderer: Renderer;
  private _post: PostStep[];
  private scene: Scene | null = null; // as rendered: its volume may be a downsampled copy (fitScene)
  private input: Scene | null = null; // as given to setScene
  private width: number;
  private height: number;
  private layout!: UniformLayout;
  private passes: RendererPasses | null = null;
  private postPasses: GpuPass[] = [];
  private presentPass: GpuPass | null = null;

  // Volume, transfer function, gradient and auxiliary textures, with their lifetimes.
  private readonly resources: SceneResources;
  // The last budget fit: a scene volume → the volume actually uploaded (itself when it fits).
  private fitted: { source: Scene['volume']; key: string; volume: Scene['volume']; bricks: BrickPlan | null } | null =
    null;
  private readonly bricking: 'off' | 'auto' | 'force';
  private readonly brickSize: number;
  private readonly brickUploadsPerFrame: number;
  private readonly brickLod: boolean;
  // Volumes backed by a multiscale source (setVolumeSource): the scene's volume is a stand-in.
  private readonly volumeSources = new WeakMap<Scene['volume'], MultiscaleSource>();
  private readonly sampling: VolumeSampling;
  readonly maxGpuBytes: number;
  private readonly warningListeners = new Set<(w: RenderWarning) => void>();
  private frame: RenderTarget | null = null;
  private accum: [RenderTarget, RenderTarget] | null = null;
  private hdr: RenderTarget | null = null;
  private postTargets: RenderTarget[] = [];
  // Ping-pong targets for the draws of a repeated post step before its last one.
  private postScratch: RenderTarget[] = [];
  // Accumulated denoiser guides, while a post step uses them; the frame target then holds the guide frames too.
  private guides: GuideBuffers | null = null;
  private frameHasGuides = false;
  // Whether this estimate accumulates guides: decided at each reset (guides are means over every
  // iteration since it), so removing the denoiser keeps the samples and adding it starts over.
  private guidesActive = false;

  private iteration = 0;
  private rendererVersion = -1;
  private variantKey = '';
  private hdrIteration = -1; // iteration count the HDR/LDR images were last rendered at
  private imageVersion = 0; // bumped whenever renderImage() produced a new LDR image
  private presentedVersion = -1;
  private postKey = ''; // post-chain parameters the current LDR image was made with
  private msPerIteration = 0;
  private disposed = false;
  private readonly loop: ProgressiveLoop;
  private readonly listeners = new Set<(stats: RenderStats) => void>();

  private constructor(backend: GpuBackend, opts: RenderContextOptions) {
    this.backend = backend;
    this._renderer = opts.renderer;
    this._post = opts.post ?? [];
    this.sampling = opts.sampling ?? 'fast';
    if (this.sampling !== 'fast' && this.sampling !== 'exact')
      throw new VptError('invalid-scene', `sampling must be 'fast' or 'exact', got ${JSON.stringify(opts.sampling)}`);
    this.resources = new SceneResources(backend, () => ({ scene: this.scene, renderer: this._renderer }), {
      sampling: this.sampling,
      allowHalfFloat: opts.allowHalfFloatVolumes === true,
    });
    if (opts.maxGpuBytes !== undefined && !(opts.maxGpuBytes > 0))
      throw new VptError('invalid-scene', `maxGpuBytes must be a positive number of bytes, got ${opts.maxGpuBytes}`);
    this.maxGpuBytes = opts.maxGpuBytes ?? defaultGpuBytes(backend);
    this.bricking = opts.bricking ?? 'off';
    if (!['off', 'auto', 'force'].includes(this.bricking))
      throw new VptError(
        'invalid-scene',
        `bricking must be 'off', 'auto' or 'force', got ${JSON.stringify(opts.bricking)}`,
      );
    this.brickSize = opts.brickSize ?? 32;
    if (!Number.isInteger(Math.log2(this.brickSize)) || this.brickSize < 8 || this.brickSize > 256)
      throw new VptError('invalid-scene', `brickSize must be a power of two from 8 to 256, got ${opts.brickSize}`);
    this.brickUploadsPerFrame = opts.brickUploadsPerFrame ?? 16;
    this.brickLod = opts.brickLod === true;
    if (!Number.isInteger(this.brickUploadsPerFrame) || this.brickUploadsPerFrame < 1)
      throw new VptError(
        'invalid-scene',
        `brickUploadsPerFrame must be a positive integer, got ${opts.brickUploadsPerFrame}`,
      );
    checkSize(opts.width, opts.height, backend);
    this.width = opts.width;
    this.height = opts.height;
    this.backend.resizeCanvas(this.width, this.height);
    this.loop = new ProgressiveLoop({
      step: (n) => this.iterate(n),
      finishFrame: () => this.present(),
      sync: () => this.backend.finish(),
      // Bricks that arrive after convergence still upload; the reset makes the loop iterate again.
      idle: () => {
        if (this.updateBricks()) this.reset();
      },
      onStats: (ms) => {
        this.msPerIteration = ms;
        this.emit();
      },
    });
    backend.onLost(() => this.loop.pause());
    backend.onRestored(() => this.restore());
  }

  static async create(opts: RenderContextOptions): Promise<RenderContext> {
    const backend = await createBackend({ backend: opts.backend ?? 'auto', canvas: opts.canvas });
    try {
      return new RenderContext(backend, opts);
    } catch (e) {
      backend.dispose();
      throw e;
    }
  }

  get renderer(): Renderer {
    return this._renderer;
  }
  get post(): readonly PostStep[] {
    return this._post;
  }
  get size(): { width: number; height: number } {
    return { width: this.width, height: this.height };
  }

  get stats(): RenderStats {
    return {
      iterations: this.iteration,
      samplesPerPixel: this.iteration,
      msPerIteration: this.msPerIteration,
      gpuBytes: this.gpuBytes(),
      bricking: this.resources.bricked?.stats() ?? null,
      renderer: this._renderer.stats?.() ?? {},
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
    for (const t of [...this.postTargets, ...this.postScratch, ...(this.guides?.targets ?? [])]) targets += target(t);
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
    const scene = this.fitScene(input);
    const [nx, ny, nz] = scene.volume.dims;
    if (this.wantsGradient(scene)) {
      const atlas = sliceAtlasLayout(scene.volume.dims);
      const max2D = this.backend.limits.maxTextureDimension2D;
      if (atlas.width > max2D || atlas.height > max2D) {
        throw new VptError(
          'limit-exceeded',
          `The gradient volume of a [${nx}, ${ny}, ${nz}] volume (needed by the 2D transfer function or the renderer) needs a ${atlas.width} x ${atlas.height} slice atlas; this device's 2D texture limit is ${max2D} (maxTextureDimension2D)`,
        );
      }
    }
    const previous = { scene: this.scene, plan: this.resources.brickPlanNow() };
    this.scene = scene;
    this.resources.setBrickPlan(this.fitted?.bricks ?? null);
    try {
      this.resources.sync();
    } catch (e) {
      // A bricked volume that cannot be held (VptError 'limit-exceeded'): keep the previous scene.
      this.scene = previous.scene;
      this.resources.setBrickPlan(previous.plan);
      this.fitted = null;
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
    const l = source?.levels;
    const ok =
      Array.isArray(l) &&
      l.length > 0 &&
      l.every(
        (v) =>
          [v.dims, v.spacing, v.origin].every((a) => Array.isArray(a) && a.length === 3 && a.every(Number.isFinite)) &&
          v.dims.every((d) => Number.isInteger(d) && d >= 1) &&
          v.spacing.every((x) => x > 0),
      ) &&
      typeof source.readRegion === 'function';
    if (!ok)
      throw new VptError(
        'invalid-scene',
        'setVolumeSource: the source needs levels (level 0 finest) with positive integer dims, positive spacing, an origin each, and readRegion()',
      );
    if (source.type !== standIn.type)
      throw new VptError(
        'invalid-scene',
        `setVolumeSource: the stand-in volume is ${standIn.type}, the source ${source.type}; they must match`,
      );
    this.volumeSources.set(standIn, source);
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
    const pixels = this.width * this.height;
    const targetBytes =
      pixels *
      16 *
      (this._renderer.frameFormats.length + 2 * this._renderer.accumulationFormats.length + 1 + this._post.length);
    return this.maxGpuBytes - targetBytes - TF_RESOLUTION * 16 * 256;
  }

  /**
   * The scene with a volume that fits the device: each side within the 3D texture limit and
   * the whole within maxGpuBytes (volume + gradient at this scene's sampling, plus the render
   * targets and the TF); otherwise downsampled by integer box averages (scene/downsample.ts)
   * with a warning naming the factors. The fit is kept per source volume, so setting the same
   * volume again neither recomputes nor warns again.
   */
  private fitScene(scene: Scene): Scene {
    const sampling = scene.sampling ?? this.sampling;
    const gradient = this.wantsGradient(scene);
    const key = `${sampling}|${gradient}|${this.width}x${this.height}`;
    const f = this.fitted;
    if (f && f.key === key && f.source === scene.volume) {
      return f.volume === scene.volume ? scene : { ...scene, volume: f.volume };
    }
    if (f && f.key === key && f.bricks && !f.bricks.source && sameVoxels(f.source, scene.volume)) {
      this.fitted = { ...f, source: scene.volume, volume: scene.volume };
      return scene;
    }
    if (f && f.key === key && sameVoxels(f.source, scene.volume) && f.volume !== f.source) {
      // The same voxels with another value range: keep the downsampled copy, take the new range.
      const volume = { ...f.volume, valueRange: scene.volume.valueRange };
      this.fitted = { source: scene.volume, key, volume, bricks: null };
      return { ...scene, volume };
    }
    const upload = this.resources.planUpload(scene.volume, sampling);
    const perVoxel = upload.bytesPerVoxel + (gradient ? (sampling === 'exact' ? 4 : 2) : 0);
    const budget = this.volumeBudgetBytes;
    const max3D = this.backend.limits.maxTextureDimension3D;
    const from = [...scene.volume.dims] as [number, number, number];
    const factors = fitFactors(from, perVoxel, budget, max3D);
    if (!factors) {
      throw new VptError(
        'limit-exceeded',
        `maxGpuBytes (${this.maxGpuBytes} bytes) leaves no room for a volume next to the ${this.width} x ${this.height} render targets`,
      );
    }
    // Bricks instead of a downsampled copy: the full data stays available to the view.
    const brickable = scene.transferFunction.dimensions !== '2d' && !gradient;
    const source = this.volumeSources.get(scene.volume);
    if (
      brickable &&
      (source || this.bricking === 'force' || (this.bricking === 'auto' && factors.some((f) => f > 1)))
    ) {
      const bricks: BrickPlan = {
        capacityBytes: budget,
        brickSize: this.brickSize,
        uploadsPerFrame: this.brickUploadsPerFrame,
        lod: this.brickLod,
        onFailure: (message) => this.warn({ code: 'brick-load-failed', message }),
        ...(source ? { source } : {}),
      };
      const volume = source ? standInWithLevel0Box(scene.volume, source) : scene.volume;
      this.fitted = { source: scene.volume, key, volume, bricks };
      return volume === scene.volume ? scene : { ...scene, volume };
    }
    let volume = scene.volume;
    if (factors.some((f) => f > 1)) {
      volume = downsampleVolume(scene.volume, factors);
      const over3D = from.some((d) => d > max3D);
      const why = over3D
        ? `a side exceeds this device's 3D texture limit of ${max3D} (maxTextureDimension3D)`
        : `${voxelCount(from)} voxels x ${perVoxel} bytes exceed the GPU memory budget of ${this.maxGpuBytes} bytes (maxGpuBytes)`;
      this.warn({
        code: 'volume-downsampled',
        factors,
        from,
        to: [...volume.dims] as [number, number, number],
        message: `Volume [${from.join(', ')}] downsampled by [${factors.join(', ')}] to [${volume.dims.join(', ')}]: ${why}`,
      });
    }
    this.fitted = { source: scene.volume, key, volume, bricks: null };
    return volume === scene.volume ? scene : { ...scene, volume };
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
    this._renderer = renderer;
    this.passes = null;
    this.destroyRendererTargets();
    this.reset();
  }

  setPost(steps: PostStep[]): void {
    this._post = steps;
    this.postPasses = [];
    this.hdrIteration = -1;
    // Guides are means over every iteration since the reset: a chain that starts using them starts over.
    if (!this.guidesActive && this.guidesWanted()) this.reset();
  }

  setSize(width: number, height: number): void {
    checkSize(width, height, this.backend);
    if (width === this.width && height === this.height) return;
    this.width = width;
    this.height = height;
    this.backend.resizeCanvas(width, height);
    this.destroyRendererTargets();
    this.destroyPostTargets();
    this.reset();
  }

  /** Drop accumulated samples: the next iteration starts a new estimate. */
  reset(): void {
    this.iteration = 0;
    this.hdrIteration = -1;
    this.guidesActive = this.guidesWanted();
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
    const postKey = JSON.stringify(this._post.map((s) => [s.name, s.uniformValues(), s.defines?.()]));
    if (
      this.hdrIteration === this.iteration &&
      this.postKey === postKey &&
      this.postPasses.length === this._post.length
    )
      return;
    this.postKey = postKey;
    this.prepare();
    const uniforms = this.uniforms(this.scene, this.iteration - 1);
    const accTextures: Record<string, GpuTexture> = {};
    this.accum![0].textures.forEach((t, i) => {
      accTextures[`accum${i}`] = t;
    });
    this.backend.draw(this.passes!.render, { uniforms, textures: accTextures, target: this.hdr! });
    this.preparePost();
    let input = this.hdr!.textures[0];
    this._post.forEach((step, i) => {
      const pass = this.postPasses[i];
      const guides = step.usesGuides && this.guides ? this.guides.textures() : {};
      const draws = postDraws(step);
      for (let d = 0; d < draws; d++) {
        // Draws before the last alternate between the two scratch targets; the last writes the step's own.
        const target = d === draws - 1 ? this.postTargets[i] : this.scratchTarget(d % 2);
        this.backend.draw(pass, {
          uniforms: step.uniforms.pack(step.uniformValues(d)),
          textures: { ...guides, inputImage: input },
          target,
        });
        input = target.textures[0];
      }
    });
    this.hdrIteration = this.iteration;
    this.imageVersion++;
  }

  /** Draw the current LDR image to the canvas. */
  present(): void {
    if (!this.scene || this.backend.isLost || this.iteration === 0) return;
    this.renderImage();
    if (this.presentedVersion === this.imageVersion) return;
    this.presentPass ??= this.backend.createPass(PRESENT_PASS);
    this.backend.draw(this.presentPass, {
      uniforms: PRESENT_PASS.uniforms.pack({ pad: 0 }),
      textures: { inputImage: this.ldrTexture() },
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
      if (!this.loop.running && !this.backend.isLost) this.iterate(n - this.iteration);
      else await new Promise((resolve) => setTimeout(resolve, 10));
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
    const image = steps > 0 ? this.postTargets[steps - 1] : this.hdr;
    return (await this.backend.readTexture(image.textures[0])) as Float32Array;
  }

  /**
   * How many leading post steps keep linear radiance (PostStep.keepsRadiance, e.g. the
   * denoiser): readHDR({ afterPost: true }) returns the image after them, and an HDR export
   * made that way was processed by them. The last step writes the LDR image and never counts.
   */
  radianceStepCount(): number {
    let n = 0;
    while (n < this._post.length - 1 && this._post[n].keepsRadiance) n++;
    return n;
  }

  /** The LDR image after the post chain, RGBA8, top row first (waits for the first sample like readHDR). */
  async readLDR(): Promise<Uint8Array> {
    if (this.scene && this.iteration === 0) await this.whenSamples(1);
    this.renderImage();
    if (!this.hdr) throw new VptError('invalid-scene', 'Nothing rendered yet: call setScene() and iterate first');
    return (await this.backend.readTexture(this.ldrTexture())) as Uint8Array;
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
      ),
      // The bricked sampler reads level 0's dims and the brick size from here (a streamed
      // scene's volume is a coarser stand-in); nothing else reads volumeDims when bricked.
      ...(bricked ? { volumeDims: [...bricked.geometry.levels[0].dims, bricked.geometry.brickSize] } : {}),
      ...this._renderer.paramValues(scene),
      ...(hasClip(scene.clip) ? clipUniformValues(scene.clip, scene.volume) : {}),
    });
  }

  /** A 2D transfer function reads the gradient magnitude, and so does a renderer that asks for it. */
  private wantsGradient(scene: Scene): boolean {
    return this.resources.wantsGradient(scene);
  }

  /** Which shared chunks (and defines) the generate pass needs for this scene. */
  private chunkOptions(scene: Scene): Required<CommonChunkOptions> {
    const tf2d = scene.transferFunction.dimensions === '2d';
    return {
      tf2d,
      gradient: this.wantsGradient(scene),
      hardwareFilter: this.resources.volumeUpload?.filter === 'linear',
      bricked: this.resources.bricked !== null,
      clip: hasClip(scene.clip),
    };
  }

  /** Compile the renderer's variant for the current scene and allocate its targets. */
  private prepare(): void {
    const r = this._renderer;
    const chunks = this.chunkOptions(this.scene!);
    // VPT_TF_2D / VPT_GRADIENT let a kernel branch at compile time on what the scene binds.
    const writeGuides = this.guidesActive && r.writesGuides === true;
    const features = {
      ...r.features(this.scene!),
      VPT_TF_2D: chunks.tf2d,
      VPT_GRADIENT: chunks.gradient,
      VPT_GUIDES: writeGuides,
      VPT_CLIP: chunks.clip,
    };
    // VPT_CLIP cuts the kernels' #if lines but becomes a backend define only when set, so an
    // unclipped variant's program is today's byte for byte.
    const { VPT_CLIP: clipFlag, ...unclipped } = features;
    const defines = clipFlag ? features : unclipped;
    const frameFormats = writeGuides ? [...r.frameFormats, ...GUIDE_FRAME_FORMATS] : r.frameFormats;
    if (this.frame && this.frameHasGuides !== writeGuides) this.destroyRendererTargets();
    if (r.version !== this.rendererVersion) {
      this.rendererVersion = r.version;
      this.reset();
    }
    this.resources.syncGradient();
    this.resources.syncAuxiliaryTextures();
    const auxBindings = [...this.resources.auxTextures]
      .filter(([, a]) => a.bind)
      .map(([name, a]) => ({ name, dimension: a.dimension }));
    const gradientBindings = chunks.gradient
      ? [
          { name: 'gradientMagnitude', dimension: '2d' as const },
          { name: 'gradientMax', dimension: '2d' as const },
        ]
      : [];
    const key = `${r.name}|${JSON.stringify(features)}|${auxBindings.map((b) => b.name).join(',')}|${chunks.hardwareFilter ? 'filtered' : 'exact'}${chunks.bricked ? '|bricked' : ''}`;
    if (!this.passes || key !== this.variantKey) {
      // The clip uniforms come last, and only in a clipped variant: an unclipped layout is unchanged.
      this.layout = new UniformLayout('Params', [
        ...SCENE_UNIFORM_FIELDS,
        ...r.paramFields,
        ...(chunks.clip ? CLIP_UNIFORM_FIELDS : []),
      ]);
      // The volume/TF chunks read the `volume` and `transferFunction` (and gradient) textures,
      // which only the generate pass binds; integrate and render get the texture-free chunks.
      const common = commonChunks(chunks);
      const generateChunks = writeGuides
        ? { glsl: common.glsl + GUIDES.glsl, wgsl: common.wgsl + GUIDES.wgsl }
        : common;
      const mk = (
        stage: 'generate' | 'integrate' | 'render',
        textures: { name: string; dimension: '2d' | '3d' }[],
        outputs: typeof r.frameFormats,
      ) =>
        this.backend.createPass({
          label: `${r.name}.${stage}`,
          // Kernels mark variants with #if lines on their feature flags; one preprocessor cuts both languages.
          glsl:
            (stage === 'generate' ? generateChunks : PASS_CHUNKS).glsl + preprocess(r.kernels[stage].glsl, features),
          wgsl:
            (stage === 'generate' ? generateChunks : PASS_CHUNKS).wgsl + preprocess(r.kernels[stage].wgsl, features),
          uniforms: this.layout,
          textures,
          outputs,
          defines,
        });
      const frameTex = r.frameFormats.map((_, i) => ({ name: `frame${i}`, dimension: '2d' as const }));
      const accTex = r.accumulationFormats.map((_, i) => ({ name: `accum${i}`, dimension: '2d' as const }));
      this.passes = {
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
          ],
          frameFormats,
        ),
        integrate: mk('integrate', [...frameTex, ...accTex], r.accumulationFormats),
        render: mk('render', accTex, ['rgba32float']),
      };
      this.variantKey = key;
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

  /** Some post step reads the denoiser guides. */
  private guidesWanted(): boolean {
    return this._post.some((s) => s.usesGuides === true);
  }

  /** Scratch target k (0 or 1) for the non-final draws of repeated post steps, made on first use. */
  private scratchTarget(k: number): RenderTarget {
    while (this.postScratch.length <= k)
      this.postScratch.push(
        this.backend.createRenderTarget(
          this.width,
          this.height,
          ['rgba32float'],
          `post scratch ${this.postScratch.length}`,
        ),
      );
    return this.postScratch[k];
  }

  private preparePost(): void {
    if (this.postPasses.length !== this._post.length || this.postTargets.length !== this._post.length) {
      this.destroyPostTargets();
      this.postPasses = this._post.map((step, i) =>
        this.backend.createPass({
          label: `post.${step.name}`,
          glsl: step.glsl,
          wgsl: step.wgsl,
          uniforms: step.uniforms,
          textures: [
            { name: 'inputImage', dimension: '2d' },
            ...(step.usesGuides ? GUIDE_TEXTURE_NAMES.map((name) => ({ name, dimension: '2d' as const })) : []),
          ],
          outputs: [i === this._post.length - 1 ? 'rgba8unorm' : 'rgba32float'],
          defines: step.defines?.() ?? {},
        }),
      );
      this.postTargets = this._post.map((_, i) =>
        this.backend.createRenderTarget(
          this.width,
          this.height,
          [i === this._post.length - 1 ? 'rgba8unorm' : 'rgba32float'],
          `post ${i}`,
        ),
      );
    }
  }

  private ldrTexture(): GpuTexture {
    if (this._post.length === 0) {
      throw new VptError(
        'invalid-scene',
        'The post chain is empty: add at least one step (e.g. sRGB encoding) to get an LDR image',
      );
    }
    return this.postTargets[this.postTargets.length - 1].textures[0];
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
  }

  private destroyPostTargets(): void {
    [...this.postTargets, ...this.postScratch].forEach((t) => this.backend.destroyRenderTarget(t));
    this.postTargets = [];
    this.postScratch = [];
    this.postPasses = [];
  }

  private releaseGpuResources(): void {
    this.destroyRendererTargets();
    this.destroyPostTargets();
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
    this.postTargets = [];
    this.postScratch = [];
    this.postPasses = [];
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

/** Draws of a post step: its `repeat` (a positive integer), else 1. */
function postDraws(step: PostStep): number {
  const r = step.repeat ?? 1;
  if (!Number.isInteger(r) || r < 1)
    throw new VptError('invalid-scene', `post step "${step.name}": repeat must be a positive integer, got ${r}`);
  return r;
}

/** maxGpuBytes when the caller gives none: WebGPU's maxBufferSize (one allocation the device admits) within [1 GiB, 4 GiB]; 1 GiB on WebGL 2, which reports no memory figure. */
function defaultGpuBytes(backend: GpuBackend): number {
  const m = backend.limits.maxBufferSize;
  return m ? Math.min(MAX_DEFAULT_GPU_BYTES, Math.max(DEFAULT_GPU_BYTES, m)) : DEFAULT_GPU_BYTES;
}

function checkSize(width: number, height: number, backend: GpuBackend): void {
  const max = backend.limits.maxTextureDimension2D;
  if (!Number.isInteger(width) || !Number.isInteger(height) || width < 1 || height < 1) {
    throw new VptError('invalid-scene', `Render size must be positive integers, got ${width} x ${height}`);
  }
  if (width > max || height > max)
    throw new VptError(
      'limit-exceeded',
      `Render size ${width} x ${height} exceeds this device's 2D texture limit of ${max} (maxTextureDimension2D)`,
    );
}

/**
 * The stand-in of a streamed volume as the scene renders it: its voxels, with the spacing
 * stretched so that its box is the source's level 0 (a coarser level's box can be a little
 * larger or smaller, its sides rounded to whole voxels), and the source's value range.
 */
function standInWithLevel0Box(standIn: Scene['volume'], source: MultiscaleSource): Scene['volume'] {
  const l0 = source.levels[0];
  const spacing = [0, 1, 2].map((a) => (l0.dims[a] * l0.spacing[a]) / standIn.dims[a]) as [number, number, number];
  const valueRange = source.valueRange ?? standIn.valueRange;
  return { ...standIn, spacing, ...(valueRange ? { valueRange: [valueRange[0], valueRange[1]] } : {}) };
}
