/**
 * How a volume goes to the GPU: the texture format per voxel type and sampling mode, the
 * texel data for it, and how a stored texel decodes to the data value. The value range
 * (and its inversion) is not applied here: the kernels map the decoded value with the
 * scene uniforms `valueScale` / `valueOffset` (volumeValueMapping), so a range change
 * never re-uploads the volume.
 *
 * - 'fast' (default): the smallest filterable format that holds the type — uint8 → r8unorm
 *   (the data as is); uint16 → r16unorm and int16 → r16snorm where the device has 16-bit
 *   normalized textures, else r16float holding the integer itself (uint16 shifted by −32768
 *   when it holds values ≥ 65520, which half cannot represent); float32 → r16float of the
 *   data normalized to its own finite min..max when the caller allows half precision, else
 *   r32float. Kernels read it with one hardware-filtered fetch, or — r32float without
 *   float32 filtering — with the manual trilinear filter.
 * - 'exact': r32float holding the data value (integers are exact in float32) and the
 *   manual trilinear filter in full float: the reference for CPU twins and bit parity.
 *
 * r16float error bound (integer data stored as itself, round to nearest): integers with
 * |x| ≤ 2048 are exact; above, half has 11 significant bits, so the error is at most half
 * a unit in the last place: relative error ≤ 1/2049 ≈ 4.9e-4 of |x|; for int16 ≤ 8 data
 * units (|x| ≥ 16384), ≤ 8/65535 ≈ 1.2e-4 of the 16-bit span; for uint16 ≤ 16 units
 * (x ≥ 32768), ≤ 2.4e-4 of the span (tested over all 65536 values).
 * r16snorm maps −32768 to −1.0 like −32767 (GL/WebGPU snorm rule): one unit of error there.
 */
import type { Volume } from '../scene/volume.js';
import { channelCount, channelVolume, normalizationRange, voxelCount } from '../scene/volume.js';
import type { BackendCapabilities, TextureData, TextureFormat } from './backend.js';
import { BYTES_PER_TEXEL, isFilterable } from './backend.js';
import { floatToHalf } from './half-float.js';

export type VolumeSampling = 'fast' | 'exact';

export interface VolumeFormatOptions {
  sampling: VolumeSampling;
  /** float32 volumes may be stored as r16float (half the memory, ~3 significant digits). Default false. */
  allowHalfFloat?: boolean;
}

export interface VolumeUpload {
  format: TextureFormat;
  /** 'linear': the kernels read it with one hardware-filtered fetch; 'nearest': the manual trilinear filter. */
  filter: 'linear' | 'nearest';
  /** Data value = texel value × decodeScale + decodeOffset (texel value as the shader reads it). */
  decodeScale: number;
  decodeOffset: number;
  bytesPerVoxel: number;
}

/** The upload for a volume on a device (no data is touched except to find a float32 or uint16 volume's extremes). */
export function planVolumeUpload(volume: Volume, caps: BackendCapabilities, opts: VolumeFormatOptions): VolumeUpload {
  const make = (format: TextureFormat, decodeScale: number, decodeOffset: number, filtered: boolean): VolumeUpload => ({
    format,
    decodeScale,
    decodeOffset,
    bytesPerVoxel: BYTES_PER_TEXEL[format],
    filter: filtered && isFilterable(format, caps) ? 'linear' : 'nearest',
  });
  if (opts.sampling === 'exact') return make('r32float', 1, 0, false);
  switch (volume.type) {
    case 'uint8':
      return make('r8unorm', 255, 0, true);
    case 'uint16':
      if (caps.norm16) return make('r16unorm', 65535, 0, true);
      return make('r16float', 1, maxOf(volume.data) >= HALF_OVERFLOW ? 32768 : 0, true);
    case 'int16':
      return caps.norm16 ? make('r16snorm', 32767, 0, true) : make('r16float', 1, 0, true);
    case 'float32': {
      if (!opts.allowHalfFloat) return make('r32float', 1, 0, true);
      const [lo, hi] = finiteExtent(volume.data);
      return make('r16float', hi - lo, lo, true);
    }
  }
}

/** The upload takes the volume's own array as it is (no conversion, no copy). */
export function uploadsDataAsIs(upload: VolumeUpload): boolean {
  return upload.format === 'r8unorm' || upload.format === 'r16unorm' || upload.format === 'r16snorm';
}

/** Texel data for a planned upload: the volume's own array where the format takes it as is. */
export function volumeTextureData(volume: Volume, upload: VolumeUpload): TextureData {
  return volumeTextureSlab(volume, upload, 0, volume.dims[2]);
}

/**
 * Texel data of slices [z0, z1) (RenderContext converts and uploads large volumes slab by
 * slab, so no full-size converted copy exists): a view of the volume's own array where the
 * format takes it as is, else a converted copy of just those slices — written into `scratch`
 * when given and large enough (one buffer reused for every slab, since both backends copy
 * the data when it is written to the texture).
 */
export function volumeTextureSlab(
  volume: Volume,
  upload: VolumeUpload,
  z0: number,
  z1: number,
  scratch?: ArrayBuffer,
): TextureData {
  const slice = volume.dims[0] * volume.dims[1];
  const src = volume.data.subarray(z0 * slice, z1 * slice);
  const fill = normalizationRange(volume)[0]; // non-finite voxels read as the value that maps to 0
  if (uploadsDataAsIs(upload)) return src as TextureData; // Uint8Array / Uint16Array / Int16Array as stored
  switch (upload.format) {
    case 'r16float': {
      const out =
        scratch && scratch.byteLength >= src.length * 2
          ? new Uint16Array(scratch, 0, src.length)
          : new Uint16Array(src.length);
      if (volume.type === 'float32') {
        const inv = upload.decodeScale > 0 ? 1 / upload.decodeScale : 0;
        for (let i = 0; i < out.length; i++) {
          const x = src[i];
          out[i] = floatToHalf(((Number.isFinite(x) ? x : fill) - upload.decodeOffset) * inv);
        }
      } else {
        // 16-bit integers: one table lookup per voxel. Index = the integer plus a bias that makes
        // it non-negative; entry = half(integer − decodeOffset).
        const bias = volume.type === 'int16' ? 32768 : 0;
        const table = halfTable(bias + upload.decodeOffset);
        for (let i = 0; i < out.length; i++) out[i] = table[src[i] + bias];
      }
      return out;
    }
    case 'r32float': {
      const out = () =>
        scratch && scratch.byteLength >= src.length * 4
          ? new Float32Array(scratch, 0, src.length)
          : new Float32Array(src.length);
      if (volume.type !== 'float32') {
        const o = out();
        o.set(src);
        return o;
      }
      const f = src as Float32Array;
      let clean = true;
      for (let i = 0; i < f.length && clean; i++) clean = Number.isFinite(f[i]);
      if (clean) return f;
      const o = out();
      for (let i = 0; i < f.length; i++) o[i] = Number.isFinite(f[i]) ? f[i] : fill;
      return o;
    }
    default:
      throw new RangeError(`no volume data for format ${upload.format}`);
  }
}

/**
 * The scene uniforms that turn a texel into the normalized value v = clamp(texel ·
 * valueScale + valueOffset, 0, 1): decode, then map the value range [lo, hi] to [0, 1]
 * (lo > hi inverts: valueScale < 0). Applied after filtering, which commutes with the
 * affine part, so both sampling paths compute clamp(map(trilinear(data))).
 */
export function volumeValueMapping(
  volume: Volume,
  upload: Pick<VolumeUpload, 'decodeScale' | 'decodeOffset'>,
): { valueScale: number; valueOffset: number } {
  const [lo, hi] = normalizationRange(volume);
  const inv = 1 / (hi - lo);
  return { valueScale: upload.decodeScale * inv, valueOffset: (upload.decodeOffset - lo) * inv };
}

// Half's largest finite value is 65504; from 65520 on, rounding gives Infinity.
const HALF_OVERFLOW = 65520;

/** Half bits of (i − shift) for i = 0..65535 (the last two tables kept: slabs of one volume share one). */
const tables = new Map<number, Uint16Array>();
function halfTable(shift: number): Uint16Array {
  let t = tables.get(shift);
  if (!t) {
    t = new Uint16Array(65536);
    for (let i = 0; i < t.length; i++) t[i] = floatToHalf(i - shift);
    if (tables.size >= 2) tables.clear();
    tables.set(shift, t);
  }
  return t;
}

function maxOf(data: ArrayLike<number>): number {
  let m = -Infinity;
  for (let i = 0; i < data.length; i++) if (data[i] > m) m = data[i];
  return m;
}

function finiteExtent(data: ArrayLike<number>): [number, number] {
  let lo = Infinity,
    hi = -Infinity;
  for (let i = 0; i < data.length; i++) {
    const x = data[i];
    if (!Number.isFinite(x)) continue;
    if (x < lo) lo = x;
    if (x > hi) hi = x;
  }
  if (!Number.isFinite(lo)) return [0, 1];
  return hi > lo ? [lo, hi] : [lo, lo + 1];
}

/** Texture components for N drawn channels: 1, 2, or 4 (three channels take an RGBA texture, its last component 0). */
export function channelComponents(n: number): 1 | 2 | 4 {
  return n <= 1 ? 1 : n === 2 ? 2 : 4;
}

const MULTI: Record<string, [TextureFormat, TextureFormat]> = {
  r8unorm: ['rg8unorm', 'rgba8unorm'],
  r16unorm: ['rg16unorm', 'rgba16unorm'],
  r16snorm: ['rg16snorm', 'rgba16snorm'],
  r16float: ['rg16float', 'rgba16float'],
  r32float: ['rg32float', 'rgba32float'],
};

/**
 * The upload of the drawn channels `channels` (indices into the volume's) as one texture of
 * 1, 2 or 4 components (scene/channels.ts). One channel is planned exactly as a scalar volume
 * holding it (so one channel through this path uploads what the scalar path does); more take
 * the multi-component twin of that format, same bytes per component: rg8/rgba8 unorm,
 * rg16/rgba16 unorm or snorm where the device has them, else half floats holding the integers
 * (shifted for uint16 data ≥ 65520, as for one channel), and rg32/rgba32 float for float32 data
 * (half-float storage of float32 data is for scalar volumes only).
 */
export function planChannelUpload(
  volume: Volume,
  caps: BackendCapabilities,
  opts: VolumeFormatOptions,
  channels: readonly number[],
): VolumeUpload {
  if (channels.length === 1) return planVolumeUpload(channelVolume(volume, channels[0]), caps, opts);
  const scalar = planVolumeUpload(channelVolume(volume, channels[0]), caps, { ...opts, allowHalfFloat: false });
  let decodeOffset = scalar.decodeOffset;
  if (scalar.format === 'r16float' && volume.type === 'uint16') {
    // Half cannot hold uint16 values ≥ 65520: shift every channel when any drawn one holds them.
    const big = channels.some((c) => maxOf(channelVolume(volume, c).data) >= HALF_OVERFLOW);
    decodeOffset = big ? 32768 : 0;
  }
  const format = MULTI[scalar.format][channels.length === 2 ? 0 : 1];
  return {
    format,
    decodeScale: scalar.decodeScale,
    decodeOffset,
    bytesPerVoxel: BYTES_PER_TEXEL[format],
    filter: scalar.filter === 'linear' && isFilterable(format, caps) ? 'linear' : 'nearest',
  };
}

/**
 * Texel data of the drawn channels for a planned upload: the volume's own interleaved array
 * where it is exactly the texture (every channel drawn, 2 or 4 of them, in order, a format
 * that takes the data as is), else the channels gathered (and converted) into the texture's
 * components, unused ones 0. Non-finite float voxels read as the value that maps to 0 in
 * their channel, as for a scalar volume.
 */
export function channelTextureData(volume: Volume, upload: VolumeUpload, channels: readonly number[]): TextureData {
  if (channels.length === 1) return volumeTextureData(channelVolume(volume, channels[0]), upload);
  const c = channelCount(volume);
  const comps = channelComponents(channels.length);
  const inOrder = channels.every((ch, k) => ch === k);
  if (uploadsDataAsIs(upload) || isMultiAsIs(upload.format)) {
    if (comps === c && channels.length === c && inOrder) return volume.data as TextureData;
  }
  const count = voxelCount(volume.dims);
  const src = volume.data;
  const n = count * comps;
  const fills = channels.map((ch) => normalizationRange(channelVolume(volume, ch))[0]);
  const gather = (out: TextureData, convert: (x: number, k: number) => number) => {
    for (let i = 0; i < count; i++)
      for (let k = 0; k < channels.length; k++) out[comps * i + k] = convert(src[channels[k] + c * i], k);
    return out;
  };
  if (isMultiAsIs(upload.format)) {
    const Arr = volume.type === 'uint8' ? Uint8Array : volume.type === 'int16' ? Int16Array : Uint16Array;
    return gather(new Arr(n), (x) => x);
  }
  if (upload.format === 'rg16float' || upload.format === 'rgba16float') {
    const inv = upload.decodeScale > 0 ? 1 / upload.decodeScale : 0;
    return gather(new Uint16Array(n), (x, k) =>
      floatToHalf(((Number.isFinite(x) ? x : fills[k]) - upload.decodeOffset) * inv),
    );
  }
  if (upload.format === 'rg32float' || upload.format === 'rgba32float')
    return gather(new Float32Array(n), (x, k) => (Number.isFinite(x) ? x : fills[k]));
  throw new RangeError(`no channel data for format ${upload.format}`);
}

function isMultiAsIs(format: TextureFormat): boolean {
  return /^(rg|rgba)(8unorm|16unorm|16snorm)$/.test(format);
}
