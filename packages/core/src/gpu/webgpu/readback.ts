/**
 * Texture readback: copy a 2D texture into a mappable buffer (rows padded to the 256-byte
 * bytesPerRow alignment copyTextureToBuffer requires) and unpack it tightly, top row first.
 */
import type { TextureFormat } from '../backend.js';
import { fromHalfArray } from '../half-float.js';
import { formatInfo } from './formats.js';

const ROW_ALIGN = 256;

export interface PendingReadback {
  buffer: GPUBuffer;
  bytesPerRow: number;
}

/** Encode and submit the copy; the caller maps `buffer` and then calls unpackReadback. */
export function submitReadback(
  device: GPUDevice,
  texture: GPUTexture,
  width: number,
  height: number,
  format: TextureFormat,
  label: string,
): PendingReadback {
  const tight = width * formatInfo(format).bytesPerTexel;
  const bytesPerRow = Math.ceil(tight / ROW_ALIGN) * ROW_ALIGN;
  const buffer = device.createBuffer({
    label: `vpt readback of ${label}`,
    size: bytesPerRow * height,
    usage: GPUBufferUsage.COPY_DST | GPUBufferUsage.MAP_READ,
  });
  const encoder = device.createCommandEncoder({ label: `vpt readback of ${label}` });
  encoder.copyTextureToBuffer({ texture }, { buffer, bytesPerRow, rowsPerImage: height }, [width, height, 1]);
  device.queue.submit([encoder.finish()]);
  return { buffer, bytesPerRow };
}

/**
 * Strip the row padding. Texel row 0 (WebGPU's first row in memory) is vpt's top row,
 * so rows are copied in order: Float32Array (W*H for r32float, W*H*4 for rgba32float)
 * or Uint8Array W*H*4 for rgba8unorm.
 */
export function unpackReadback(
  mapped: ArrayBuffer,
  bytesPerRow: number,
  width: number,
  height: number,
  format: TextureFormat,
): Float32Array | Uint8Array {
  const info = formatInfo(format);
  const tight = width * info.bytesPerTexel;
  const src = new Uint8Array(mapped);
  const bytes = new Uint8Array(tight * height);
  for (let y = 0; y < height; y++) bytes.set(src.subarray(y * bytesPerRow, y * bytesPerRow + tight), y * tight);
  if (format === 'r16float') return fromHalfArray(new Uint16Array(bytes.buffer));
  if (format === 'r8unorm') return Float32Array.from(bytes, (b) => b / 255);
  return info.isFloat ? new Float32Array(bytes.buffer) : bytes;
}
