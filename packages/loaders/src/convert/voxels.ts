import type { VoxelArray, VoxelType } from '@vpt/core';
import { SOURCE_BYTES, type SourceType } from './size.js';

export type SourceArray =
  Uint8Array | Int8Array | Uint16Array | Int16Array | Uint32Array | Int32Array | Float32Array | Float64Array;

/** The typed array of each source voxel type (reading binary data, or building it from parsed numbers). */
export const SOURCE_ARRAY: Record<
  SourceType,
  { new (b: ArrayBuffer, o?: number, n?: number): SourceArray; new (n: number): SourceArray }
> = {
  uint8: Uint8Array,
  int8: Int8Array,
  uint16: Uint16Array,
  int16: Int16Array,
  uint32: Uint32Array,
  int32: Int32Array,
  float32: Float32Array,
  float64: Float64Array,
};

export const OUTPUT_ARRAY: Record<VoxelType, new (n: number) => VoxelArray> = {
  uint8: Uint8Array,
  uint16: Uint16Array,
  int16: Int16Array,
  float32: Float32Array,
};

export const OUTPUT_BYTES: Record<VoxelType, number> = { uint8: 1, uint16: 2, int16: 2, float32: 4 };

const HOST_LITTLE = new Uint8Array(new Uint16Array([1]).buffer)[0] === 1;

/**
 * `count` samples of `type` from `bytes` at `offset`, in this machine's byte order (the
 * caller has checked that the bytes are there). With `view` (bytes the loader owns), aligned
 * data in this machine's order is a typed-array view over them, no copy and no per-voxel
 * work; otherwise one slab copy (memcpy), then a byte swap where the order differs.
 */
export function readSamples(
  bytes: Uint8Array,
  offset: number,
  count: number,
  type: SourceType,
  littleEndian: boolean,
  view = false,
): SourceArray {
  const size = SOURCE_BYTES[type];
  const at = bytes.byteOffset + offset;
  if (view && (size === 1 || littleEndian === HOST_LITTLE) && at % size === 0)
    return new SOURCE_ARRAY[type](bytes.buffer as ArrayBuffer, at, count);
  const copy = bytes.slice(offset, offset + count * size);
  if (size > 1 && littleEndian !== HOST_LITTLE) swapBytes(copy, size);
  return new SOURCE_ARRAY[type](copy.buffer, 0, count);
}

/** May voxels read from these bytes share their memory (the loader's own, not the caller's)? */
export function ownsMemory(bytes: Uint8Array, borrowed: ArrayBufferLike | undefined): boolean {
  return bytes.buffer !== borrowed;
}

/** Reverse the byte order of each `size`-byte sample of a fresh (aligned) copy, a word at a time. */
function swapBytes(b: Uint8Array, size: number): void {
  const n = Math.floor(b.length / size);
  if (size === 2) {
    const w = new Uint16Array(b.buffer, b.byteOffset, n);
    for (let i = 0; i < n; i++) {
      const x = w[i];
      w[i] = (x >>> 8) | ((x & 0xff) << 8);
    }
  } else if (size === 4 || size === 8) {
    const w = new Uint32Array(b.buffer, b.byteOffset, (n * size) / 4);
    for (let i = 0; i < w.length; i++) {
      const x = w[i];
      w[i] = ((x & 0xff) << 24) | ((x & 0xff00) << 8) | ((x >>> 8) & 0xff00) | (x >>> 24);
    }
    // An 8-byte sample is two swapped words, which also trade places.
    if (size === 8)
      for (let i = 0; i + 1 < w.length; i += 2) {
        const t = w[i];
        w[i] = w[i + 1];
        w[i + 1] = t;
      }
  } else {
    for (let i = 0; i + size <= b.length; i += size) b.subarray(i, i + size).reverse();
  }
}

export interface SampleRange {
  min: number;
  max: number;
  nonFinite: number;
}

/** Finite min/max and the number of NaN/±Inf samples. */
export function scanRange(a: ArrayLike<number>): SampleRange {
  let min = Infinity,
    max = -Infinity,
    nonFinite = 0;
  for (let i = 0; i < a.length; i++) {
    const x = a[i];
    if (x !== x || x === Infinity || x === -Infinity) {
      nonFinite++;
      continue;
    }
    if (x < min) min = x;
    if (x > max) max = x;
  }
  return { min, max, nonFinite };
}

const isIntegral = (t: SourceType) => t !== 'float32' && t !== 'float64';

/**
 * The narrowest core type that holds every value exactly: integer data whose (scaled) range
 * fits 8 or 16 bits stays integer (a CT stored as uint16 with intercept −1024 becomes
 * int16), everything else becomes float32.
 */
export function chooseType(source: SourceType, scaled: { min: number; max: number }, integral: boolean): VoxelType {
  if (!integral || !isIntegral(source)) return 'float32';
  const { min, max } = scaled;
  if (!(min <= max)) return source === 'uint8' ? 'uint8' : source === 'uint16' ? 'uint16' : 'int16'; // no finite values at all
  if (source === 'uint8' && min >= 0 && max <= 255) return 'uint8';
  if (source === 'uint16' && min >= 0 && max <= 65535) return 'uint16';
  if (min >= -32768 && max <= 32767) return 'int16';
  if (min >= 0 && max <= 65535) return 'uint16';
  return 'float32';
}

/**
 * The core type for these samples, scanning them only when the answer depends on their
 * range (32-bit integers, integer rescaling); 8/16-bit integers and floats map to a fixed
 * type, so the common files are read with no per-voxel pass here. `warnings` gets a note
 * when 32-bit integers beyond ±2^24 become float32 (they round), as OME-Zarr's reader says.
 */
export function chooseTypeOf(
  samples: SourceArray,
  source: SourceType,
  scaling: Scaling,
  warnings: string[],
): VoxelType {
  const integral = integralScaling(scaling);
  const identity = scaling.slope === 1 && scaling.inter === 0;
  if (!integral || !isIntegral(source)) return 'float32';
  if (identity && (source === 'uint8' || source === 'uint16' || source === 'int16' || source === 'int8'))
    return source === 'int8' ? 'int16' : source;
  const range = scanRange(samples);
  const type = chooseType(source, scaledRange(range, scaling), integral);
  const scaled = scaledRange(range, scaling);
  if (type === 'float32' && Math.max(Math.abs(scaled.min), Math.abs(scaled.max)) > FLOAT32_EXACT_INTEGER)
    warnings.push(
      `${source} data is read as float32, and its values reach ${Math.max(Math.abs(scaled.min), Math.abs(scaled.max))}: integers beyond ±2^24 round`,
    );
  return type;
}

/** 2^24: the largest integer magnitude below which float32 holds every integer exactly. */
export const FLOAT32_EXACT_INTEGER = 1 << 24;

export interface Scaling {
  slope: number;
  inter: number;
}

export const IDENTITY: Scaling = { slope: 1, inter: 0 };

/** True when slope and intercept map integers to integers. */
export function integralScaling(s: Scaling): boolean {
  return Number.isInteger(s.slope) && Number.isInteger(s.inter);
}

export function scaledRange(r: { min: number; max: number }, s: Scaling): { min: number; max: number } {
  const a = r.min * s.slope + s.inter,
    b = r.max * s.slope + s.inter;
  return { min: Math.min(a, b), max: Math.max(a, b) };
}

/** out[at + i] = src[i] · slope + inter (float32 rounding for float output). */
export function convertInto(src: SourceArray, s: Scaling, out: VoxelArray, at = 0): void {
  if (s.slope === 1 && s.inter === 0) {
    // TypedArray.set converts element by element (float64 → float32 rounds, int8 → int16 widens).
    (out as { set(a: ArrayLike<number>, o: number): void }).set(src, at);
    return;
  }
  const { slope, inter } = s;
  for (let i = 0; i < src.length; i++) out[at + i] = src[i] * slope + inter;
}

/** Convert a whole source array to the chosen core type (no copy when it already is one). */
export function toVoxelArray(src: SourceArray, type: VoxelType, s: Scaling = IDENTITY): VoxelArray {
  if (s.slope === 1 && s.inter === 0 && src instanceof OUTPUT_ARRAY[type]) return src as VoxelArray;
  const out = new OUTPUT_ARRAY[type](src.length);
  convertInto(src, s, out);
  return out;
}
