/** vpt texture formats → WebGL 2 (internal format, format, type) and their texel layout. */
import type { TextureFormat } from '../backend.js';

export interface GlFormat {
  internalFormat: number;
  format: number;
  type: number;
  /** Components per texel in the uploaded/read data. */
  channels: number;
  /** Float formats take/return Float32Array; rgba8unorm Uint8Array. */
  isFloat: boolean;
}

// WebGL 2 enum values (fixed by the spec), so this table needs no context to build.
const GL_RED = 0x1903;
const GL_RGBA = 0x1908;
const GL_FLOAT = 0x1406;
const GL_UNSIGNED_BYTE = 0x1401;
const GL_R32F = 0x822e;
const GL_RGBA32F = 0x8814;
const GL_RGBA8 = 0x8058;

const FORMATS: Record<TextureFormat, GlFormat> = {
  r32float: { internalFormat: GL_R32F, format: GL_RED, type: GL_FLOAT, channels: 1, isFloat: true },
  rgba32float: { internalFormat: GL_RGBA32F, format: GL_RGBA, type: GL_FLOAT, channels: 4, isFloat: true },
  rgba8unorm: { internalFormat: GL_RGBA8, format: GL_RGBA, type: GL_UNSIGNED_BYTE, channels: 4, isFloat: false },
};

export function glFormat(format: TextureFormat): GlFormat {
  const f = FORMATS[format];
  if (!f) throw new RangeError(`unknown texture format "${format}"`);
  return f;
}

/** Check that `data` has the right element type and length for a whole texture. */
export function checkTextureData(label: string, format: TextureFormat, texels: number, data: Float32Array | Uint8Array): void {
  const f = glFormat(format);
  if (f.isFloat && !(data instanceof Float32Array)) throw new TypeError(`texture "${label}" (${format}) needs a Float32Array`);
  if (!f.isFloat && !(data instanceof Uint8Array)) throw new TypeError(`texture "${label}" (${format}) needs a Uint8Array`);
  const expected = texels * f.channels;
  if (data.length !== expected) {
    throw new RangeError(`texture "${label}" (${format}) needs ${expected} values (${texels} texels x ${f.channels}), got ${data.length}`);
  }
}
