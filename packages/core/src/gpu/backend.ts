/**
 * The GPU backend interface. vpt's kernels are full-screen fragment passes: every
 * pass reads textures (with exact integer texel loads, never hardware filtering, so
 * both backends compute bit-identical results on SwiftShader) and writes one or more
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

/** Texture formats vpt uses. All are sampled with texelFetch / textureLoad. */
export type TextureFormat = 'r32float' | 'rgba32float' | 'rgba8unorm';

export interface TextureDescriptor {
  dimension: '2d' | '3d';
  width: number;
  height: number;
  /** 1 for 2D textures. */
  depth?: number;
  format: TextureFormat;
  /** Tightly packed texel data, x fastest, then y, then z. Float32Array for float formats, Uint8Array for rgba8unorm. */
  data?: Float32Array | Uint8Array;
  label?: string;
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
}

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
  readonly canvas: HTMLCanvasElement | OffscreenCanvas;

  createTexture(desc: TextureDescriptor): GpuTexture;
  /** Replace the whole content of a texture. */
  writeTexture(texture: GpuTexture, data: Float32Array | Uint8Array): void;
  destroyTexture(texture: GpuTexture): void;

  createRenderTarget(width: number, height: number, formats: readonly TextureFormat[], label?: string): RenderTarget;
  destroyRenderTarget(target: RenderTarget): void;

  /** Compile (or fetch from the cache) a pass. Throws VptError('shader-compile') with the log. */
  createPass(desc: PassDescriptor): GpuPass;
  /** Record and submit one full-screen draw. */
  draw(pass: GpuPass, call: DrawCall): void;

  /**
   * Read a whole 2D texture back, top row first, tightly packed.
   * Float32Array for float formats, Uint8Array for rgba8unorm. Waits for the GPU.
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
}

export interface BackendOptions {
  /** 'auto' picks WebGPU where offered, else WebGL 2. */
  backend?: BackendPreference;
  canvas?: HTMLCanvasElement | OffscreenCanvas;
  /** WebGPU only: ask the adapter for 'timestamp-query' when present. */
  powerPreference?: 'high-performance' | 'low-power';
}
