/**
 * The GPU backend interface. vpt's kernels are full-screen fragment passes: every
 * pass reads textures (with exact integer texel loads, so both backends compute
 * bit-identical results on SwiftShader; only the volume's fast sampling path uses the
 * texture unit's filter, see PassTextureBinding.filter) and writes one or more
 * colour targets. This tiny surface is all a renderer or post step needs, and it
 * maps one-to-one onto WebGL 2 (program + framebuffer + draw) and WebGPU (render
 * pipeline + render pass).
 *
 * Image convention inside vpt: texel (i, j) of every 2D target is pixel column i,
 * row j counted from the TOP of the image. Kernels get that pixel from the prelude
 * (`vptPixel()`), so readbacks come out top row first on both backends; only the
 * final presentation to a WebGL canvas flips rows (GL shows row 0 at the bottom).
 */
import type { UniformLayout } from '../uniforms/layout.js';

export type BackendKind = 'webgl2' | 'webgpu';
export type BackendPreference = BackendKind | 'auto';

/**
 * Texture formats vpt uses. Passes read them with texelFetch / textureLoad, except a
 * binding declared `filter: 'linear'` (the volume's fast path), read with one filtered fetch.
 * The 8/16-bit single-channel formats hold volumes (volume-format.ts): r8unorm, r16unorm /
 * r16snorm (WebGL 2 EXT_texture_norm16, WebGPU 'texture-formats-tier1'; see
 * BackendCapabilities.norm16) and r16float (everywhere; also a render target).
 */
export type TextureFormat =
  | 'r32float'
  | 'rgba32float'
  | 'rgba8unorm'
  | 'r8unorm'
  | 'r16unorm'
  | 'r16snorm'
  | 'r16float'
  // Multichannel volumes (scene/channels.ts): 2 or 4 components of the scalar formats above.
  | 'rg8unorm'
  | 'rg16unorm'
  | 'rgba16unorm'
  | 'rg16snorm'
  | 'rgba16snorm'
  | 'rg16float'
  | 'rgba16float'
  | 'rg32float';

/**
 * Texel data: Float32Array for r32float/rg32float/rgba32float, Uint8Array for
 * r8unorm/rg8unorm/rgba8unorm, Uint16Array for r16unorm/rg16unorm/rgba16unorm and for the
 * 16-bit floats (IEEE half bits), Int16Array for the 16-bit snorm formats; components interleaved.
 */
export type TextureData = Float32Array | Uint8Array | Uint16Array | Int16Array;

export interface TextureDescriptor {
  dimension: '2d' | '3d';
  width: number;
  height: number;
  /** 1 for 2D textures. */
  depth?: number;
  format: TextureFormat;
  /** Tightly packed texel data, x fastest, then y, then z (element type: see TextureData). */
  data?: TextureData;
  label?: string;
  /**
   * 'linear' lets passes read the texture with one filtered fetch (a binding with
   * `filter: 'linear'`); only for formats `BackendCapabilities.filterable` admits. Integer
   * texel loads work either way. Default 'nearest'.
   */
  filter?: 'nearest' | 'linear';
}

export interface GpuTexture {
  readonly dimension: '2d' | '3d';
  readonly width: number;
  readonly height: number;
  readonly depth: number;
  readonly format: TextureFormat;
  readonly label: string;
}

/** A set of colour attachments of equal size, written together by one pass (MRT). */
export interface RenderTarget {
  readonly width: number;
  readonly height: number;
  readonly textures: readonly GpuTexture[];
}

/** A texture a pass reads. `kind` picks the sampler type in the generated declarations. */
export interface PassTextureBinding {
  name: string;
  dimension: '2d' | '3d';
  /**
   * 'linear': the kernel may also read it with one filtered fetch: GLSL `texture(name, uvw)`
   * (the texture must have been made with `filter: 'linear'`), WGSL
   * `textureSampleLevel(name, vptLinearSampler, uvw, 0.0)` (the prelude declares the
   * clamp-to-edge linear sampler `vptLinearSampler` when any binding asks for it).
   */
  filter?: 'linear';
}

/**
 * A full-screen pass. The backend prepends a prelude to the kernel source:
 *
 * GLSL ES 3.0 prelude (then `source`, which must define `void main()`):
 *   #version 300 es, highp float/int/sampler3D/usampler…
 *   the uniform block from `uniforms.glslBlock('u')` (fields read as `u.name`)
 *   `uniform highp sampler2D <name>;` / `sampler3D` per texture
 *   `layout(location = k) out vec4 vpt_out<k>;` per output
 *   `ivec2 vptPixel()` — pixel (column, row-from-top) of this fragment
 *   `ivec2 vptTargetSize()` — the target's size in pixels
 *   `#define` lines from `defines`
 *
 * WGSL prelude (then `source`, which must define
 *   `@fragment fn fs_main(@builtin(position) fragCoord: vec4f) -> VptOut`):
 *   the struct from `uniforms.wgslStruct()` bound as `@group(0) @binding(0) var<uniform> u: <Struct>;`
 *   `@group(0) @binding(1 + k) var <name>: texture_2d<f32>;` / `texture_3d<f32>` per texture
 *   `struct VptOut { @location(k) out<k>: vec4f, … }`
 *   `fn vptPixel(fragCoord: vec4f) -> vec2i` and `fn vptTargetSize() -> vec2i`
 *   `const <NAME>: bool/i32/f32 = …;` for each entry of `defines` (booleans become `const NAME = true;`)
 * The target size is passed through a backend-owned uniform, not through `u`.
 */
export interface PassDescriptor {
  /** For error messages and the variant cache. */
  label: string;
  glsl: string;
  wgsl: string;
  uniforms: UniformLayout;
  textures: readonly PassTextureBinding[];
  /** Formats of the colour outputs, in location order. */
  outputs: readonly TextureFormat[];
  /** Compile-time specialisation (feature flags, constants). */
  defines?: Readonly<Record<string, boolean | number>>;
}

export interface GpuPass {
  readonly descriptor: PassDescriptor;
}

export interface DrawCall {
  /** Packed with `pass.descriptor.uniforms.pack(...)`. */
  uniforms: ArrayBuffer;
  /** One texture per `descriptor.textures` entry, by name. */
  textures: Readonly<Record<string, GpuTexture>>;
  /** Where to draw; `'canvas'` presents to the context's canvas (LDR, a single rgba8unorm output). */
  target: RenderTarget | 'canvas';
}

export interface BackendLimits {
  maxTextureDimension2D: number;
  maxTextureDimension3D: number;
  /** WebGPU's maxBufferSize (a hint of the device's memory class); undefined on WebGL 2, which reports none. */
  maxBufferSize?: number;
}

/** Optional formats and filtering the device offers. */
export interface BackendCapabilities {
  /** r16unorm / r16snorm textures (WebGL 2 EXT_texture_norm16; WebGPU 'texture-formats-tier1'). */
  norm16: boolean;
  /** r32float can be filtered (WebGL 2 OES_texture_float_linear; WebGPU 'float32-filterable'). */
  float32Filterable: boolean;
}

/** Whether a format can be read with a linear filter on a device with these capabilities. */
export function isFilterable(format: TextureFormat, caps: BackendCapabilities): boolean {
  if (format === 'r32float' || format === 'rg32float' || format === 'rgba32float') return caps.float32Filterable;
  return true;
}

/** The number of whole slices `texels` makes at zOffset of a 3D texture; throws when they do not fit. */
/** Checks that [origin, origin + size) is a non-empty box inside a 3D texture (writeTextureRegion). */
export function checkTextureRegion(
  tex: GpuTexture,
  origin: readonly [number, number, number],
  size: readonly [number, number, number],
): void {
  const ext = [tex.width, tex.height, tex.depth];
  const ok =
    tex.dimension === '3d' &&
    [0, 1, 2].every(
      (a) =>
        Number.isInteger(origin[a]) &&
        Number.isInteger(size[a]) &&
        origin[a] >= 0 &&
        size[a] >= 1 &&
        origin[a] + size[a] <= ext[a],
    );
  if (!ok)
    throw new RangeError(
      `texture "${tex.label}": the region at [${origin.join(', ')}] of size [${size.join(', ')}] is not inside its ${ext.join('x')} (${tex.dimension})`,
    );
}

export function sliceCount(tex: GpuTexture, zOffset: number, texels: number): number {
  const depth = texels / (tex.width * tex.height);
  if (
    tex.dimension !== '3d' ||
    !Number.isInteger(zOffset) ||
    zOffset < 0 ||
    !Number.isInteger(depth) ||
    depth < 1 ||
    zOffset + depth > tex.depth
  ) {
    throw new RangeError(
      `texture "${tex.label}": ${texels} texels at slice ${zOffset} are not whole slices inside its ${tex.width}x${tex.height}x${tex.depth} (${tex.dimension})`,
    );
  }
  return depth;
}

/** Bytes per texel of each format, as the device stores it (for the memory budget and stats). */
export const BYTES_PER_TEXEL: Readonly<Record<TextureFormat, number>> = {
  r32float: 4,
  rgba32float: 16,
  rgba8unorm: 4,
  r8unorm: 1,
  r16unorm: 2,
  r16snorm: 2,
  r16float: 2,
  rg8unorm: 2,
  rg16unorm: 4,
  rgba16unorm: 8,
  rg16snorm: 4,
  rgba16snorm: 8,
  rg16float: 4,
  rgba16float: 8,
  rg32float: 8,
};

export interface BackendInfo {
  kind: BackendKind;
  /** WebGL UNMASKED_RENDERER / WebGPU adapter description, for benchmark records. */
  renderer: string;
  vendor: string;
}

export interface GpuBackend {
  readonly kind: BackendKind;
  readonly info: BackendInfo;
  readonly limits: BackendLimits;
  readonly capabilities: BackendCapabilities;
  readonly canvas: HTMLCanvasElement | OffscreenCanvas;

  createTexture(desc: TextureDescriptor): GpuTexture;
  /** Replace the whole content of a texture. */
  writeTexture(texture: GpuTexture, data: TextureData): void;
  /**
   * Replace slices [zOffset, zOffset + data's depth) of a 3D texture (whole slices, tightly
   * packed): large volumes are converted and uploaded in slabs, so no full-size copy exists.
   */
  writeTextureSlices(texture: GpuTexture, zOffset: number, data: TextureData): void;
  /**
   * Replace the box [origin, origin + size) of a 3D texture (tightly packed, x fastest): the
   * brick cache writes one brick into its atlas slot (bricking/bricked-volume.ts).
   */
  writeTextureRegion(
    texture: GpuTexture,
    origin: readonly [number, number, number],
    size: readonly [number, number, number],
    data: TextureData,
  ): void;
  destroyTexture(texture: GpuTexture): void;

  createRenderTarget(width: number, height: number, formats: readonly TextureFormat[], label?: string): RenderTarget;
  destroyRenderTarget(target: RenderTarget): void;

  /** Compile (or fetch from the cache) a pass. Throws VptError('shader-compile') with the log. */
  createPass(desc: PassDescriptor): GpuPass;
  /**
   * Start compiling these passes all at once and resolve when the driver has finished them,
   * without blocking the thread: a later createPass of the same descriptor then finds the work
   * done. WebGL 2 compiles every shader, then links every program, and waits on
   * KHR_parallel_shader_compile's COMPLETION_STATUS_KHR; WebGPU creates the modules and
   * awaits createRenderPipelineAsync. Never rejects: a pass that fails to compile fails in
   * createPass, with the log, as before.
   */
  compileAhead(descs: readonly PassDescriptor[]): Promise<void>;
  /** Record and submit one full-screen draw. */
  draw(pass: GpuPass, call: DrawCall): void;

  /**
   * Read a whole 2D texture back, top row first, tightly packed.
   * Float32Array for float formats (r16float converted), Uint8Array for rgba8unorm. Waits for the GPU.
   */
  readTexture(texture: GpuTexture): Promise<Float32Array | Uint8Array>;
  /** Resolve when all submitted work has finished (a 1-texel readback on WebGL 2). */
  finish(): Promise<void>;

  /** Resize the canvas drawing buffer (in device pixels). */
  resizeCanvas(width: number, height: number): void;

  /**
   * Loss handling. `onLost` fires when the context/device is lost; every GpuTexture,
   * RenderTarget and GpuPass made before is then invalid. `onRestored` fires once the
   * backend can be used again (WebGL: after webglcontextrestored; WebGPU: after a new
   * device was requested); the owner re-creates its resources.
   */
  onLost(callback: () => void): void;
  onRestored(callback: () => void): void;
  readonly isLost: boolean;

  /** Test hook: force a loss (WEBGL_lose_context / GPUDevice.destroy) and, after `restoreAfterMs`, a restore. */
  simulateLoss(restoreAfterMs?: number): Promise<void>;

  /** Free every GPU resource this backend made. */
  dispose(): void;

  /**
   * A 2D texture made by someone else on the same context or device (a shared one,
   * BackendOptions.gl or .device): a WebGLTexture on WebGL 2, a GPUTexture on WebGPU. It is
   * bound like this backend's own, read as an unfilterable float texture (a depth texture
   * reads its depth), never written or destroyed by it.
   */
  importTexture?(handle: WebGLTexture | GPUTexture, width: number, height: number, label: string): GpuTexture;
  /** The native texture behind one of this backend's textures: WebGLTexture on WebGL 2, GPUTexture on WebGPU. */
  textureHandle?(texture: GpuTexture): WebGLTexture | GPUTexture | null;
}

export interface BackendOptions {
  /** 'auto' picks WebGPU where offered, else WebGL 2. */
  backend?: BackendPreference;
  canvas?: HTMLCanvasElement | OffscreenCanvas;
  /** WebGPU only: ask the adapter for 'timestamp-query' when present. */
  powerPreference?: 'high-performance' | 'low-power';
  /**
   * WebGL 2 only: draw on this existing context (one shared with another renderer, such as
   * three.js's WebGLRenderer) instead of acquiring one from `canvas`. The backend then sets
   * the GL state it relies on before each use, never resizes the canvas and never loses the
   * context on dispose; the other renderer must reset its own state cache afterwards.
   */
  gl?: WebGL2RenderingContext;
  /**
   * WebGPU only: draw on this existing GPUDevice (one shared with another renderer, such as
   * three.js's WebGPURenderer) instead of requesting one. The backend never destroys it, and
   * does not replace it after a loss (the owner does). Its limits are the owner's: vpt's MRT
   * passes need maxColorAttachmentBytesPerSample of at least 48 (64 with denoiser guides).
   */
  device?: GPUDevice;
}
