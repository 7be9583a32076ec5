/** vpt texture formats → WebGPU: texel size, components, usage flags, and data checks. */
import type { TextureFormat } from '../backend.js';

export interface GpuFormatInfo {
  /** Bytes per texel in uploaded and read-back data (tightly packed). */
  bytesPerTexel: number;
  /** Components per texel in the uploaded/read data. */
  channels: number;
  /** Float formats take/return Float32Array; rgba8unorm Uint8Array. */
  isFloat: boolean;
  /**
   * Colour-attachment byte cost and alignment, from the WebGPU spec's "render target pixel
   * byte cost" table, to check maxColorAttachmentBytesPerSample before a pipeline fails.
   */
  renderByteCost: number;
  renderByteAlign: number;
}

const FORMATS: Record<TextureFormat, GpuFormatInfo> = {
  r32float: { bytesPerTexel: 4, channels: 1, isFloat: true, renderByteCost: 4, renderByteAlign: 4 },
  rgba32float: { bytesPerTexel: 16, channels: 4, isFloat: true, renderByteCost: 16, renderByteAlign: 4 },
  rgba8unorm: { bytesPerTexel: 4, channels: 4, isFloat: false, renderByteCost: 8, renderByteAlign: 1 },
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
    : GPUTextureUsage.TEXTURE_BINDING | GPUTextureUsage.COPY_DST | GPUTextureUsage.COPY_SRC | GPUTextureUsage.RENDER_ATTACHMENT;
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
export function checkTextureData(label: string, format: TextureFormat, texels: number, data: Float32Array | Uint8Array): void {
  const f = formatInfo(format);
  if (f.isFloat && !(data instanceof Float32Array)) throw new TypeError(`texture "${label}" (${format}) needs a Float32Array`);
  if (!f.isFloat && !(data instanceof Uint8Array)) throw new TypeError(`texture "${label}" (${format}) needs a Uint8Array`);
  const expected = texels * f.channels;
  if (data.length !== expected) {
    throw new RangeError(`texture "${label}" (${format}) needs ${expected} values (${texels} texels x ${f.channels}), got ${data.length}`);
  }
}
