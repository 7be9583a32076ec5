/** vpt texture formats → WebGPU: texel size, components, usage flags, and data checks. */
import type { TextureData, TextureFormat } from '../backend.js';

export interface GpuFormatInfo {
  /** Bytes per texel in uploaded and read-back data (tightly packed). */
  bytesPerTexel: number;
  /** Components per texel in the uploaded/read data. */
  channels: number;
  /** The typed array uploads take (see TextureData). */
  array: typeof Float32Array | typeof Uint8Array | typeof Uint16Array | typeof Int16Array;
  /** Read back as Float32Array (r16float converted from half bits); rgba8unorm reads as bytes. */
  isFloat: boolean;
  /**
   * Colour-attachment byte cost and alignment, from the WebGPU spec's "render target pixel
   * byte cost" table, to check maxColorAttachmentBytesPerSample before a pipeline fails.
   */
  renderByteCost: number;
  renderByteAlign: number;
}

const FORMATS: Record<TextureFormat, GpuFormatInfo> = {
  r32float: {
    bytesPerTexel: 4,
    channels: 1,
    array: Float32Array,
    isFloat: true,
    renderByteCost: 4,
    renderByteAlign: 4,
  },
  rgba32float: {
    bytesPerTexel: 16,
    channels: 4,
    array: Float32Array,
    isFloat: true,
    renderByteCost: 16,
    renderByteAlign: 4,
  },
  rgba8unorm: {
    bytesPerTexel: 4,
    channels: 4,
    array: Uint8Array,
    isFloat: false,
    renderByteCost: 8,
    renderByteAlign: 1,
  },
  // Volume formats (r16float is also the fast path's gradient target). r8unorm/r16* are only sampled.
  r8unorm: { bytesPerTexel: 1, channels: 1, array: Uint8Array, isFloat: true, renderByteCost: 1, renderByteAlign: 1 },
  r16unorm: { bytesPerTexel: 2, channels: 1, array: Uint16Array, isFloat: true, renderByteCost: 2, renderByteAlign: 2 },
  r16snorm: { bytesPerTexel: 2, channels: 1, array: Int16Array, isFloat: true, renderByteCost: 2, renderByteAlign: 2 },
  r16float: { bytesPerTexel: 2, channels: 1, array: Uint16Array, isFloat: true, renderByteCost: 2, renderByteAlign: 2 },
  // Multichannel volumes: only uploaded and sampled (the norm16 ones need 'texture-formats-tier1', as r16unorm).
  rg8unorm: { bytesPerTexel: 2, channels: 2, array: Uint8Array, isFloat: true, renderByteCost: 2, renderByteAlign: 1 },
  rg16unorm: {
    bytesPerTexel: 4,
    channels: 2,
    array: Uint16Array,
    isFloat: true,
    renderByteCost: 4,
    renderByteAlign: 2,
  },
  rgba16unorm: {
    bytesPerTexel: 8,
    channels: 4,
    array: Uint16Array,
    isFloat: true,
    renderByteCost: 8,
    renderByteAlign: 2,
  },
  rg16snorm: { bytesPerTexel: 4, channels: 2, array: Int16Array, isFloat: true, renderByteCost: 4, renderByteAlign: 2 },
  rgba16snorm: {
    bytesPerTexel: 8,
    channels: 4,
    array: Int16Array,
    isFloat: true,
    renderByteCost: 8,
    renderByteAlign: 2,
  },
  rg16float: {
    bytesPerTexel: 4,
    channels: 2,
    array: Uint16Array,
    isFloat: true,
    renderByteCost: 4,
    renderByteAlign: 2,
  },
  rgba16float: {
    bytesPerTexel: 8,
    channels: 4,
    array: Uint16Array,
    isFloat: true,
    renderByteCost: 8,
    renderByteAlign: 2,
  },
  rg32float: {
    bytesPerTexel: 8,
    channels: 2,
    array: Float32Array,
    isFloat: true,
    renderByteCost: 8,
    renderByteAlign: 4,
  },
};

export function formatInfo(format: TextureFormat): GpuFormatInfo {
  const f = FORMATS[format];
  if (!f) throw new RangeError(`unknown texture format "${format}"`);
  return f;
}

/**
 * 2D textures are render targets, kernel inputs and readback sources; 3D textures
 * (volumes, grids) are only uploaded and read by kernels.
 */
export function textureUsage(dimension: '2d' | '3d'): GPUTextureUsageFlags {
  return dimension === '3d'
    ? GPUTextureUsage.TEXTURE_BINDING | GPUTextureUsage.COPY_DST
    : GPUTextureUsage.TEXTURE_BINDING |
        GPUTextureUsage.COPY_DST |
        GPUTextureUsage.COPY_SRC |
        GPUTextureUsage.RENDER_ATTACHMENT;
}

/** Bytes per sample of a set of colour attachments, as the spec adds them up (aligned running sum). */
export function colorAttachmentBytesPerSample(formats: readonly TextureFormat[]): number {
  let total = 0;
  for (const f of formats) {
    const info = formatInfo(f);
    total = Math.ceil(total / info.renderByteAlign) * info.renderByteAlign + info.renderByteCost;
  }
  return total;
}

/** Check that `data` has the right element type and length for a whole texture. */
export function checkTextureData(label: string, format: TextureFormat, texels: number, data: TextureData): void {
  const f = formatInfo(format);
  if (!(data instanceof f.array)) throw new TypeError(`texture "${label}" (${format}) needs a ${f.array.name}`);
  const expected = texels * f.channels;
  if (data.length !== expected) {
    throw new RangeError(
      `texture "${label}" (${format}) needs ${expected} values (${texels} texels x ${f.channels}), got ${data.length}`,
    );
  }
}
