/**
 * The WebGPU implementation of GpuBackend: textures, MRT render targets, full-screen
 * passes (one buffer-less triangle per render pass, one submit per draw), readback, and
 * device-loss handling with automatic re-acquisition of a device.
 *
 * Shader errors: createPass() is synchronous but WebGPU reports compilation
 * asynchronously. A compile error that is already known is thrown by createPass()/draw();
 * otherwise it is found in the background and the next finish() or readTexture()
 * rejects with the VptError('shader-compile') (see pipeline-cache.ts).
 */
import { VptError } from '../../errors.js';
import type {
  BackendCapabilities, BackendInfo, BackendLimits, BackendOptions, DrawCall, GpuBackend, GpuPass, GpuTexture, PassDescriptor, RenderTarget,
  TextureData, TextureDescriptor, TextureFormat,
} from '../backend.js';
import { DeferredErrors } from './deferred-errors.js';
import { type GpuDeviceHandle, requestGpuDevice } from './device-setup.js';
import { checkTextureData, colorAttachmentBytesPerSample, formatInfo, textureUsage } from './formats.js';
import { PipelineCache } from './pipeline-cache.js';
import { submitReadback, unpackReadback } from './readback.js';
import { WebGPUPass, WebGPURenderTarget, WebGPUTexture } from './resources.js';
import { UniformBufferPool } from './uniform-pool.js';
import { BUILTINS_BYTE_SIZE, linearSamplerBinding, usesLinearSampler } from './wgsl-prelude.js';
import { isFilterable, sliceCount } from '../backend.js';

export { isWebGPUAvailable } from './device-setup.js';

export async function createWebGPUBackend(canvas: HTMLCanvasElement | OffscreenCanvas, options: BackendOptions = {}): Promise<GpuBackend> {
  const handle = await requestGpuDevice(options);
  return new WebGPUBackend(canvas, options, handle);
}

/** How long simulateLoss() waits (beyond restoreAfterMs) for a new device before giving up. */
const RESTORE_TIMEOUT_MS = 10_000;
/** Delays between attempts to get a new device after a loss; a GPU process restart can take a moment. */
const RESTORE_RETRY_MS = [0, 250, 1000, 4000];

interface Waiter { resolve: () => void; reject: (e: unknown) => void }

/** Everything that lives and dies with one GPUDevice. */
interface DeviceState {
  readonly device: GPUDevice;
  readonly pipelines: PipelineCache;
  readonly uniforms: UniformBufferPool;
  readonly errors: DeferredErrors;
}

class WebGPUBackend implements GpuBackend {
  readonly kind = 'webgpu' as const;
  private currentInfo: BackendInfo;
  private state: DeviceState;
  private readonly context: GPUCanvasContext;
  private readonly canvasFormat: GPUTextureFormat;
  /** Bumped on every restore: objects from an older generation belong to a dead device. */
  private generation = 0;
  private lost = false;
  private disposed = false;
  /** Set by simulateLoss(): how long the lost handler waits before asking for a new device. */
  private restoreDelayMs: number | null = null;
  private readonly textures = new Set<WebGPUTexture>();
  private readonly targets = new Set<WebGPURenderTarget>();
  /** Readback buffers awaiting mapAsync, destroyed by dispose() (which aborts the map). */
  private readonly readbacks = new Set<GPUBuffer>();
  /** The clamp-to-edge linear sampler of filtered bindings, per device (made on first use). */
  private sampler: { device: GPUDevice; sampler: GPUSampler } | null = null;
  private readonly lostCallbacks: Array<() => void> = [];
  private readonly restoredCallbacks: Array<() => void> = [];
  private restoreWaiters: Waiter[] = [];

  /**
   * The current GPUDevice (a new one after a restore), for tools that time or inspect the
   * device, such as the benchmarks' timestamp queries. Rendering goes through the pass interface.
   */
  get device(): GPUDevice { return this.state.device; }

  constructor(readonly canvas: HTMLCanvasElement | OffscreenCanvas, private readonly options: BackendOptions, handle: GpuDeviceHandle) {
    const context = canvas.getContext('webgpu') as GPUCanvasContext | null;
    if (!context) {
      handle.device.destroy();
      throw new VptError('no-backend', 'This canvas cannot give a WebGPU context (it already has a WebGL or 2D context); use a fresh canvas');
    }
    this.context = context;
    this.canvasFormat = navigator.gpu.getPreferredCanvasFormat();
    this.currentInfo = handle.info;
    this.state = this.attach(handle);
  }

  get info(): BackendInfo {
    return this.currentInfo;
  }

  get limits(): BackendLimits {
    const l = this.state.device.limits;
    return { maxTextureDimension2D: l.maxTextureDimension2D, maxTextureDimension3D: l.maxTextureDimension3D, maxBufferSize: l.maxBufferSize };
  }

  private linearSampler(): GPUSampler {
    const device = this.state.device;
    if (this.sampler?.device !== device) {
      this.sampler = { device, sampler: device.createSampler({ label: 'vpt linear clamp', magFilter: 'linear', minFilter: 'linear', addressModeU: 'clamp-to-edge', addressModeV: 'clamp-to-edge', addressModeW: 'clamp-to-edge' }) };
    }
    return this.sampler.sampler;
  }

  get capabilities(): BackendCapabilities {
    const f = this.state.device.features;
    return { norm16: f.has('texture-formats-tier1'), float32Filterable: f.has('float32-filterable') };
  }

  get isLost(): boolean {
    return this.lost;
  }

  // ——— textures ———

  createTexture(desc: TextureDescriptor): GpuTexture {
    this.assertNotDisposed();
    const label = desc.label ?? `${desc.dimension} ${desc.format} texture`;
    const depth = desc.dimension === '3d' ? desc.depth ?? 1 : 1;
    if (desc.dimension === '2d' && desc.depth !== undefined && desc.depth !== 1) {
      throw new RangeError(`texture "${label}": a 2D texture has depth 1, got ${desc.depth}`);
    }
    formatInfo(desc.format);
    if ((desc.format === 'r16unorm' || desc.format === 'r16snorm') && !this.capabilities.norm16) {
      throw new VptError('missing-extension', `texture "${label}" is ${desc.format}, which needs the 'texture-formats-tier1' feature`);
    }
    if (desc.filter === 'linear' && !isFilterable(desc.format, this.capabilities)) {
      throw new VptError('missing-extension', `texture "${label}" (${desc.format}) cannot be filtered here: that needs the 'float32-filterable' feature`);
    }
    this.checkTextureSize(label, desc.dimension, desc.width, desc.height, depth);
    if (desc.data) checkTextureData(label, desc.format, desc.width * desc.height * depth, desc.data);
    const tex = this.allocTexture(desc.dimension, desc.width, desc.height, depth, desc.format, label);
    if (desc.data && tex.handle) this.upload(tex, desc.data);
    this.textures.add(tex);
    return tex;
  }

  writeTexture(texture: GpuTexture, data: TextureData): void {
    this.assertNotDisposed();
    const tex = this.own(texture, WebGPUTexture, 'texture');
    checkTextureData(tex.label, tex.format, tex.width * tex.height * tex.depth, data);
    if (this.lost) return;
    this.assertCurrent(tex, `texture "${tex.label}"`);
    this.upload(tex, data);
  }

  writeTextureSlices(texture: GpuTexture, zOffset: number, data: TextureData): void {
    this.assertNotDisposed();
    const tex = this.own(texture, WebGPUTexture, 'texture');
    const depth = sliceCount(tex, zOffset, data.length / formatInfo(tex.format).channels);
    checkTextureData(tex.label, tex.format, tex.width * tex.height * depth, data);
    if (this.lost) return;
    this.assertCurrent(tex, `texture "${tex.label}"`);
    if (!tex.handle) throw new RangeError(`texture "${tex.label}" was destroyed`);
    const bytesPerRow = tex.width * formatInfo(tex.format).bytesPerTexel;
    const view = data as Float32Array<ArrayBuffer> | Uint8Array<ArrayBuffer> | Uint16Array<ArrayBuffer> | Int16Array<ArrayBuffer>;
    this.state.device.queue.writeTexture({ texture: tex.handle, origin: [0, 0, zOffset] }, view, { bytesPerRow, rowsPerImage: tex.height }, [tex.width, tex.height, depth]);
  }

  destroyTexture(texture: GpuTexture): void {
    if (this.disposed) return;
    const tex = this.own(texture, WebGPUTexture, 'texture');
    this.textures.delete(tex);
    // Destroying a texture of a lost device is harmless, so stale objects need no special case.
    tex.destroy();
  }

  // ——— render targets ———

  createRenderTarget(width: number, height: number, formats: readonly TextureFormat[], label = 'render target'): RenderTarget {
    this.assertNotDisposed();
    if (formats.length === 0) throw new RangeError(`render target "${label}" needs at least one format`);
    formats.forEach((f) => formatInfo(f));
    this.checkColorAttachments(`Render target "${label}"`, formats);
    this.checkTextureSize(label, '2d', width, height, 1);
    const textures = formats.map((f, k) => this.allocTexture('2d', width, height, 1, f, `${label} [${k}]`));
    const target = new WebGPURenderTarget(width, height, textures, label, this.generation);
    this.targets.add(target);
    return target;
  }

  destroyRenderTarget(target: RenderTarget): void {
    if (this.disposed) return;
    const t = this.own(target, WebGPURenderTarget, 'render target');
    this.targets.delete(t);
    t.textures.forEach((tex) => tex.destroy());
  }

  // ——— passes ———

  createPass(desc: PassDescriptor): GpuPass {
    this.assertNotDisposed();
    const limits = this.state.device.limits;
    if (desc.textures.length > limits.maxSampledTexturesPerShaderStage) {
      throw new VptError('limit-exceeded', `Pass "${desc.label}" reads ${desc.textures.length} textures; this device allows ${limits.maxSampledTexturesPerShaderStage} (maxSampledTexturesPerShaderStage)`);
    }
    if (desc.outputs.length === 0) throw new RangeError(`pass "${desc.label}" has no outputs`);
    desc.outputs.forEach((f) => formatInfo(f));
    this.checkColorAttachments(`Pass "${desc.label}"`, desc.outputs);
    if (desc.uniforms.byteSize > limits.maxUniformBufferBindingSize) {
      throw new VptError('limit-exceeded', `Pass "${desc.label}" has a ${desc.uniforms.byteSize}-byte uniform struct; this device allows ${limits.maxUniformBufferBindingSize} (maxUniformBufferBindingSize)`);
    }
    if (this.lost) return new WebGPUPass(desc, null, this.generation);
    return new WebGPUPass(desc, this.state.pipelines.get(desc), this.generation);
  }

  draw(pass: GpuPass, call: DrawCall): void {
    this.assertNotDisposed();
    if (this.lost) return; // nothing can be drawn; the owner redraws after onRestored
    const p = this.own(pass, WebGPUPass, 'pass');
    const desc = p.descriptor;
    this.assertCurrent(p, `pass "${desc.label}"`);
    const entry = p.program!;
    if (entry.error) throw entry.error;
    const { device, pipelines, uniforms, errors } = this.state;

    if (call.uniforms.byteLength < desc.uniforms.byteSize) {
      throw new RangeError(`pass "${desc.label}": the uniform buffer has ${call.uniforms.byteLength} bytes, the layout needs ${desc.uniforms.byteSize}`);
    }

    let width: number;
    let height: number;
    let views: GPUTextureView[];
    let pipeline: GPURenderPipeline;
    let targetTextures: readonly WebGPUTexture[] = [];
    if (call.target === 'canvas') {
      if (desc.outputs.length !== 1 || desc.outputs[0] !== 'rgba8unorm') {
        throw new RangeError(`pass "${desc.label}" draws to the canvas, so it must have one rgba8unorm output, not [${desc.outputs.join(', ')}]`);
      }
      const current = this.context.getCurrentTexture();
      width = current.width;
      height = current.height;
      views = [current.createView()];
      // The canvas texture has the preferred format (often bgra8unorm), not rgba8unorm.
      pipeline = pipelines.pipeline(entry, [this.canvasFormat]);
    } else {
      const t = this.own(call.target, WebGPURenderTarget, 'render target');
      this.assertCurrent(t, `render target "${t.label}"`);
      if (t.textures.length !== desc.outputs.length || t.textures.some((tex, k) => tex.format !== desc.outputs[k])) {
        throw new RangeError(`pass "${desc.label}" writes [${desc.outputs.join(', ')}] but render target "${t.label}" holds [${t.textures.map((x) => x.format).join(', ')}]`);
      }
      width = t.width;
      height = t.height;
      views = t.textures.map((tex) => tex.view());
      pipeline = pipelines.pipeline(entry, desc.outputs);
      targetTextures = t.textures;
    }

    const textureEntries: GPUBindGroupEntry[] = desc.textures.map((binding, k) => {
      const given = call.textures[binding.name];
      if (!given) throw new RangeError(`pass "${desc.label}" needs texture "${binding.name}"`);
      const tex = this.own(given, WebGPUTexture, 'texture');
      this.assertCurrent(tex, `texture "${tex.label}"`);
      if (tex.dimension !== binding.dimension) {
        throw new RangeError(`pass "${desc.label}": "${binding.name}" is a ${binding.dimension} texture, got ${tex.dimension} texture "${tex.label}"`);
      }
      if (targetTextures.includes(tex)) {
        throw new RangeError(`pass "${desc.label}" reads texture "${tex.label}" while writing it (a feedback loop): ping-pong between two targets instead`);
      }
      if (!tex.handle) throw new RangeError(`pass "${desc.label}": texture "${tex.label}" was destroyed`);
      return { binding: 1 + k, resource: tex.view() };
    });

    // One buffer holds the pass's uniforms at 0 and VptBuiltins at the next aligned offset.
    const userSize = desc.uniforms.byteSize;
    const builtinsOffset = Math.ceil(userSize / device.limits.minUniformBufferOffsetAlignment) * device.limits.minUniformBufferOffsetAlignment;
    const buffer = uniforms.acquire(builtinsOffset + BUILTINS_BYTE_SIZE);
    device.queue.writeBuffer(buffer, 0, call.uniforms, 0, userSize);
    device.queue.writeBuffer(buffer, builtinsOffset, new Int32Array([width, height, 0, 0]));

    device.pushErrorScope('validation');
    const group0 = device.createBindGroup({
      label: desc.label,
      layout: entry.bindGroupLayout,
      entries: [
        { binding: 0, resource: { buffer, offset: 0, size: userSize } }, ...textureEntries,
        ...(usesLinearSampler(desc) ? [{ binding: linearSamplerBinding(desc), resource: this.linearSampler() }] : []),
      ],
    });
    const group1 = device.createBindGroup({
      label: 'vpt builtins',
      layout: pipelines.builtinsLayout,
      entries: [{ binding: 0, resource: { buffer, offset: builtinsOffset, size: BUILTINS_BYTE_SIZE } }],
    });
    const encoder = device.createCommandEncoder({ label: desc.label });
    const rp = encoder.beginRenderPass({
      label: desc.label,
      colorAttachments: views.map((view) => ({ view, loadOp: 'clear', storeOp: 'store', clearValue: [0, 0, 0, 0] })),
    });
    rp.setPipeline(pipeline);
    rp.setBindGroup(0, group0);
    rp.setBindGroup(1, group1);
    rp.draw(3);
    rp.end();
    device.queue.submit([encoder.finish()]);
    uniforms.submitted();
    errors.track(
      device.popErrorScope().then(async (err) => {
        if (!err) return null;
        // A broken kernel invalidates its pipeline and so this draw: report the compiler's log.
        const compileError = await entry.checked;
        return compileError ?? new Error(`WebGPU validation error while drawing pass "${desc.label}": ${err.message}`);
      }),
    );
  }

  // ——— readback and sync ———

  async readTexture(texture: GpuTexture): Promise<Float32Array | Uint8Array> {
    this.assertNotDisposed();
    const tex = this.own(texture, WebGPUTexture, 'texture');
    if (tex.dimension !== '2d') throw new RangeError(`readTexture reads 2D textures only; "${tex.label}" is 3D`);
    if (this.lost) throw new VptError('context-lost', `Cannot read texture "${tex.label}": the WebGPU device is lost`);
    this.assertCurrent(tex, `texture "${tex.label}"`);
    if (!tex.handle) throw new RangeError(`readTexture: texture "${tex.label}" was destroyed`);
    const state = this.state;
    const { buffer, bytesPerRow } = submitReadback(state.device, tex.handle, tex.width, tex.height, tex.format, tex.label);
    this.readbacks.add(buffer);
    try {
      // A kernel that failed to compile wrote nothing: report that rather than stale texels.
      await state.errors.flush();
      try {
        await buffer.mapAsync(GPUMapMode.READ);
      } catch (e) {
        throw this.readFailure(tex.label, state, e);
      }
      if (this.disposed || this.lost || this.state !== state) throw this.readFailure(tex.label, state);
      return unpackReadback(buffer.getMappedRange(), bytesPerRow, tex.width, tex.height, tex.format);
    } finally {
      this.readbacks.delete(buffer);
      buffer.destroy(); // also unmaps
    }
  }

  async finish(): Promise<void> {
    this.assertNotDisposed();
    if (this.lost) return;
    const state = this.state;
    await state.device.queue.onSubmittedWorkDone();
    if (this.state === state && !this.lost) await state.errors.flush();
  }

  resizeCanvas(width: number, height: number): void {
    this.assertNotDisposed();
    if (!Number.isInteger(width) || !Number.isInteger(height) || width < 1 || height < 1) {
      throw new RangeError(`canvas size must be positive integers, got ${width}x${height}`);
    }
    // The configured context picks up the new size at the next getCurrentTexture().
    if (this.canvas.width !== width) this.canvas.width = width;
    if (this.canvas.height !== height) this.canvas.height = height;
  }

  // ——— device loss ———

  onLost(callback: () => void): void {
    this.lostCallbacks.push(callback);
  }

  onRestored(callback: () => void): void {
    this.restoredCallbacks.push(callback);
  }

  simulateLoss(restoreAfterMs = 50): Promise<void> {
    if (this.disposed) return Promise.reject(new VptError('disposed', 'This WebGPU backend was disposed'));
    if (this.lost) return Promise.reject(new VptError('context-lost', 'The WebGPU device is already lost'));
    return new Promise<void>((resolve, reject) => {
      const timer = setTimeout(() => {
        this.restoreWaiters = this.restoreWaiters.filter((w) => w !== waiter);
        reject(new VptError('context-lost', `No new WebGPU device within ${restoreAfterMs + RESTORE_TIMEOUT_MS} ms of the simulated loss`));
      }, restoreAfterMs + RESTORE_TIMEOUT_MS);
      const waiter: Waiter = {
        resolve: () => { clearTimeout(timer); resolve(); },
        reject: (e) => { clearTimeout(timer); reject(e); },
      };
      this.restoreWaiters.push(waiter);
      this.restoreDelayMs = restoreAfterMs;
      // Lost from now on (draws become no-ops at once); callbacks run when device.lost resolves.
      this.lost = true;
      this.state.device.destroy();
    });
  }

  private handleLost(state: DeviceState, info: GPUDeviceLostInfo): void {
    if (this.disposed || state !== this.state) return;
    this.lost = true;
    runCallbacks(this.lostCallbacks);
    const delay = this.restoreDelayMs ?? 0;
    this.restoreDelayMs = null;
    if (info.reason !== 'destroyed') console.warn(`vpt: the WebGPU device was lost (${info.message}); requesting a new one`);
    setTimeout(() => void this.restore(state), delay);
  }

  /** Get a new adapter and device (a lost device never comes back), then let owners re-create resources. */
  private async restore(lostState: DeviceState): Promise<void> {
    let handle: GpuDeviceHandle | null = null;
    let failure: unknown = null;
    for (const wait of RESTORE_RETRY_MS) {
      if (wait) await sleep(wait);
      if (this.disposed) break;
      try {
        handle = await requestGpuDevice(this.options);
        break;
      } catch (e) {
        failure = e;
      }
    }
    if (this.disposed || lostState !== this.state) {
      handle?.device.destroy();
      return;
    }
    const waiters = this.restoreWaiters;
    this.restoreWaiters = [];
    if (!handle) {
      const err = new VptError('context-lost', 'The WebGPU device was lost and no new device could be obtained', { cause: failure });
      console.error(err);
      waiters.forEach((w) => w.reject(err));
      return; // stays lost
    }
    // Every GPU object died with the old device: forget them and start a new generation.
    this.forgetDeviceObjects();
    this.generation++;
    this.currentInfo = handle.info;
    this.state = this.attach(handle);
    this.lost = false;
    runCallbacks(this.restoredCallbacks);
    waiters.forEach((w) => w.resolve());
  }

  // ——— disposal ———

  dispose(): void {
    if (this.disposed) return;
    this.disposed = true;
    this.forgetDeviceObjects();
    this.readbacks.forEach((b) => b.destroy());
    this.readbacks.clear();
    this.context.unconfigure();
    this.restoreWaiters.forEach((w) => w.reject(new VptError('disposed', 'The WebGPU backend was disposed')));
    this.restoreWaiters = [];
    // Last, and after `disposed` is set, so the lost handler does not ask for a new device.
    this.state.device.destroy();
  }

  // ——— internals ———

  /** Set up per-device state and configure the canvas for a (new) device. */
  private attach(handle: GpuDeviceHandle): DeviceState {
    const device = handle.device;
    const errors = new DeferredErrors();
    const state: DeviceState = { device, pipelines: new PipelineCache(device, errors), uniforms: new UniformBufferPool(device), errors };
    device.lost.then((info) => this.handleLost(state, info));
    device.addEventListener('uncapturederror', (event) => {
      console.error(`vpt: uncaptured WebGPU error: ${(event as GPUUncapturedErrorEvent).error.message}`);
    });
    this.context.configure({ device, format: this.canvasFormat, alphaMode: 'premultiplied', usage: GPUTextureUsage.RENDER_ATTACHMENT });
    return state;
  }

  /** Destroy (harmless on a lost device) and drop everything made on the current device. */
  private forgetDeviceObjects(): void {
    this.textures.forEach((t) => t.destroy());
    this.targets.forEach((t) => t.textures.forEach((tex) => tex.destroy()));
    this.textures.clear();
    this.targets.clear();
    this.state.uniforms.destroy();
    this.state.pipelines.clear();
  }

  private allocTexture(dimension: '2d' | '3d', width: number, height: number, depth: number, format: TextureFormat, label: string): WebGPUTexture {
    if (this.lost) return new WebGPUTexture(dimension, width, height, depth, format, label, null, this.generation);
    const handle = this.state.device.createTexture({ label, dimension, format, size: [width, height, depth], usage: textureUsage(dimension) });
    return new WebGPUTexture(dimension, width, height, depth, format, label, handle, this.generation);
  }

  private upload(tex: WebGPUTexture, data: TextureData): void {
    if (!tex.handle) throw new RangeError(`texture "${tex.label}" was destroyed`);
    const bytesPerRow = tex.width * formatInfo(tex.format).bytesPerTexel;
    // The IDL takes [AllowShared] views; the typings only admit views over a plain ArrayBuffer.
    const view = data as Float32Array<ArrayBuffer> | Uint8Array<ArrayBuffer> | Uint16Array<ArrayBuffer> | Int16Array<ArrayBuffer>;
    this.state.device.queue.writeTexture({ texture: tex.handle }, view, { bytesPerRow, rowsPerImage: tex.height }, [tex.width, tex.height, tex.depth]);
  }

  /** Sizes are checked against the device before createTexture, which would only report a validation error later. */
  private checkTextureSize(label: string, dimension: '2d' | '3d', width: number, height: number, depth: number): void {
    for (const [name, v] of [['width', width], ['height', height], ['depth', depth]] as const) {
      if (!Number.isInteger(v) || v < 1) throw new RangeError(`texture "${label}": ${name} must be a positive integer, got ${v}`);
    }
    const limits = this.state.device.limits;
    if (dimension === '3d') {
      const max = limits.maxTextureDimension3D;
      if (width > max || height > max || depth > max) {
        throw new VptError('limit-exceeded', `3D texture "${label}" is ${width}x${height}x${depth}, but this device's maxTextureDimension3D is ${max}`);
      }
    } else {
      const max = limits.maxTextureDimension2D;
      if (width > max || height > max) {
        throw new VptError('limit-exceeded', `2D texture "${label}" is ${width}x${height}, but this device's maxTextureDimension2D is ${max}`);
      }
    }
  }

  private checkColorAttachments(what: string, formats: readonly TextureFormat[]): void {
    const limits = this.state.device.limits;
    if (formats.length > limits.maxColorAttachments) {
      throw new VptError('limit-exceeded', `${what} has ${formats.length} colour attachments; this device allows ${limits.maxColorAttachments} (maxColorAttachments)`);
    }
    const bytes = colorAttachmentBytesPerSample(formats);
    if (bytes > limits.maxColorAttachmentBytesPerSample) {
      throw new VptError('limit-exceeded', `${what} writes ${bytes} bytes per pixel ([${formats.join(', ')}]); this device allows ${limits.maxColorAttachmentBytesPerSample} (maxColorAttachmentBytesPerSample)`);
    }
  }

  private readFailure(label: string, state: DeviceState, cause?: unknown): VptError {
    if (this.disposed) return new VptError('disposed', `Reading texture "${label}" was cut short: the WebGPU backend was disposed`, { cause });
    if (this.lost || this.state !== state) return new VptError('context-lost', `Reading texture "${label}" failed: the WebGPU device was lost`, { cause });
    return new VptError('context-lost', `Reading texture "${label}" failed: mapAsync was rejected`, { cause });
  }

  private own<T>(obj: unknown, cls: abstract new (...args: never[]) => T, what: string): T {
    if (!(obj instanceof cls)) throw new TypeError(`this ${what} was not made by this WebGPU backend`);
    return obj;
  }

  private assertCurrent(obj: { generation: number }, what: string): void {
    if (obj.generation !== this.generation) {
      throw new VptError('context-lost', `${what} was made before the WebGPU device was lost; re-create it after onRestored`);
    }
  }

  private assertNotDisposed(): void {
    if (this.disposed) throw new VptError('disposed', 'This WebGPU backend was disposed');
  }
}

function sleep(ms: number): Promise<void> {
  return new Promise((r) => setTimeout(r, ms));
}

/** Run owner callbacks; one that throws must not stop the others or the backend's own bookkeeping. */
function runCallbacks(callbacks: ReadonlyArray<() => void>): void {
  for (const cb of callbacks) {
    try {
      cb();
    } catch (e) {
      console.error('vpt: a device-loss callback threw', e);
    }
  }
}
