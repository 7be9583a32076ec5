import { VptError } from '../errors.js';
import { createBackend } from '../gpu/create-backend.js';
import type { BackendPreference, GpuBackend, GpuPass, GpuTexture, RenderTarget } from '../gpu/backend.js';
import type { PostStep } from '../post-step.js';
import type { AuxiliaryPass, AuxiliaryTexture, Renderer, VolumeBinding } from '../renderer.js';
import type { Scene } from '../scene/scene.js';
import { validateScene } from '../scene/scene.js';
import { rasterizeTransferFunction, TF_RESOLUTION, transferFunctionSize } from '../scene/transfer-function.js';
import { voxelCount } from '../scene/volume.js';
import { downsampleVolume, fitFactors } from '../scene/downsample.js';
import { BYTES_PER_TEXEL } from '../gpu/backend.js';
import { planVolumeUpload, uploadsDataAsIs, volumeTextureData, volumeTextureSlab, volumeValueMapping, type VolumeSampling, type VolumeUpload } from '../gpu/volume-format.js';
import { gradientAtlasLayout } from '../gradient/atlas.js';
import { buildGradientVolume, destroyGradientVolume, type GradientVolume } from '../gradient/gradient-volume.js';
import { glslCommon, GLSL_RAY, GLSL_RNG, type CommonChunkOptions } from '../shaders/glsl-common.js';
import { SCENE_UNIFORM_FIELDS, sceneUniformValues } from '../shaders/scene-uniforms.js';
import { wgslCommon, WGSL_RAY, WGSL_RNG } from '../shaders/wgsl-common.js';
import { UniformLayout } from '../uniforms/layout.js';
import { PRESENT_PASS } from './present-pass.js';
import { ProgressiveLoop } from './progressive-loop.js';

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

/** Something the context changed to make a scene fit, reported through onWarning (and console.warn without a listener). */
export interface RenderWarning {
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
/** Voxels per converted upload slab (32 MiB of r16float, 64 MiB of r32float). */
const SLAB_VOXELS = 1 << 24;

export interface RenderStats {
  /** Iterations accumulated since the last reset. */
  iterations: number;
  /** Samples per pixel (one path per pixel per iteration). */
  samplesPerPixel: number;
  /** Mean wall-clock ms per iteration over the last measured batch (GPU synchronised). */
  msPerIteration: number;
  /** GPU memory held now. */
  gpuBytes: GpuBytes;
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

  private volumeTexture: GpuTexture | null = null;
  private volumeSource: Scene['volume'] | null = null;
  private volumeUpload: VolumeUpload | null = null;
  private volumeKey = 0; // bumped on every volume upload (VolumeBinding.key)
  private planMemo: { volume: Scene['volume']; sampling: VolumeSampling; plan: VolumeUpload } | null = null;
  private mappingMemo: { volume: Scene['volume']; upload: Pick<VolumeUpload, 'decodeScale' | 'decodeOffset'>; mapping: { valueScale: number; valueOffset: number } } | null = null;
  // The last budget fit: a scene volume → the volume actually uploaded (itself when it fits).
  private fitted: { source: Scene['volume']; key: string; volume: Scene['volume'] } | null = null;
  private readonly sampling: VolumeSampling;
  private readonly allowHalfFloat: boolean;
  readonly maxGpuBytes: number;
  private readonly warningListeners = new Set<(w: RenderWarning) => void>();
  private tfTexture: GpuTexture | null = null;
  private tfSource: string | null = null;
  // The volume's gradient magnitude (gradient/), built on the GPU the first time a 2D TF or
  // a renderer with needsGradient asks for it, kept until the volume changes.
  private gradient: GradientVolume | null = null;
  private gradientSource: Scene['volume'] | null = null;
  private gradientKey = '';
  // Renderer-declared textures by name; `target` is set for GPU-made ones (AuxiliaryPass).
  private auxTextures = new Map<string, AuxEntry>();
  private auxFor: { scene: Scene | null; renderer: Renderer | null; version: number } = { scene: null, renderer: null, version: -1 };
  private frame: RenderTarget | null = null;
  private accum: [RenderTarget, RenderTarget] | null = null;
  private hdr: RenderTarget | null = null;
  private postTargets: RenderTarget[] = [];

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
    if (this.sampling !== 'fast' && this.sampling !== 'exact') throw new VptError('invalid-scene', `sampling must be 'fast' or 'exact', got ${JSON.stringify(opts.sampling)}`);
    this.allowHalfFloat = opts.allowHalfFloatVolumes === true;
    if (opts.maxGpuBytes !== undefined && !(opts.maxGpuBytes > 0)) throw new VptError('invalid-scene', `maxGpuBytes must be a positive number of bytes, got ${opts.maxGpuBytes}`);
    this.maxGpuBytes = opts.maxGpuBytes ?? defaultGpuBytes(backend);
    checkSize(opts.width, opts.height, backend);
    this.width = opts.width;
    this.height = opts.height;
    this.backend.resizeCanvas(this.width, this.height);
    this.loop = new ProgressiveLoop({
      step: (n) => this.iterate(n),
      finishFrame: () => this.present(),
      sync: () => this.backend.finish(),
      onStats: (ms) => { this.msPerIteration = ms; this.emit(); },
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

  get renderer(): Renderer { return this._renderer; }
  get post(): readonly PostStep[] { return this._post; }
  get size(): { width: number; height: number } { return { width: this.width, height: this.height }; }

  get stats(): RenderStats {
    return { iterations: this.iteration, samplesPerPixel: this.iteration, msPerIteration: this.msPerIteration, gpuBytes: this.gpuBytes() };
  }

  /** Called when the context changes something to make a scene fit (a downsampled volume). */
  onWarning(listener: (warning: RenderWarning) => void): () => void {
    this.warningListeners.add(listener);
    return () => this.warningListeners.delete(listener);
  }

  /** GPU memory held now, by kind (textures as allocated: width × height × depth × bytes per texel). */
  gpuBytes(): GpuBytes {
    const tex = (t: GpuTexture | null | undefined) => (t ? t.width * t.height * t.depth * BYTES_PER_TEXEL[t.format] : 0);
    const target = (t: RenderTarget | null | undefined) => (t ? t.textures.reduce((a, x) => a + tex(x), 0) : 0);
    const volume = tex(this.volumeTexture);
    const gradient = this.gradient ? target(this.gradient.atlas) + target(this.gradient.max) : 0;
    let auxiliary = tex(this.tfTexture);
    for (const a of this.auxTextures.values()) auxiliary += tex(a.texture);
    let targets = target(this.frame) + target(this.hdr) + (this.accum ? target(this.accum[0]) + target(this.accum[1]) : 0);
    for (const t of this.postTargets) targets += target(t);
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
    const scene = this.fitScene(input);
    this.input = input;
    const [nx, ny, nz] = scene.volume.dims;
    if (this.wantsGradient(scene)) {
      const atlas = gradientAtlasLayout(scene.volume.dims);
      const max2D = this.backend.limits.maxTextureDimension2D;
      if (atlas.width > max2D || atlas.height > max2D) {
        throw new VptError('limit-exceeded', `The gradient volume of a [${nx}, ${ny}, ${nz}] volume (needed by the 2D transfer function or the renderer) needs a ${atlas.width} x ${atlas.height} slice atlas; this device's 2D texture limit is ${max2D} (maxTextureDimension2D)`);
      }
    }
    this.scene = scene;
    this.syncSceneResources();
    this.reset();
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
    if (f && f.key === key && sameVoxels(f.source, scene.volume) && f.volume !== f.source) {
      // The same voxels with another value range: keep the downsampled copy, take the new range.
      const volume = { ...f.volume, valueRange: scene.volume.valueRange };
      this.fitted = { source: scene.volume, key, volume };
      return { ...scene, volume };
    }
    const upload = this.planUpload(scene.volume, sampling);
    const perVoxel = upload.bytesPerVoxel + (gradient ? (sampling === 'exact' ? 4 : 2) : 0);
    const pixels = this.width * this.height;
    const targetBytes = pixels * 16 * (this._renderer.frameFormats.length + 2 * this._renderer.accumulationFormats.length + 1 + this._post.length);
    const budget = this.maxGpuBytes - targetBytes - TF_RESOLUTION * 16 * 256;
    const max3D = this.backend.limits.maxTextureDimension3D;
    const from = [...scene.volume.dims] as [number, number, number];
    const factors = fitFactors(from, perVoxel, budget, max3D);
    if (!factors) {
      throw new VptError('limit-exceeded', `maxGpuBytes (${this.maxGpuBytes} bytes) leaves no room for a volume next to the ${this.width} x ${this.height} render targets`);
    }
    let volume = scene.volume;
    if (factors.some((f) => f > 1)) {
      volume = downsampleVolume(scene.volume, factors);
      const over3D = from.some((d) => d > max3D);
      const why = over3D
        ? `a side exceeds this device's 3D texture limit of ${max3D} (maxTextureDimension3D)`
        : `${voxelCount(from)} voxels x ${perVoxel} bytes exceed the GPU memory budget of ${this.maxGpuBytes} bytes (maxGpuBytes)`;
      const warning: RenderWarning = {
        code: 'volume-downsampled', factors, from, to: [...volume.dims] as [number, number, number],
        message: `Volume [${from.join(', ')}] downsampled by [${factors.join(', ')}] to [${volume.dims.join(', ')}]: ${why}`,
      };
      if (this.warningListeners.size === 0) console.warn(`vpt: ${warning.message}`);
      this.warningListeners.forEach((l) => l(warning));
    }
    this.fitted = { source: scene.volume, key, volume };
    return volume === scene.volume ? scene : { ...scene, volume };
  }

  /** Shallow-merge changes into the current scene (camera, lights, TF…) and reset. */
  updateScene(changes: Partial<Scene>): void {
    if (!this.input) throw new VptError('invalid-scene', 'updateScene() before setScene()');
    this.setScene({ ...this.input, ...changes });
  }

  getScene(): Scene | null { return this.scene; }

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
  }

  /** Run n iterations (generate + integrate each). Does not wait for the GPU. */
  iterate(n = 1): void {
    this.assertAlive();
    if (!this.scene || this.backend.isLost) return;
    this.prepare();
    const scene = this.scene;
    const passes = this.passes!;
    const textures: Record<string, GpuTexture> = { volume: this.volumeTexture!, transferFunction: this.tfTexture! };
    if (this.gradient && this.wantsGradient(scene)) {
      textures.gradientMagnitude = this.gradient.atlas.textures[0];
      textures.gradientMax = this.gradient.max.textures[0];
    }
    for (const [name, aux] of this.auxTextures) if (aux.bind) textures[name] = aux.texture;
    for (let k = 0; k < n; k++) {
      const uniforms = this.uniforms(scene);
      this.backend.draw(passes.generate, { uniforms, textures, target: this.frame! });
      const [prev, next] = this.accum!;
      const integrateTextures: Record<string, GpuTexture> = {};
      this.frame!.textures.forEach((t, i) => { integrateTextures[`frame${i}`] = t; });
      prev.textures.forEach((t, i) => { integrateTextures[`accum${i}`] = t; });
      this.backend.draw(passes.integrate, { uniforms, textures: integrateTextures, target: next });
      this.accum = [next, prev];
      this.iteration++;
    }
  }

  /** Reset, run exactly n iterations, render and post-process, and wait for the GPU. */
  async renderIterations(n: number): Promise<void> {
    if (!Number.isInteger(n) || n < 1) throw new VptError('invalid-scene', `renderIterations needs a positive integer, got ${n}`);
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
    if (this.hdrIteration === this.iteration && this.postKey === postKey && this.postPasses.length === this._post.length) return;
    this.postKey = postKey;
    this.prepare();
    const uniforms = this.uniforms(this.scene, this.iteration - 1);
    const accTextures: Record<string, GpuTexture> = {};
    this.accum![0].textures.forEach((t, i) => { accTextures[`accum${i}`] = t; });
    this.backend.draw(this.passes!.render, { uniforms, textures: accTextures, target: this.hdr! });
    this.preparePost();
    let input = this.hdr!.textures[0];
    this._post.forEach((step, i) => {
      const pass = this.postPasses[i];
      this.backend.draw(pass, { uniforms: step.uniforms.pack(step.uniformValues()), textures: { inputImage: input }, target: this.postTargets[i] });
      input = this.postTargets[i].textures[0];
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

  /** The HDR render output (linear RGB, a = coverage), RGBA float, top row first. */
  async readHDR(): Promise<Float32Array> {
    this.renderImage();
    if (!this.hdr) throw new VptError('invalid-scene', 'Nothing rendered yet: call setScene() and iterate first');
    return (await this.backend.readTexture(this.hdr.textures[0])) as Float32Array;
  }

  /** The LDR image after the post chain, RGBA8, top row first. */
  async readLDR(): Promise<Uint8Array> {
    this.renderImage();
    if (!this.hdr) throw new VptError('invalid-scene', 'Nothing rendered yet: call setScene() and iterate first');
    return (await this.backend.readTexture(this.ldrTexture())) as Uint8Array;
  }

  /**
   * The sample of the most recent iteration alone (the renderer's frame buffer,
   * output `index`), RGBA float, top row first. For tests and debugging.
   */
  async readFrame(index = 0): Promise<Float32Array> {
    if (!this.frame || this.iteration === 0) throw new VptError('invalid-scene', 'Nothing rendered yet: call setScene() and iterate first');
    return (await this.backend.readTexture(this.frame.textures[index])) as Float32Array;
  }

  /**
   * An auxiliary texture of the renderer as its kernels see it (for tests and tools), read
   * back as floats; built first if the scene changed since the last iteration.
   */
  async readAuxiliaryTexture(name: string): Promise<Float32Array> {
    this.assertAlive();
    if (!this.scene) throw new VptError('invalid-scene', 'readAuxiliaryTexture() before setScene()');
    this.syncAuxiliaryTextures();
    const aux = this.auxTextures.get(name);
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
    if (!this.gradient || this.gradientSource !== this.scene.volume || this.gradientKey !== this.volumeBinding(this.scene).key) {
      this.dropGradient();
      this.gradient = buildGradientVolume(this.backend, this.volumeTexture!, this.scene.volume, this.gradientOptions(this.scene));
      this.gradientSource = this.scene.volume;
      this.gradientKey = this.volumeBinding(this.scene).key;
    }
    const g = this.gradient;
    const [atlas, max] = await Promise.all([this.backend.readTexture(g.atlas.textures[0]), this.backend.readTexture(g.max.textures[0])]) as Float32Array[];
    const [nx, ny, nz] = this.scene.volume.dims;
    const magnitudes = new Float32Array(nx * ny * nz);
    for (let z = 0; z < nz; z++) {
      const ox = (z % g.layout.columns) * nx, oy = Math.floor(z / g.layout.columns) * ny;
      for (let y = 0; y < ny; y++) {
        magnitudes.set(atlas.subarray(ox + g.layout.width * (oy + y), ox + g.layout.width * (oy + y) + nx), nx * (y + ny * z));
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
    const [a, b] = await Promise.all(halves.map((i) => this.backend.readTexture(this.accum![0].textures[i]))) as Float32Array[];
    let sq = 0, sum = 0, n = 0;
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

  stop(): void { this.loop.stop(); }

  get running(): boolean { return this.loop.running; }

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
    return this.layout.pack({
      ...sceneUniformValues(scene, this.width, this.height, iteration, TF_RESOLUTION, this.volumeMapping(scene)),
      ...this._renderer.paramValues(scene),
    });
  }

  /** The texel → normalized value map of the uploaded volume (scene uniforms valueScale/valueOffset). */
  private volumeMapping(scene: Scene): { valueScale: number; valueOffset: number } {
    // Memoized: normalizationRange scans int16/float32 data without a valueRange, and this runs every iteration.
    const upload = this.volumeUpload ?? EXACT_DECODE;
    const m = this.mappingMemo;
    if (m && m.volume === scene.volume && m.upload === upload) return m.mapping;
    const mapping = volumeValueMapping(scene.volume, upload);
    this.mappingMemo = { volume: scene.volume, upload, mapping };
    return mapping;
  }

  /** What auxiliary passes need to read the volume texture's texels (Renderer.auxiliaryTextures). */
  private volumeBinding(scene: Scene): VolumeBinding {
    const m = this.volumeMapping(scene);
    return { ...m, format: this.volumeUpload?.format ?? 'r32float', key: `${this.volumeKey}|${m.valueScale}|${m.valueOffset}` };
  }

  /** The upload plan of a volume, kept per volume and sampling (a uint16 or half-float plan scans the data once). */
  private planUpload(volume: Scene['volume'], sampling: VolumeSampling): VolumeUpload {
    const memo = this.planMemo;
    // The plan depends on the voxels alone, not on the value range.
    if (memo && sameVoxels(memo.volume, volume) && memo.sampling === sampling) return memo.plan;
    const plan = planVolumeUpload(volume, this.backend.capabilities, { sampling, allowHalfFloat: this.allowHalfFloat });
    this.planMemo = { volume, sampling, plan };
    return plan;
  }

  private samplingOf(scene: Scene): VolumeSampling {
    return scene.sampling ?? this.sampling;
  }

  /**
   * The volume texture: the volume's own array when the format takes it as is, else converted
   * and written in slabs of about 16 M voxels, so a real-size volume never has a full-size
   * converted copy next to it in memory.
   */
  private uploadVolume(volume: Scene['volume'], upload: VolumeUpload): GpuTexture {
    const [width, height, depth] = volume.dims;
    const desc = { dimension: '3d' as const, width, height, depth, format: upload.format, filter: upload.filter, label: 'volume' };
    if (uploadsDataAsIs(upload) || width * height * depth <= SLAB_VOXELS) return this.backend.createTexture({ ...desc, data: volumeTextureData(volume, upload) });
    const texture = this.backend.createTexture(desc);
    const slabDepth = Math.max(1, Math.floor(SLAB_VOXELS / (width * height)));
    const scratch = new ArrayBuffer(slabDepth * width * height * 4); // one buffer for every slab
    for (let z = 0; z < depth; z += slabDepth) {
      const z1 = Math.min(depth, z + slabDepth);
      this.backend.writeTextureSlices(texture, z, volumeTextureSlab(volume, upload, z, z1, scratch));
    }
    return texture;
  }

  /** Upload the volume and transfer function when they changed (by identity / content). */
  private syncSceneResources(): void {
    const scene = this.scene!;
    const upload = this.planUpload(scene.volume, this.samplingOf(scene));
    const same = this.volumeUpload && this.volumeUpload.format === upload.format && this.volumeUpload.filter === upload.filter
      && this.volumeUpload.decodeScale === upload.decodeScale && this.volumeUpload.decodeOffset === upload.decodeOffset;
    if (this.volumeTexture && same && this.volumeSource !== scene.volume && sameVoxels(this.volumeSource!, scene.volume)) {
      // Only the value range (or name) changed: the kernels map it, so nothing is uploaded;
      // the gradient volume and the majorant grid follow through their keys.
      this.volumeSource = scene.volume;
      this.dropGradient();
    }
    if (this.volumeSource !== scene.volume || !this.volumeTexture || !same) {
      if (this.volumeTexture) this.backend.destroyTexture(this.volumeTexture);
      this.volumeTexture = null;
      this.dropGradient();
      const [width, height, depth] = scene.volume.dims;
      this.volumeTexture = this.uploadVolume(scene.volume, upload);
      this.volumeSource = scene.volume;
      this.volumeUpload = upload;
      this.volumeKey++;
    }
    const tfKey = JSON.stringify(scene.transferFunction);
    if (this.tfSource !== tfKey || !this.tfTexture) {
      const data = rasterizeTransferFunction(scene.transferFunction, TF_RESOLUTION);
      const [width, height] = transferFunctionSize(scene.transferFunction, TF_RESOLUTION);
      if (this.tfTexture && (this.tfTexture.width !== width || this.tfTexture.height !== height)) {
        this.backend.destroyTexture(this.tfTexture);
        this.tfTexture = null;
      }
      if (this.tfTexture) this.backend.writeTexture(this.tfTexture, data);
      else this.tfTexture = this.backend.createTexture({ dimension: '2d', width, height, format: 'rgba32float', data, label: 'transfer function' });
      this.tfSource = tfKey;
    }
    this.syncGradient();
  }

  /** A 2D transfer function reads the gradient magnitude, and so does a renderer that asks for it. */
  private wantsGradient(scene: Scene): boolean {
    return scene.transferFunction.dimensions === '2d' || this._renderer.needsGradient === true;
  }

  /** Build the gradient-magnitude volume when the scene first needs it (GPU passes, no read-back). */
  private syncGradient(): void {
    const scene = this.scene!;
    if (!this.wantsGradient(scene) || !this.volumeTexture || this.backend.isLost) return;
    if (this.gradient && this.gradientSource === scene.volume && this.gradientKey === this.volumeBinding(scene).key) return;
    this.dropGradient();
    this.gradient = buildGradientVolume(this.backend, this.volumeTexture, scene.volume, this.gradientOptions(scene));
    this.gradientSource = scene.volume;
    this.gradientKey = this.volumeBinding(scene).key;
  }

  /** The gradient build reads texels through the scene's mapping; 16 bits on the fast path. */
  private gradientOptions(scene: Scene) {
    return { ...this.volumeMapping(scene), format: this.samplingOf(scene) === 'exact' ? 'r32float' as const : 'r16float' as const };
  }

  private dropGradient(): void {
    if (this.gradient) destroyGradientVolume(this.backend, this.gradient);
    this.gradient = null;
    this.gradientSource = null;
    this.gradientKey = '';
  }

  /** Which shared chunks (and defines) the generate pass needs for this scene. */
  private chunkOptions(scene: Scene): Required<CommonChunkOptions> {
    const tf2d = scene.transferFunction.dimensions === '2d';
    return { tf2d, gradient: this.wantsGradient(scene), hardwareFilter: this.volumeUpload?.filter === 'linear' };
  }

  /** Compile the renderer's variant for the current scene and allocate its targets. */
  private prepare(): void {
    const r = this._renderer;
    const chunks = this.chunkOptions(this.scene!);
    // VPT_TF_2D / VPT_GRADIENT let a kernel branch at compile time on what the scene binds.
    const features = { ...r.features(this.scene!), VPT_TF_2D: chunks.tf2d, VPT_GRADIENT: chunks.gradient };
    if (r.version !== this.rendererVersion) {
      this.rendererVersion = r.version;
      this.reset();
    }
    this.syncGradient();
    this.syncAuxiliaryTextures();
    const auxBindings = [...this.auxTextures].filter(([, a]) => a.bind).map(([name, a]) => ({ name, dimension: a.dimension }));
    const gradientBindings = chunks.gradient ? [{ name: 'gradientMagnitude', dimension: '2d' as const }, { name: 'gradientMax', dimension: '2d' as const }] : [];
    const key = `${r.name}|${JSON.stringify(features)}|${auxBindings.map((b) => b.name).join(',')}|${chunks.hardwareFilter ? 'filtered' : 'exact'}`;
    if (!this.passes || key !== this.variantKey) {
      this.layout = new UniformLayout('Params', [...SCENE_UNIFORM_FIELDS, ...r.paramFields]);
      const mk = (stage: 'generate' | 'integrate' | 'render', textures: { name: string; dimension: '2d' | '3d' }[], outputs: typeof r.frameFormats) =>
        this.backend.createPass({
          label: `${r.name}.${stage}`,
          glsl: GLSL_COMMON_FOR(stage, chunks) + r.kernels[stage].glsl,
          wgsl: WGSL_COMMON_FOR(stage, chunks) + r.kernels[stage].wgsl,
          uniforms: this.layout,
          textures,
          outputs,
          defines: features,
        });
      const frameTex = r.frameFormats.map((_, i) => ({ name: `frame${i}`, dimension: '2d' as const }));
      const accTex = r.accumulationFormats.map((_, i) => ({ name: `accum${i}`, dimension: '2d' as const }));
      this.passes = {
        generate: mk('generate', [{ name: 'volume', dimension: '3d', ...(chunks.hardwareFilter ? { filter: 'linear' as const } : {}) }, { name: 'transferFunction', dimension: '2d' }, ...gradientBindings, ...auxBindings], r.frameFormats),
        integrate: mk('integrate', [...frameTex, ...accTex], r.accumulationFormats),
        render: mk('render', accTex, ['rgba32float']),
      };
      this.variantKey = key;
    }
    if (!this.frame) {
      this.frame = this.backend.createRenderTarget(this.width, this.height, r.frameFormats, `${r.name} frame`);
      this.accum = [
        this.backend.createRenderTarget(this.width, this.height, r.accumulationFormats, `${r.name} accumulation A`),
        this.backend.createRenderTarget(this.width, this.height, r.accumulationFormats, `${r.name} accumulation B`),
      ];
      this.hdr = this.backend.createRenderTarget(this.width, this.height, ['rgba32float'], 'HDR render');
    }
  }

  /** Build, reuse or free the renderer's auxiliary textures (only when scene or renderer changed). */
  private syncAuxiliaryTextures(): void {
    const r = this._renderer;
    if (this.auxFor.scene === this.scene && this.auxFor.renderer === r && this.auxFor.version === r.version) return;
    const specs: readonly AuxiliaryTexture[] = r.auxiliaryTextures?.(this.scene!, this.volumeBinding(this.scene!)) ?? [];
    const wanted = new Set(specs.map((a) => a.name));
    for (const [name, aux] of this.auxTextures) {
      if (!wanted.has(name)) { this.releaseAux(aux); this.auxTextures.delete(name); }
    }
    for (const spec of specs) {
      const have = this.auxTextures.get(spec.name);
      if (have && have.key === spec.key) continue;
      if (have) { this.releaseAux(have); this.auxTextures.delete(spec.name); }
      this.auxTextures.set(spec.name, spec.render ? this.renderAux(spec, spec.render) : { key: spec.key, texture: this.backend.createTexture(this.auxDescriptor(spec)), dimension: spec.dimension, bind: spec.bind !== false });
    }
    this.auxFor = { scene: this.scene, renderer: r, version: r.version };
  }

  private auxDescriptor(spec: AuxiliaryTexture) {
    if (!spec.create) throw new RangeError(`auxiliary texture "${spec.name}" has neither create() nor render`);
    return spec.create();
  }

  /** Run an AuxiliaryPass into a new 2D target, reading the scene's textures and earlier auxiliary ones. */
  private renderAux(spec: AuxiliaryTexture, p: AuxiliaryPass): AuxEntry {
    if (spec.dimension !== '2d') throw new RangeError(`auxiliary texture "${spec.name}": a GPU-made texture is 2D`);
    const textures: Record<string, GpuTexture> = {};
    for (const b of p.inputs) {
      const t = b.name === 'volume' ? this.volumeTexture : b.name === 'transferFunction' ? this.tfTexture : this.auxTextures.get(b.name)?.texture;
      if (!t) throw new RangeError(`auxiliary pass "${p.label}" reads "${b.name}", which is not the volume, the transfer function or an earlier auxiliary texture`);
      textures[b.name] = t;
    }
    const pass = this.backend.createPass({ label: p.label, glsl: p.glsl, wgsl: p.wgsl, uniforms: p.uniforms, textures: p.inputs, outputs: [p.format] });
    const target = this.backend.createRenderTarget(p.width, p.height, [p.format], p.label);
    this.backend.draw(pass, { uniforms: p.uniforms.pack(p.values), textures, target });
    return { key: spec.key, texture: target.textures[0], dimension: '2d', target, bind: spec.bind !== false };
  }

  private releaseAux(aux: AuxEntry): void {
    if (aux.target) this.backend.destroyRenderTarget(aux.target);
    else this.backend.destroyTexture(aux.texture);
  }

  private preparePost(): void {
    if (this.postPasses.length !== this._post.length || this.postTargets.length !== this._post.length) {
      this.destroyPostTargets();
      this.postPasses = this._post.map((step, i) => this.backend.createPass({
        label: `post.${step.name}`,
        glsl: step.glsl,
        wgsl: step.wgsl,
        uniforms: step.uniforms,
        textures: [{ name: 'inputImage', dimension: '2d' }],
        outputs: [i === this._post.length - 1 ? 'rgba8unorm' : 'rgba32float'],
        defines: step.defines?.() ?? {},
      }));
      this.postTargets = this._post.map((_, i) =>
        this.backend.createRenderTarget(this.width, this.height, [i === this._post.length - 1 ? 'rgba8unorm' : 'rgba32float'], `post ${i}`));
    }
  }

  private ldrTexture(): GpuTexture {
    if (this._post.length === 0) {
      throw new VptError('invalid-scene', 'The post chain is empty: add at least one step (e.g. sRGB encoding) to get an LDR image');
    }
    return this.postTargets[this.postTargets.length - 1].textures[0];
  }

  private destroyRendererTargets(): void {
    if (this.frame) this.backend.destroyRenderTarget(this.frame);
    this.accum?.forEach((t) => this.backend.destroyRenderTarget(t));
    if (this.hdr) this.backend.destroyRenderTarget(this.hdr);
    this.frame = null;
    this.accum = null;
    this.hdr = null;
  }

  private destroyPostTargets(): void {
    this.postTargets.forEach((t) => this.backend.destroyRenderTarget(t));
    this.postTargets = [];
    this.postPasses = [];
  }

  private releaseGpuResources(): void {
    this.destroyRendererTargets();
    this.destroyPostTargets();
    if (this.volumeTexture) this.backend.destroyTexture(this.volumeTexture);
    if (this.tfTexture) this.backend.destroyTexture(this.tfTexture);
    this.volumeTexture = null;
    this.tfTexture = null;
    this.dropGradient();
    this.auxTextures.forEach((a) => this.releaseAux(a));
    this.auxTextures.clear();
    this.auxFor = { scene: null, renderer: null, version: -1 };
  }

  /** After a context/device loss: every GPU object is gone; rebuild from the retained scene and continue. */
  private restore(): void {
    if (this.disposed) return;
    // The old handles belong to the lost context: forget them without calling destroy.
    this.frame = null; this.accum = null; this.hdr = null;
    this.postTargets = []; this.postPasses = []; this.presentPass = null;
    this.volumeTexture = null; this.volumeSource = null; this.tfTexture = null; this.tfSource = null;
    this.gradient = null; this.gradientSource = null; this.gradientKey = '';
    this.volumeUpload = null; this.planMemo = null;
    this.passes = null; this.variantKey = ''; this.presentedVersion = -1;
    this.auxTextures.clear(); this.auxFor = { scene: null, renderer: null, version: -1 };
    this.backend.resizeCanvas(this.width, this.height);
    if (this.scene) this.syncSceneResources();
    this.reset();
    this.loop.resume();
  }
}

interface AuxEntry {
  key: string;
  texture: GpuTexture;
  dimension: '2d' | '3d';
  /** Bound to the generate pass (AuxiliaryTexture.bind). */
  bind: boolean;
  /** The render target a GPU-made texture lives in (destroyed with it). */
  target?: RenderTarget;
}

// The volume/TF chunks read the `volume` and `transferFunction` (and gradient) textures,
// which only the generate pass binds; integrate and render get the texture-free chunks.
const GLSL_COMMON_FOR = (stage: string, o: CommonChunkOptions) => (stage === 'generate' ? glslCommon(o) : GLSL_RNG + GLSL_RAY);
const WGSL_COMMON_FOR = (stage: string, o: CommonChunkOptions) => (stage === 'generate' ? wgslCommon(o) : WGSL_RNG + WGSL_RAY);

const EXACT_DECODE = { decodeScale: 1, decodeOffset: 0 };

/** Two volumes with the same voxels (the same array, dims and type): they differ at most in value range or name. */
function sameVoxels(a: Scene['volume'], b: Scene['volume']): boolean {
  return a.data === b.data && a.type === b.type && a.dims.every((d, i) => d === b.dims[i]);
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
  if (width > max || height > max) throw new VptError('limit-exceeded', `Render size ${width} x ${height} exceeds this device's 2D texture limit of ${max} (maxTextureDimension2D)`);
}
