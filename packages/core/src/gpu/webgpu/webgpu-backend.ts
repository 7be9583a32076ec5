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
  BackendCapabilities,
  BackendInfo,
  BackendLimits,
  BackendOptions,
  DrawCall,
  GpuBackend,
  GpuPass,
  GpuTexture,
  PassDescriptor,
  RenderTarget,
  TextureData,
  TextureDescriptor,
  TextureFormat,
} from '../backend.js';
import { DeferredErrors } from './deferred-errors.js';
import { type GpuDeviceHandle, requestGpuDevice } from './device-setup.js';
import { checkTextureData, colorAttachmentBytesPerSample, formatInfo, textureUsage } from './formats.js';
import {
  checkBoundTexture,
  checkCanvasOutputs,
  checkPassOutputs,
  checkReadable,
  checkTargetFormats,
  checkTargetOutputs,
  checkTextureCapabilities,
  checkTextureSize,
  checkUniformBytes,
  givenTexture,
  textureLabelAndDepth,
  type TextureSizeLimits,
} from '../validation.js';
import { BackendBase, runCallbacks } from '../backend-base.js';
import { PipelineCache } from './pipeline-cache.js';
import { submitReadback, unpackReadback } from './readback.js';
import { WebGPUPass, WebGPURenderTarget, WebGPUTexture } from './resources.js';
import { UniformBufferPool } from './uniform-pool.js';
import { BUILTINS_BYTE_SIZE, linearSamplerBinding, usesLinearSampler } from './wgsl-prelude.js';
import { checkTextureRegion, sliceCount } from '../backend.js';

export { isWebGPUAvailable } from './device-setup.js';

export async function createWebGPUBackend(
  canvas: HTMLCanvasElement | OffscreenCanvas,
  options: BackendOptions = {},
): Promise<GpuBackend> {
  const handle: GpuDeviceHandle = options.device
    ? {
        adapter: null,
        device: options.device,
        info: { kind: 'webgpu', renderer: 'shared GPUDevice', vendor: 'unknown' },
      }
    : await requestGpuDevice(options);
  return new WebGPUBackend(canvas, options, handle);
}

/** How long simulateLoss() waits (beyond restoreAfterMs) for a new device before giving up. */
const RESTORE_TIMEOUT_MS = 10_000;
/** Delays between attempts to get a new device after a loss; a GPU process restart can take a moment. */
const RESTORE_RETRY_MS = [0, 250, 1000, 4000];

interface Waiter {
  resolve: () => void;
  reject: (e: unknown) => void;
}

/** Everything that lives and dies with one GPUDevice. */
interface DeviceState {
  readonly device: GPUDevice;
  readonly pipelines: PipelineCache;
  readonly uniforms: UniformBufferPool;
  readonly errors: DeferredErrors;
}

class WebGPUBackend extends BackendBase implements GpuBackend {
  readonly kind = 'webgpu' as const;
  private currentInfo: BackendInfo;
  private state: DeviceState;
  private readonly context: GPUCanvasContext;
  private readonly canvasFormat: GPUTextureFormat;
  private lost = false;
  /** Set by simulateLoss(): how long the lost handler waits before asking for a new device. */
  private restoreDelayMs: number | null = null;
  private readonly textures = new Set<WebGPUTexture>();
  /** Textures of the device's owner (importTexture): bound, never destroyed. */
  private readonly imported = new WeakSet<WebGPUTexture>();
  /** Drawing on a GPUDevice someone else owns (BackendOptions.device): never destroyed or replaced here. */
  private readonly shared: boolean;
  private readonly targets = new Set<WebGPURenderTarget>();
  /** Readback buffers awaiting mapAsync, destroyed by dispose() (which aborts the map). */
  private readonly readbacks = new Set<GPUBuffer>();
  /** The clamp-to-edge linear sampler of filtered bindings, per device (made on first use). */
  private sampler: { device: GPUDevice; sampler: GPUSampler } | null = null;
  private restoreWaiters: Waiter[] = [];

  /**
   * The current GPUDevice (a new one after a restore), for tools that time or inspect the
   * device, such as the benchmarks' timestamp queries. Rendering goes through the pass interface.
   */
  get device(): GPUDevice {
    return this.state.device;
  }

  constructor(
    readonly canvas: HTMLCanvasElement | OffscreenCanvas,
    private readonly options: BackendOptions,
    handle: GpuDeviceHandle,
  ) {
    super({ backend: 'WebGPU', lossTarget: 'WebGPU device' });
    this.shared = options.device !== undefined;
    const context = canvas.getContext('webgpu') as GPUCanvasContext | null;
    if (!context) {
      if (!options.device) handle.device.destroy();
      throw new VptError(
        'no-backend',
        'This canvas cannot give a WebGPU context (it already has a WebGL or 2D context); use a fresh canvas',
      );
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
    return {
      maxTextureDimension2D: l.maxTextureDimension2D,
      maxTextureDimension3D: l.maxTextureDimension3D,
      maxBufferSize: l.maxBufferSize,
    };
  }

  private linearSampler(): GPUSampler {
    const device = this.state.device;
    if (this.sampler?.device !== device) {
      this.sampler = {
        device,
        sampler: device.createSampler({
          label: 'vpt linear clamp',
          magFilter: 'linear',
          minFilter: 'linear',
          addressModeU: 'clamp-to-edge',
          addressModeV: 'clamp-to-edge',
          addressModeW: 'clamp-to-edge',
        }),
      };
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
    const { label, depth } = textureLabelAndDepth(desc);
    formatInfo(desc.format);
    checkTextureCapabilities(label, desc, this.capabilities, {
      norm16: "the 'texture-formats-tier1' feature",
      float32Filterable: "the 'float32-filterable' feature",
    });
    checkTextureSize(label, desc.dimension, desc.width, desc.height, depth, this.sizeLimits());
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
    const view = data as
      Float32Array<ArrayBuffer> | Uint8Array<ArrayBuffer> | Uint16Array<ArrayBuffer> | Int16Array<ArrayBuffer>;
    this.state.device.queue.writeTexture(
      { texture: tex.handle, origin: [0, 0, zOffset] },
      view,
      { bytesPerRow, rowsPerImage: tex.height },
      [tex.width, tex.height, depth],
    );
  }

  writeTextureRegion(
    texture: GpuTexture,
    origin: readonly [number, number, number],
    size: readonly [number, number, number],
    data: TextureData,
  ): void {
    this.assertNotDisposed();
    const tex = this.own(texture, WebGPUTexture, 'texture');
    checkTextureRegion(tex, origin, size);
    checkTextureData(tex.label, tex.format, size[0] * size[1] * size[2], data);
    if (this.lost) return;
    this.assertCurrent(tex, `texture "${tex.label}"`);
    if (!tex.handle) throw new RangeError(`texture "${tex.label}" was destroyed`);
    const view = data as
      Float32Array<ArrayBuffer> | Uint8Array<ArrayBuffer> | Uint16Array<ArrayBuffer> | Int16Array<ArrayBuffer>;
    this.state.device.queue.writeTexture(
      { texture: tex.handle, origin: [...origin] },
      view,
      { bytesPerRow: size[0] * formatInfo(tex.format).bytesPerTexel, rowsPerImage: size[1] },
      [...size],
    );
  }

  destroyTexture(texture: GpuTexture): void {
    if (this.disposed) return;
    const tex = this.own(texture, WebGPUTexture, 'texture');
    if (this.imported.has(tex)) return; // its owner destroys it
    this.textures.delete(tex);
    // Destroying a texture of a lost device is harmless, so stale objects need no special case.
    tex.destroy();
  }

  importTexture(handle: WebGLTexture | GPUTexture, width: number, height: number, label: string): GpuTexture {
    this.assertNotDisposed();
    checkTextureSize(label, '2d', width, height, 1, this.sizeLimits());
    // Bound as an unfilterable float texture (r32float's layout), which a depth32float texture allows.
    const tex = new WebGPUTexture('2d', width, height, 1, 'r32float', label, handle as GPUTexture, this.generation);
    this.imported.add(tex);
    return tex;
  }

  textureHandle(texture: GpuTexture): GPUTexture | null {
    return this.own(texture, WebGPUTexture, 'texture').handle;
  }

  // ——— render targets ———

  createRenderTarget(
    width: number,
    height: number,
    formats: readonly TextureFormat[],
    label = 'render target',
  ): RenderTarget {
    this.assertNotDisposed();
    checkTargetFormats(label, formats);
    formats.forEach((f) => formatInfo(f));
    this.checkColorAttachments(`Render target "${label}"`, formats);
    checkTextureSize(label, '2d', width, height, 1, this.sizeLimits());
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
      throw new VptError(
        'limit-exceeded',
        `Pass "${desc.label}" reads ${desc.textures.length} textures; this device allows ${limits.maxSampledTexturesPerShaderStage} (maxSampledTexturesPerShaderStage)`,
      );
    }
    checkPassOutputs(desc);
    desc.outputs.forEach((f) => formatInfo(f));
    this.checkColorAttachments(`Pass "${desc.label}"`, desc.outputs);
    if (desc.uniforms.byteSize > limits.maxUniformBufferBindingSize) {
      throw new VptError(
        'limit-exceeded',
        `Pass "${desc.label}" has a ${desc.uniforms.byteSize}-byte uniform struct; this device allows ${limits.maxUniformBufferBindingSize} (maxUniformBufferBindingSize)`,
      );
    }
    if (this.lost) return new WebGPUPass(desc, null, this.generation);
    return new WebGPUPass(desc, this.state.pipelines.get(desc), this.generation);
  }

  async compileAhead(descs: readonly PassDescriptor[]): Promise<void> {
    if (this.disposed || this.lost) return;
    try {
      await this.state.pipelines.compileAhead(descs);
    } catch {
      // A module or layout the device would not make: createPass reports it.
    }
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

    checkUniformBytes(desc, call);

    let width: number;
    let height: number;
    let views: GPUTextureView[];
    let pipeline: GPURenderPipeline;
    let targetTextures: readonly WebGPUTexture[] = [];
    if (call.target === 'canvas') {
      checkCanvasOutputs(desc);
      const current = this.context.getCurrentTexture();
      width = current.width;
      height = current.height;
      views = [current.createView()];
      // The canvas texture has the preferred format (often bgra8unorm), not rgba8unorm.
      pipeline = pipelines.pipeline(entry, [this.canvasFormat]);
    } else {
      const t = this.own(call.target, WebGPURenderTarget, 'render target');
      this.assertCurrent(t, `render target "${t.label}"`);
      checkTargetOutputs(desc, t);
      width = t.width;
      height = t.height;
      views = t.textures.map((tex) => tex.view());
      pipeline = pipelines.pipeline(entry, desc.outputs);
      targetTextures = t.textures;
    }

    const textureEntries: GPUBindGroupEntry[] = desc.textures.map((binding, k) => {
      const tex = this.own(givenTexture(desc, binding, call), WebGPUTexture, 'texture');
      this.assertCurrent(tex, `texture "${tex.label}"`);
      checkBoundTexture(desc, binding, tex, targetTextures);
      if (!tex.handle) throw new RangeError(`pass "${desc.label}": texture "${tex.label}" was destroyed`);
      return { binding: 1 + k, resource: tex.view() };
    });

    // One buffer holds the pass's uniforms at 0 and VptBuiltins at the next aligned offset.
    const userSize = desc.uniforms.byteSize;
    const builtinsOffset =
      Math.ceil(userSize / device.limits.minUniformBufferOffsetAlignment) *
      device.limits.minUniformBufferOffsetAlignment;
    const buffer = uniforms.acquire(builtinsOffset + BUILTINS_BYTE_SIZE);
    device.queue.writeBuffer(buffer, 0, call.uniforms, 0, userSize);
    device.queue.writeBuffer(buffer, builtinsOffset, new Int32Array([width, height, 0, 0]));

    device.pushErrorScope('validation');
    const group0 = device.createBindGroup({
      label: desc.label,
      layout: entry.bindGroupLayout,
      entries: [
        { binding: 0, resource: { buffer, offset: 0, size: userSize } },
        ...textureEntries,
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
    checkReadable(tex);
    if (this.lost) throw new VptError('context-lost', `Cannot read texture "${tex.label}": the WebGPU device is lost`);
    this.assertCurrent(tex, `texture "${tex.label}"`);
    if (!tex.handle) throw new RangeError(`readTexture: texture "${tex.label}" was destroyed`);
    const state = this.state;
    const { buffer, bytesPerRow } = submitReadback(
      state.device,
      tex.handle,
      tex.width,
      tex.height,
      tex.format,
      tex.label,
    );
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

  // ——— device loss ———

  simulateLoss(restoreAfterMs = 50): Promise<void> {
    if (this.disposed) return Promise.reject(new VptError('disposed', 'This WebGPU backend was disposed'));
    if (this.lost) return Promise.reject(new VptError('context-lost', 'The WebGPU device is already lost'));
    return new Promise<void>((resolve, reject) => {
      const timer = setTimeout(() => {
        this.restoreWaiters = this.restoreWaiters.filter((w) => w !== waiter);
        reject(
          new VptError(
            'context-lost',
            `No new WebGPU device within ${restoreAfterMs + RESTORE_TIMEOUT_MS} ms of the simulated loss`,
          ),
        );
      }, restoreAfterMs + RESTORE_TIMEOUT_MS);
      const waiter: Waiter = {
        resolve: () => {
          clearTimeout(timer);
          resolve();
        },
        reject: (e) => {
          clearTimeout(timer);
          reject(e);
        },
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
    runCallbacks(this.lostCallbacks, 'device-loss');
    // A shared device is its owner's to replace: vpt's context stays lost.
    if (this.shared) return;
    const delay = this.restoreDelayMs ?? 0;
    this.restoreDelayMs = null;
    if (info.reason !== 'destroyed')
      console.warn(`vpt: the WebGPU device was lost (${info.message}); requesting a new one`);
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
      const err = new VptError('context-lost', 'The WebGPU device was lost and no new device could be obtained', {
        cause: failure,
      });
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
    runCallbacks(this.restoredCallbacks, 'device-loss');
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
    if (!this.shared) this.state.device.destroy();
  }

  // ——— internals ———

  /** Set up per-device state and configure the canvas for a (new) device. */
  private attach(handle: GpuDeviceHandle): DeviceState {
    const device = handle.device;
    const errors = new DeferredErrors();
    const state: DeviceState = {
      device,
      pipelines: new PipelineCache(device, errors),
      uniforms: new UniformBufferPool(device),
      errors,
    };
    device.lost.then((info) => this.handleLost(state, info));
    device.addEventListener('uncapturederror', (event) => {
      console.error(`vpt: uncaptured WebGPU error: ${(event as GPUUncapturedErrorEvent).error.message}`);
    });
    this.context.configure({
      device,
      format: this.canvasFormat,
      alphaMode: 'premultiplied',
      usage: GPUTextureUsage.RENDER_ATTACHMENT,
    });
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

  private allocTexture(
    dimension: '2d' | '3d',
    width: number,
    height: number,
    depth: number,
    format: TextureFormat,
    label: string,
  ): WebGPUTexture {
    if (this.lost) return new WebGPUTexture(dimension, width, height, depth, format, label, null, this.generation);
    const handle = this.state.device.createTexture({
      label,
      dimension,
      format,
      size: [width, height, depth],
      usage: textureUsage(dimension),
    });
    return new WebGPUTexture(dimension, width, height, depth, format, label, handle, this.generation);
  }

  private upload(tex: WebGPUTexture, data: TextureData): void {
    if (!tex.handle) throw new RangeError(`texture "${tex.label}" was destroyed`);
    const bytesPerRow = tex.width * formatInfo(tex.format).bytesPerTexel;
    // The IDL takes [AllowShared] views; the typings only admit views over a plain ArrayBuffer.
    const view = data as
      Float32Array<ArrayBuffer> | Uint8Array<ArrayBuffer> | Uint16Array<ArrayBuffer> | Int16Array<ArrayBuffer>;
    this.state.device.queue.writeTexture({ texture: tex.handle }, view, { bytesPerRow, rowsPerImage: tex.height }, [
      tex.width,
      tex.height,
      tex.depth,
    ]);
  }

  private sizeLimits(): TextureSizeLimits {
    const limits = this.state.device.limits;
    return {
      max2D: limits.maxTextureDimension2D,
      max3D: limits.maxTextureDimension3D,
      name2D: 'maxTextureDimension2D',
      name3D: 'maxTextureDimension3D',
    };
  }

  private checkColorAttachments(what: string, formats: readonly TextureFormat[]): void {
    const limits = this.state.device.limits;
    if (formats.length > limits.maxColorAttachments) {
      throw new VptError(
        'limit-exceeded',
        `${what} has ${formats.length} colour attachments; this device allows ${limits.maxColorAttachments} (maxColorAttachments)`,
      );
    }
    const bytes = colorAttachmentBytesPerSample(formats);
    if (bytes > limits.maxColorAttachmentBytesPerSample) {
      throw new VptError(
        'limit-exceeded',
        `${what} writes ${bytes} bytes per pixel ([${formats.join(', ')}]); this device allows ${limits.maxColorAttachmentBytesPerSample} (maxColorAttachmentBytesPerSample)`,
      );
    }
  }

  private readFailure(label: string, state: DeviceState, cause?: unknown): VptError {
    if (this.disposed)
      return new VptError('disposed', `Reading texture "${label}" was cut short: the WebGPU backend was disposed`, {
        cause,
      });
    if (this.lost || this.state !== state)
      return new VptError('context-lost', `Reading texture "${label}" failed: the WebGPU device was lost`, { cause });
    return new VptError('context-lost', `Reading texture "${label}" failed: mapAsync was rejected`, { cause });
  }
}

function sleep(ms: number): Promise<void> {
  return new Promise((r) => setTimeout(r, ms));
}
