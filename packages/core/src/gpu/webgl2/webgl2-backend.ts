/**
 * The WebGL 2 implementation of GpuBackend: textures, MRT render targets, full-screen
 * passes (one buffer-less triangle per draw), readback, and context-loss handling.
 */
import { VptError } from '../../errors.js';
import type {
  BackendCapabilities,
  BackendInfo,
  BackendLimits,
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
import { checkTextureRegion, sliceCount } from '../backend.js';
import { type GlLimits, acquireContext, readInfo, readLimits, requireColorBufferFloat } from './context-setup.js';
import { ProgramCache, UNIFORM_BLOCK_BINDING } from './program-cache.js';
import { WebGL2Pass, WebGL2RenderTarget, WebGL2Texture } from './resources.js';
import { checkTextureData, glFormat } from './texture-formats.js';
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

export function createWebGL2Backend(
  canvas: HTMLCanvasElement | OffscreenCanvas,
  shared?: WebGL2RenderingContext,
): GpuBackend {
  return new WebGL2Backend(canvas, shared);
}

/** How long simulateLoss() waits for the browser to restore the context before giving up. */
const RESTORE_TIMEOUT_MS = 10_000;

interface Waiter {
  resolve: () => void;
  reject: (e: unknown) => void;
}

class WebGL2Backend extends BackendBase implements GpuBackend {
  readonly kind = 'webgl2' as const;
  readonly info: BackendInfo;
  private readonly gl: WebGL2RenderingContext;
  private glLimits: GlLimits;
  private caps: BackendCapabilities = { norm16: false, float32Filterable: false };
  private lost = false;
  private readonly programs: ProgramCache;
  private readonly textures = new Set<WebGL2Texture>();
  private readonly targets = new Set<WebGL2RenderTarget>();
  private readFramebuffer: WebGLFramebuffer | null = null;
  private syncTarget: { texture: WebGLTexture; framebuffer: WebGLFramebuffer } | null = null;
  private readonly syncPixel = new Uint8Array(4);
  private vao: WebGLVertexArrayObject | null = null;
  private loseContextExt: WEBGL_lose_context | null = null;
  private restoreWaiters: Waiter[] = [];

  /** Drawing on a context someone else owns (BackendOptions.gl): state is set before each use. */
  private readonly shared: boolean;
  private readonly imported = new WeakSet<WebGL2Texture>();

  constructor(
    readonly canvas: HTMLCanvasElement | OffscreenCanvas,
    sharedGl?: WebGL2RenderingContext,
  ) {
    super({ backend: 'WebGL 2', lossTarget: 'WebGL context' });
    this.shared = sharedGl !== undefined;
    const gl = sharedGl ?? acquireContext(canvas);
    if (gl.isContextLost())
      throw new VptError('context-lost', 'The WebGL 2 context was lost as soon as it was created');
    requireColorBufferFloat(gl);
    this.gl = gl;
    this.info = readInfo(gl);
    this.glLimits = readLimits(gl);
    this.programs = new ProgramCache(gl);
    this.initState();
    const events = canvas as EventTarget;
    events.addEventListener('webglcontextlost', this.handleLost);
    events.addEventListener('webglcontextrestored', this.handleRestored);
  }

  get limits(): BackendLimits {
    return {
      maxTextureDimension2D: this.glLimits.maxTextureDimension2D,
      maxTextureDimension3D: this.glLimits.maxTextureDimension3D,
    };
  }

  get capabilities(): BackendCapabilities {
    return this.caps;
  }

  get isLost(): boolean {
    return this.lost || this.gl.isContextLost();
  }

  // ——— textures ———

  createTexture(desc: TextureDescriptor): GpuTexture {
    this.assertNotDisposed();
    this.enterShared();
    const { label, depth } = textureLabelAndDepth(desc);
    checkTextureSize(label, desc.dimension, desc.width, desc.height, depth, this.sizeLimits());
    if (desc.data) checkTextureData(label, desc.format, desc.width * desc.height * depth, desc.data);
    checkTextureCapabilities(label, desc, this.caps, {
      norm16: 'EXT_texture_norm16',
      float32Filterable: 'OES_texture_float_linear',
    });
    const linear = desc.filter === 'linear';
    const tex = this.allocTexture(
      desc.dimension,
      desc.width,
      desc.height,
      depth,
      desc.format,
      label,
      desc.data ?? null,
      linear,
    );
    this.textures.add(tex);
    return tex;
  }

  writeTexture(texture: GpuTexture, data: TextureData): void {
    this.assertNotDisposed();
    this.enterShared();
    const tex = this.own(texture, WebGL2Texture, 'texture');
    checkTextureData(tex.label, tex.format, tex.width * tex.height * tex.depth, data);
    if (this.isLost) return;
    this.assertCurrent(tex, `texture "${tex.label}"`);
    const gl = this.gl;
    const f = glFormat(tex.format);
    if (tex.dimension === '3d') {
      gl.bindTexture(gl.TEXTURE_3D, tex.handle);
      gl.texSubImage3D(gl.TEXTURE_3D, 0, 0, 0, 0, tex.width, tex.height, tex.depth, f.format, f.type, data);
    } else {
      gl.bindTexture(gl.TEXTURE_2D, tex.handle);
      gl.texSubImage2D(gl.TEXTURE_2D, 0, 0, 0, tex.width, tex.height, f.format, f.type, data);
    }
  }

  writeTextureSlices(texture: GpuTexture, zOffset: number, data: TextureData): void {
    this.assertNotDisposed();
    this.enterShared();
    const tex = this.own(texture, WebGL2Texture, 'texture');
    const depth = sliceCount(tex, zOffset, data.length / glFormat(tex.format).channels);
    checkTextureData(tex.label, tex.format, tex.width * tex.height * depth, data);
    if (this.isLost) return;
    this.assertCurrent(tex, `texture "${tex.label}"`);
    const gl = this.gl;
    const f = glFormat(tex.format);
    gl.bindTexture(gl.TEXTURE_3D, tex.handle);
    gl.texSubImage3D(gl.TEXTURE_3D, 0, 0, 0, zOffset, tex.width, tex.height, depth, f.format, f.type, data);
  }

  writeTextureRegion(
    texture: GpuTexture,
    origin: readonly [number, number, number],
    size: readonly [number, number, number],
    data: TextureData,
  ): void {
    this.assertNotDisposed();
    this.enterShared();
    const tex = this.own(texture, WebGL2Texture, 'texture');
    checkTextureRegion(tex, origin, size);
    checkTextureData(tex.label, tex.format, size[0] * size[1] * size[2], data);
    if (this.isLost) return;
    this.assertCurrent(tex, `texture "${tex.label}"`);
    const gl = this.gl;
    const f = glFormat(tex.format);
    gl.bindTexture(gl.TEXTURE_3D, tex.handle);
    gl.texSubImage3D(gl.TEXTURE_3D, 0, ...origin, ...size, f.format, f.type, data);
  }

  destroyTexture(texture: GpuTexture): void {
    if (this.disposed) return;
    const tex = this.own(texture, WebGL2Texture, 'texture');
    if (this.imported.has(tex)) return; // its owner deletes it
    this.textures.delete(tex);
    this.deleteTexture(tex);
  }

  importTexture(handle: WebGLTexture | GPUTexture, width: number, height: number, label: string): GpuTexture {
    this.assertNotDisposed();
    checkTextureSize(label, '2d', width, height, 1, this.sizeLimits());
    // Its format is the owner's; the kernels read it as a float sampler with texelFetch.
    const tex = new WebGL2Texture('2d', width, height, 1, 'r32float', label, handle as WebGLTexture, this.generation);
    this.imported.add(tex);
    return tex;
  }

  textureHandle(texture: GpuTexture): WebGLTexture | null {
    return this.own(texture, WebGL2Texture, 'texture').handle;
  }

  // ——— render targets ———

  createRenderTarget(
    width: number,
    height: number,
    formats: readonly TextureFormat[],
    label = 'render target',
  ): RenderTarget {
    this.assertNotDisposed();
    this.enterShared();
    checkTargetFormats(label, formats);
    if (formats.length > this.glLimits.maxColorAttachments) {
      throw new VptError(
        'limit-exceeded',
        `Render target "${label}" has ${formats.length} colour attachments; this device allows ${this.glLimits.maxColorAttachments} (MAX_COLOR_ATTACHMENTS / MAX_DRAW_BUFFERS)`,
      );
    }
    checkTextureSize(label, '2d', width, height, 1, this.sizeLimits());
    const textures = formats.map((f, k) =>
      this.allocTexture('2d', width, height, 1, f, `${label} [${k}]`, null, false),
    );
    if (this.isLost) return new WebGL2RenderTarget(width, height, textures, label, null, this.generation);

    const gl = this.gl;
    const framebuffer = gl.createFramebuffer();
    gl.bindFramebuffer(gl.DRAW_FRAMEBUFFER, framebuffer);
    textures.forEach((t, k) =>
      gl.framebufferTexture2D(gl.DRAW_FRAMEBUFFER, gl.COLOR_ATTACHMENT0 + k, gl.TEXTURE_2D, t.handle, 0),
    );
    gl.drawBuffers(textures.map((_, k) => gl.COLOR_ATTACHMENT0 + k));
    const status = gl.checkFramebufferStatus(gl.DRAW_FRAMEBUFFER);
    gl.bindFramebuffer(gl.DRAW_FRAMEBUFFER, null);
    if (status !== gl.FRAMEBUFFER_COMPLETE && !gl.isContextLost()) {
      gl.deleteFramebuffer(framebuffer);
      textures.forEach((t) => this.deleteTexture(t));
      throw new VptError(
        'missing-extension',
        `Render target "${label}" (${formats.join(', ')}, ${width}x${height}) cannot be rendered to on this device: framebuffer status 0x${status.toString(16)}`,
      );
    }
    const target = new WebGL2RenderTarget(width, height, textures, label, framebuffer, this.generation);
    this.targets.add(target);
    return target;
  }

  destroyRenderTarget(target: RenderTarget): void {
    if (this.disposed) return;
    const t = this.own(target, WebGL2RenderTarget, 'render target');
    this.targets.delete(t);
    this.deleteTarget(t);
  }

  // ——— passes ———

  createPass(desc: PassDescriptor): GpuPass {
    this.assertNotDisposed();
    this.enterShared();
    if (desc.textures.length > this.glLimits.maxTextureUnits) {
      throw new VptError(
        'limit-exceeded',
        `Pass "${desc.label}" reads ${desc.textures.length} textures; this device allows ${this.glLimits.maxTextureUnits} (MAX_TEXTURE_IMAGE_UNITS)`,
      );
    }
    checkPassOutputs(desc);
    if (desc.outputs.length > this.glLimits.maxColorAttachments) {
      throw new VptError(
        'limit-exceeded',
        `Pass "${desc.label}" writes ${desc.outputs.length} outputs; this device allows 1 to ${this.glLimits.maxColorAttachments} (MAX_DRAW_BUFFERS)`,
      );
    }
    if (desc.uniforms.byteSize > this.glLimits.maxUniformBlockSize) {
      throw new VptError(
        'limit-exceeded',
        `Pass "${desc.label}" has a ${desc.uniforms.byteSize}-byte uniform block; this device allows ${this.glLimits.maxUniformBlockSize} (MAX_UNIFORM_BLOCK_SIZE)`,
      );
    }
    if (this.isLost) return new WebGL2Pass(desc, null, this.generation);
    return new WebGL2Pass(desc, this.programs.get(desc), this.generation);
  }

  async compileAhead(descs: readonly PassDescriptor[]): Promise<void> {
    if (this.disposed || this.isLost) return;
    this.enterShared();
    try {
      await this.programs.compileAhead(descs);
    } catch {
      // A shader or program object the driver would not make: createPass reports it.
    }
  }

  draw(pass: GpuPass, call: DrawCall): void {
    this.assertNotDisposed();
    this.enterShared();
    if (this.isLost) return; // nothing can be drawn; the owner redraws after onRestored
    const p = this.own(pass, WebGL2Pass, 'pass');
    const desc = p.descriptor;
    this.assertCurrent(p, `pass "${desc.label}"`);
    const gl = this.gl;

    let width: number;
    let height: number;
    let flipY: number;
    let targetTextures: readonly WebGL2Texture[] = [];
    if (call.target === 'canvas') {
      checkCanvasOutputs(desc);
      gl.bindFramebuffer(gl.DRAW_FRAMEBUFFER, null);
      // The drawing buffer is the canvas size unless the browser had to clamp it.
      width = gl.drawingBufferWidth;
      height = gl.drawingBufferHeight;
      flipY = 1;
    } else {
      const t = this.own(call.target, WebGL2RenderTarget, 'render target');
      this.assertCurrent(t, `render target "${t.label}"`);
      checkTargetOutputs(desc, t);
      gl.bindFramebuffer(gl.DRAW_FRAMEBUFFER, t.framebuffer);
      width = t.width;
      height = t.height;
      flipY = 0;
      targetTextures = t.textures;
    }
    gl.viewport(0, 0, width, height);

    const prog = p.program!;
    gl.useProgram(prog.program);
    gl.uniform2i(prog.targetSize, width, height);
    gl.uniform1i(prog.flipY, flipY);

    if (prog.ubo) {
      checkUniformBytes(desc, call);
      gl.bindBuffer(gl.UNIFORM_BUFFER, prog.ubo);
      if (prog.uboSize === call.uniforms.byteLength) gl.bufferSubData(gl.UNIFORM_BUFFER, 0, call.uniforms);
      else {
        gl.bufferData(gl.UNIFORM_BUFFER, call.uniforms, gl.DYNAMIC_DRAW);
        prog.uboSize = call.uniforms.byteLength;
      }
      gl.bindBufferBase(gl.UNIFORM_BUFFER, UNIFORM_BLOCK_BINDING, prog.ubo);
    }

    desc.textures.forEach((binding, k) => {
      const tex = this.own(givenTexture(desc, binding, call), WebGL2Texture, 'texture');
      this.assertCurrent(tex, `texture "${tex.label}"`);
      checkBoundTexture(desc, binding, tex, targetTextures);
      gl.activeTexture(gl.TEXTURE0 + k);
      gl.bindTexture(tex.dimension === '3d' ? gl.TEXTURE_3D : gl.TEXTURE_2D, tex.handle);
    });

    gl.bindVertexArray(this.vao);
    gl.drawArrays(gl.TRIANGLES, 0, 3);
  }

  // ——— readback and sync ———

  async readTexture(texture: GpuTexture): Promise<Float32Array | Uint8Array> {
    this.assertNotDisposed();
    this.enterShared();
    const tex = this.own(texture, WebGL2Texture, 'texture');
    checkReadable(tex);
    if (this.isLost)
      throw new VptError('context-lost', `Cannot read texture "${tex.label}": the WebGL context is lost`);
    this.assertCurrent(tex, `texture "${tex.label}"`);
    const gl = this.gl;
    this.readFramebuffer ??= gl.createFramebuffer();
    gl.bindFramebuffer(gl.READ_FRAMEBUFFER, this.readFramebuffer);
    gl.framebufferTexture2D(gl.READ_FRAMEBUFFER, gl.COLOR_ATTACHMENT0, gl.TEXTURE_2D, tex.handle, 0);
    gl.readBuffer(gl.COLOR_ATTACHMENT0);
    const { width, height } = tex;
    const f = glFormat(tex.format);
    // GL returns row y = 0 first; texel row 0 is vpt's top row, so no flip is needed.
    let out: Float32Array | Uint8Array;
    if (f.readsAsFloat) {
      // RGBA/FLOAT is the one float read combination every float colour buffer supports.
      const rgba = new Float32Array(width * height * 4);
      gl.readPixels(0, 0, width, height, gl.RGBA, gl.FLOAT, rgba);
      if (f.channels === 1) {
        out = new Float32Array(width * height);
        for (let i = 0; i < out.length; i++) out[i] = rgba[4 * i];
      } else out = rgba;
    } else {
      out = new Uint8Array(width * height * 4);
      gl.readPixels(0, 0, width, height, gl.RGBA, gl.UNSIGNED_BYTE, out);
    }
    gl.framebufferTexture2D(gl.READ_FRAMEBUFFER, gl.COLOR_ATTACHMENT0, gl.TEXTURE_2D, null, 0);
    gl.bindFramebuffer(gl.READ_FRAMEBUFFER, null);
    if (gl.isContextLost())
      throw new VptError('context-lost', `Reading texture "${tex.label}" failed: the WebGL context was lost`);
    return out;
  }

  async finish(): Promise<void> {
    this.assertNotDisposed();
    this.enterShared();
    if (this.isLost) return;
    // gl.finish() returns at once in Chrome; a readPixels must wait for all queued work.
    const gl = this.gl;
    if (!this.syncTarget) {
      const texture = gl.createTexture()!;
      gl.bindTexture(gl.TEXTURE_2D, texture);
      gl.texImage2D(gl.TEXTURE_2D, 0, gl.RGBA8, 1, 1, 0, gl.RGBA, gl.UNSIGNED_BYTE, null);
      const framebuffer = gl.createFramebuffer()!;
      gl.bindFramebuffer(gl.READ_FRAMEBUFFER, framebuffer);
      gl.framebufferTexture2D(gl.READ_FRAMEBUFFER, gl.COLOR_ATTACHMENT0, gl.TEXTURE_2D, texture, 0);
      this.syncTarget = { texture, framebuffer };
    }
    gl.bindFramebuffer(gl.READ_FRAMEBUFFER, this.syncTarget.framebuffer);
    gl.readBuffer(gl.COLOR_ATTACHMENT0);
    gl.readPixels(0, 0, 1, 1, gl.RGBA, gl.UNSIGNED_BYTE, this.syncPixel);
    gl.bindFramebuffer(gl.READ_FRAMEBUFFER, null);
  }

  // ——— context loss ———

  simulateLoss(restoreAfterMs = 50): Promise<void> {
    if (this.disposed) return Promise.reject(new VptError('disposed', 'This WebGL 2 backend was disposed'));
    const ext = this.loseContextExt;
    if (!ext)
      return Promise.reject(
        new VptError('missing-extension', 'WEBGL_lose_context is not available, so a context loss cannot be simulated'),
      );
    if (this.isLost) return Promise.reject(new VptError('context-lost', 'The WebGL context is already lost'));
    return new Promise<void>((resolve, reject) => {
      const timer = setTimeout(() => {
        this.restoreWaiters = this.restoreWaiters.filter((w) => w !== waiter);
        reject(
          new VptError(
            'context-lost',
            `The WebGL context was not restored within ${restoreAfterMs + RESTORE_TIMEOUT_MS} ms`,
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
      // Registered after handleLost, so preventDefault() (which makes the context restorable) has run.
      (this.canvas as EventTarget).addEventListener(
        'webglcontextlost',
        () => {
          setTimeout(() => {
            try {
              ext.restoreContext();
            } catch (e) {
              this.restoreWaiters = this.restoreWaiters.filter((w) => w !== waiter);
              waiter.reject(new VptError('context-lost', 'WEBGL_lose_context.restoreContext() failed', { cause: e }));
            }
          }, restoreAfterMs);
        },
        { once: true },
      );
      ext.loseContext();
    });
  }

  override resizeCanvas(width: number, height: number): void {
    // A shared canvas belongs to its owner; vpt renders into its own targets of any size.
    if (this.shared) {
      this.assertNotDisposed();
      return;
    }
    super.resizeCanvas(width, height);
  }

  private readonly handleLost = (event: Event): void => {
    // Without preventDefault the browser never restores the context.
    event.preventDefault();
    if (this.disposed) return;
    this.lost = true;
    runCallbacks(this.lostCallbacks);
  };

  private readonly handleRestored = (): void => {
    if (this.disposed) return;
    // Every GL object is gone: forget them (no deletes) and make new shared state.
    this.generation++;
    this.programs.forget();
    this.textures.clear();
    this.targets.clear();
    this.readFramebuffer = null;
    this.syncTarget = null;
    this.vao = null;
    const waiters = this.restoreWaiters;
    this.restoreWaiters = [];
    try {
      requireColorBufferFloat(this.gl);
    } catch (e) {
      waiters.forEach((w) => w.reject(e));
      return; // stays lost: a restored context without float targets cannot run vpt
    }
    this.glLimits = readLimits(this.gl);
    this.initState();
    this.lost = false;
    runCallbacks(this.restoredCallbacks);
    waiters.forEach((w) => w.resolve());
  };

  // ——— disposal ———

  dispose(): void {
    if (this.disposed) return;
    const events = this.canvas as EventTarget;
    events.removeEventListener('webglcontextlost', this.handleLost);
    events.removeEventListener('webglcontextrestored', this.handleRestored);
    if (!this.isLost) {
      const gl = this.gl;
      this.textures.forEach((t) => this.deleteTexture(t));
      this.targets.forEach((t) => this.deleteTarget(t));
      this.programs.deleteAll();
      gl.deleteFramebuffer(this.readFramebuffer);
      if (this.syncTarget) {
        gl.deleteFramebuffer(this.syncTarget.framebuffer);
        gl.deleteTexture(this.syncTarget.texture);
      }
      gl.deleteVertexArray(this.vao);
    }
    this.textures.clear();
    this.targets.clear();
    this.programs.forget();
    this.readFramebuffer = null;
    this.syncTarget = null;
    this.vao = null;
    this.disposed = true;
    this.restoreWaiters.forEach((w) => w.reject(new VptError('disposed', 'The WebGL 2 backend was disposed')));
    this.restoreWaiters = [];
    // Give the driver's memory back now rather than when the canvas is collected (not a
    // shared context: its owner still draws on it).
    if (!this.shared) this.loseContextExt?.loseContext();
    this.loseContextExt = null;
  }

  // ——— internals ———

  /**
   * On a shared context, the state every pass and upload relies on (initState's, and the
   * defaults of what another renderer such as three.js changes: pixel-store flags, masks,
   * unpack buffer), set before each use; the owner resets its state cache after vpt drew.
   */
  private enterShared(): void {
    if (!this.shared || this.isLost) return;
    const gl = this.gl;
    gl.pixelStorei(gl.UNPACK_ALIGNMENT, 1);
    gl.pixelStorei(gl.PACK_ALIGNMENT, 1);
    gl.pixelStorei(gl.UNPACK_FLIP_Y_WEBGL, false);
    gl.pixelStorei(gl.UNPACK_PREMULTIPLY_ALPHA_WEBGL, false);
    gl.pixelStorei(gl.UNPACK_COLORSPACE_CONVERSION_WEBGL, gl.NONE);
    gl.pixelStorei(gl.UNPACK_ROW_LENGTH, 0);
    gl.pixelStorei(gl.UNPACK_IMAGE_HEIGHT, 0);
    gl.pixelStorei(gl.UNPACK_SKIP_ROWS, 0);
    gl.pixelStorei(gl.UNPACK_SKIP_PIXELS, 0);
    gl.pixelStorei(gl.UNPACK_SKIP_IMAGES, 0);
    gl.bindBuffer(gl.PIXEL_UNPACK_BUFFER, null);
    gl.bindBuffer(gl.PIXEL_PACK_BUFFER, null);
    gl.disable(gl.BLEND);
    gl.disable(gl.DEPTH_TEST);
    gl.disable(gl.STENCIL_TEST);
    gl.disable(gl.SCISSOR_TEST);
    gl.disable(gl.CULL_FACE);
    gl.disable(gl.DITHER);
    gl.disable(gl.SAMPLE_ALPHA_TO_COVERAGE);
    gl.disable(gl.POLYGON_OFFSET_FILL);
    gl.disable(gl.RASTERIZER_DISCARD);
    gl.colorMask(true, true, true, true);
  }

  /** State every pass relies on; set at creation and again after a restore. */
  private initState(): void {
    const gl = this.gl;
    gl.pixelStorei(gl.UNPACK_ALIGNMENT, 1);
    gl.pixelStorei(gl.PACK_ALIGNMENT, 1);
    // Passes overwrite every pixel with exact values: no blending, tests or dithering.
    gl.disable(gl.BLEND);
    gl.disable(gl.DEPTH_TEST);
    gl.disable(gl.STENCIL_TEST);
    gl.disable(gl.SCISSOR_TEST);
    gl.disable(gl.CULL_FACE);
    gl.disable(gl.DITHER);
    // The full-screen triangle reads no attributes; an empty VAO keeps it independent of other state.
    this.vao = gl.createVertexArray();
    this.loseContextExt = gl.getExtension('WEBGL_lose_context');
    // Optional: compact 16-bit volumes and filtered float volumes (see BackendCapabilities).
    this.caps = {
      norm16: !!gl.getExtension('EXT_texture_norm16'),
      float32Filterable: !!gl.getExtension('OES_texture_float_linear'),
    };
  }

  private allocTexture(
    dimension: '2d' | '3d',
    width: number,
    height: number,
    depth: number,
    format: TextureFormat,
    label: string,
    data: TextureData | null,
    linear: boolean,
  ): WebGL2Texture {
    if (this.isLost) return new WebGL2Texture(dimension, width, height, depth, format, label, null, this.generation);
    const gl = this.gl;
    const f = glFormat(format);
    const target = dimension === '3d' ? gl.TEXTURE_3D : gl.TEXTURE_2D;
    const handle = gl.createTexture();
    gl.bindTexture(target, handle);
    // texelFetch ignores the filter; NEAREST also keeps R32F/RGBA32F complete without
    // OES_texture_float_linear. LINEAR (no mipmaps) for textures read by texture().
    const filter = linear ? gl.LINEAR : gl.NEAREST;
    gl.texParameteri(target, gl.TEXTURE_MIN_FILTER, filter);
    gl.texParameteri(target, gl.TEXTURE_MAG_FILTER, filter);
    gl.texParameteri(target, gl.TEXTURE_WRAP_S, gl.CLAMP_TO_EDGE);
    gl.texParameteri(target, gl.TEXTURE_WRAP_T, gl.CLAMP_TO_EDGE);
    if (dimension === '3d') {
      gl.texParameteri(target, gl.TEXTURE_WRAP_R, gl.CLAMP_TO_EDGE);
      gl.texImage3D(target, 0, f.internalFormat, width, height, depth, 0, f.format, f.type, data);
    } else {
      gl.texImage2D(target, 0, f.internalFormat, width, height, 0, f.format, f.type, data);
    }
    gl.bindTexture(target, null);
    return new WebGL2Texture(dimension, width, height, depth, format, label, handle, this.generation);
  }

  private sizeLimits(): TextureSizeLimits {
    return {
      max2D: this.glLimits.maxTextureDimension2D,
      max3D: this.glLimits.maxTextureDimension3D,
      name2D: 'MAX_TEXTURE_SIZE',
      name3D: 'MAX_3D_TEXTURE_SIZE',
    };
  }

  private deleteTexture(tex: WebGL2Texture): void {
    // Objects of an older generation died with the lost context.
    if (tex.handle && tex.generation === this.generation && !this.isLost) this.gl.deleteTexture(tex.handle);
    tex.handle = null;
  }

  private deleteTarget(t: WebGL2RenderTarget): void {
    if (t.framebuffer && t.generation === this.generation && !this.isLost) this.gl.deleteFramebuffer(t.framebuffer);
    t.framebuffer = null;
    t.textures.forEach((tex) => this.deleteTexture(tex));
  }
}
