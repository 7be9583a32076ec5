/** vpt texture formats → WebGL 2 (internal format, format, type) and their texel layout. */
import type { TextureData, TextureFormat } from '../backend.js';

export interface GlFormat {
  internalFormat: number;
  format: number;
  type: number;
  /** Components per texel in the uploaded/read data. */
  channels: number;
  /** The typed array uploads take (see TextureData). */
  array: typeof Float32Array | typeof Uint8Array | typeof Uint16Array | typeof Int16Array;
  /** Read back as floats (RGBA/FLOAT readPixels); otherwise as RGBA8 bytes. */
  readsAsFloat: boolean;
}

// WebGL 2 enum values (fixed by the spec), so this table needs no context to build.
const GL_RED = 0x1903;
const GL_RG = 0x8227;
const GL_RG8 = 0x822b;
const GL_RG16F = 0x822f;
const GL_RG32F = 0x8230;
const GL_RGBA16F = 0x881a;
const GL_RGBA = 0x1908;
const GL_FLOAT = 0x1406;
const GL_HALF_FLOAT = 0x140b;
const GL_UNSIGNED_BYTE = 0x1401;
const GL_UNSIGNED_SHORT = 0x1403;
const GL_SHORT = 0x1402;
const GL_R32F = 0x822e;
const GL_R16F = 0x822d;
const GL_R8 = 0x8229;
const GL_RGBA32F = 0x8814;
const GL_RGBA8 = 0x8058;
// EXT_texture_norm16.
const GL_R16_EXT = 0x822a;
const GL_R16_SNORM_EXT = 0x8f98;
const GL_RG16_EXT = 0x822c;
const GL_RGBA16_EXT = 0x805b;
const GL_RG16_SNORM_EXT = 0x8f99;
const GL_RGBA16_SNORM_EXT = 0x8f9b;

const FORMATS: Record<TextureFormat, GlFormat> = {
  r32float: {
    internalFormat: GL_R32F,
    format: GL_RED,
    type: GL_FLOAT,
    channels: 1,
    array: Float32Array,
    readsAsFloat: true,
  },
  rgba32float: {
    internalFormat: GL_RGBA32F,
    format: GL_RGBA,
    type: GL_FLOAT,
    channels: 4,
    array: Float32Array,
    readsAsFloat: true,
  },
  rgba8unorm: {
    internalFormat: GL_RGBA8,
    format: GL_RGBA,
    type: GL_UNSIGNED_BYTE,
    channels: 4,
    array: Uint8Array,
    readsAsFloat: false,
  },
  r8unorm: {
    internalFormat: GL_R8,
    format: GL_RED,
    type: GL_UNSIGNED_BYTE,
    channels: 1,
    array: Uint8Array,
    readsAsFloat: true,
  },
  r16float: {
    internalFormat: GL_R16F,
    format: GL_RED,
    type: GL_HALF_FLOAT,
    channels: 1,
    array: Uint16Array,
    readsAsFloat: true,
  },
  r16unorm: {
    internalFormat: GL_R16_EXT,
    format: GL_RED,
    type: GL_UNSIGNED_SHORT,
    channels: 1,
    array: Uint16Array,
    readsAsFloat: true,
  },
  r16snorm: {
    internalFormat: GL_R16_SNORM_EXT,
    format: GL_RED,
    type: GL_SHORT,
    channels: 1,
    array: Int16Array,
    readsAsFloat: true,
  },
  // Multichannel volumes: only uploaded and sampled, never read back.
  rg8unorm: {
    internalFormat: GL_RG8,
    format: GL_RG,
    type: GL_UNSIGNED_BYTE,
    channels: 2,
    array: Uint8Array,
    readsAsFloat: true,
  },
  rg16unorm: {
    internalFormat: GL_RG16_EXT,
    format: GL_RG,
    type: GL_UNSIGNED_SHORT,
    channels: 2,
    array: Uint16Array,
    readsAsFloat: true,
  },
  rgba16unorm: {
    internalFormat: GL_RGBA16_EXT,
    format: GL_RGBA,
    type: GL_UNSIGNED_SHORT,
    channels: 4,
    array: Uint16Array,
    readsAsFloat: true,
  },
  rg16snorm: {
    internalFormat: GL_RG16_SNORM_EXT,
    format: GL_RG,
    type: GL_SHORT,
    channels: 2,
    array: Int16Array,
    readsAsFloat: true,
  },
  rgba16snorm: {
    internalFormat: GL_RGBA16_SNORM_EXT,
    format: GL_RGBA,
    type: GL_SHORT,
    channels: 4,
    array: Int16Array,
    readsAsFloat: true,
  },
  rg16float: {
    internalFormat: GL_RG16F,
    format: GL_RG,
    type: GL_HALF_FLOAT,
    channels: 2,
    array: Uint16Array,
    readsAsFloat: true,
  },
  rgba16float: {
    internalFormat: GL_RGBA16F,
    format: GL_RGBA,
    type: GL_HALF_FLOAT,
    channels: 4,
    array: Uint16Array,
    readsAsFloat: true,
  },
  rg32float: {
    internalFormat: GL_RG32F,
    format: GL_RG,
    type: GL_FLOAT,
    channels: 2,
    array: Float32Array,
    readsAsFloat: true,
  },
};

export function glFormat(format: TextureFormat): GlFormat {
  const f = FORMATS[format];
  if (!f) throw new RangeError(`unknown texture format "${format}"`);
  return f;
}

/** Check that `data` has the right element type and length for a whole texture. */
export function checkTextureData(label: string, format: TextureFormat, texels: number, data: TextureData): void {
  const f = glFormat(format);
  if (!(data instanceof f.array)) throw new TypeError(`texture "${label}" (${format}) needs a ${f.array.name}`);
  const expected = texels * f.channels;
  if (data.length !== expected) {
    throw new RangeError(
      `texture "${label}" (${format}) needs ${expected} values (${texels} texels x ${f.channels}), got ${data.length}`,
    );
  }
}
