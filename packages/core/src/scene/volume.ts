import { VptError } from '../errors.js';
import { FLOAT32_MAX } from '../validation/limits.js';

export type VoxelType = 'uint8' | 'uint16' | 'int16' | 'float32';
export type VoxelArray = Uint8Array | Uint16Array | Int16Array | Float32Array;

/** Channels a volume may hold (scene/channels.ts: at most MAX_ENABLED_CHANNELS of them are drawn at once). */
export const MAX_VOLUME_CHANNELS = 16;

/**
 * A scalar volume, or a multichannel one (`channels` > 1). Plain and serializable (the typed
 * array aside). Layout: x fastest, then y, then z: value(x,y,z) = data[x + NX*(y + NY*z)];
 * with C channels they are interleaved, the channel fastest: value(c,x,y,z) =
 * data[c + C*(x + NX*(y + NY*z))] (the order a multi-component texture takes, so 2 or 4
 * channels of uint8/uint16/int16 upload as they are).
 */
export interface Volume {
  dims: [number, number, number];
  /** Physical voxel size; only ratios matter (the box is scaled so its longest side is 1). */
  spacing: [number, number, number];
  type: VoxelType;
  data: VoxelArray;
  /**
   * The value range [LO, HI] mapped to [0, 1]: LO → 0, HI → 1, linear between, clamped
   * outside. LO > HI inverts (dense matter stored as dark values, as in cryo-ET); LO = HI is
   * invalid. Without it, uint8 maps value/255 and uint16 value/65535 (docs/design.md), and
   * int16/float32 the data's own min..max. The kernels apply it (gpu/volume-format.ts), so
   * changing it re-uploads nothing.
   */
  valueRange?: [number, number];
  name?: string;
  /** Channels per voxel, interleaved (default 1). A scene with more than one gives each its settings (Scene.channels). */
  channels?: number;
}

const ARRAY_OF: Record<VoxelType, new (n: number) => VoxelArray> = {
  uint8: Uint8Array,
  uint16: Uint16Array,
  int16: Int16Array,
  float32: Float32Array,
};

export function voxelCount(dims: readonly number[]): number {
  return dims[0] * dims[1] * dims[2];
}

/** Check a volume against the model's rules; throws VptError('invalid-scene'). */
export function validateVolume(v: Volume): void {
  const bad = (msg: string) => {
    throw new VptError('invalid-scene', `Volume${v.name ? ` "${v.name}"` : ''}: ${msg}`);
  };
  if (!v || typeof v !== 'object') bad('missing');
  if (!Array.isArray(v.dims) || v.dims.length !== 3) bad('dims must be [NX, NY, NZ]');
  for (const d of v.dims) {
    if (typeof d !== 'number' || !Number.isInteger(d) || d < 1)
      bad(`every dimension must be a positive integer, got [${v.dims.join(', ')}]`);
  }
  if (
    !Array.isArray(v.spacing) ||
    v.spacing.length !== 3 ||
    v.spacing.some((s) => typeof s !== 'number' || !Number.isFinite(s) || s <= 0 || s > FLOAT32_MAX)
  ) {
    bad(`spacing must be three positive finite (float32) numbers, got [${v.spacing}]`);
  }
  if (!(v.type in ARRAY_OF)) bad(`unknown voxel type "${v.type}"`);
  if (!(v.data instanceof ARRAY_OF[v.type])) bad(`data must be a ${ARRAY_OF[v.type].name} for type ${v.type}`);
  const c = v.channels ?? 1;
  if (typeof c !== 'number' || !Number.isInteger(c) || c < 1 || c > MAX_VOLUME_CHANNELS)
    bad(`channels must be an integer in [1, ${MAX_VOLUME_CHANNELS}] (MAX_VOLUME_CHANNELS), got ${v.channels}`);
  const n = voxelCount(v.dims) * c;
  if (v.data.length !== n)
    bad(
      c === 1
        ? `dims [${v.dims.join(', ')}] need ${n} voxels, data has ${v.data.length}`
        : `dims [${v.dims.join(', ')}] × ${c} channels need ${n} values, data has ${v.data.length}`,
    );
  if (
    v.valueRange &&
    (!Array.isArray(v.valueRange) ||
      v.valueRange.length !== 2 ||
      !v.valueRange.every(Number.isFinite) ||
      v.valueRange[0] === v.valueRange[1])
  ) {
    bad(`valueRange must be two different finite numbers [LO, HI] (LO > HI inverts), got [${v.valueRange}]`);
  }
}

/** The range [LO, HI] that maps to [0, 1] for this volume (docs/design.md conventions); LO > HI when inverted. */
export function normalizationRange(v: Volume): [number, number] {
  if (v.type === 'uint8' && !v.valueRange) return [0, 255];
  if (v.type === 'uint16' && !v.valueRange) return [0, 65535];
  if (v.valueRange) return v.valueRange;
  let lo = Infinity,
    hi = -Infinity;
  for (let i = 0; i < v.data.length; i++) {
    const x = v.data[i];
    if (!Number.isFinite(x)) continue; // NaN/Inf voxels must not stretch the range
    if (x < lo) lo = x;
    if (x > hi) hi = x;
  }
  if (!Number.isFinite(lo)) return [0, 1];
  if (hi > lo) return [lo, hi];
  // A constant volume has no range of its own. It is mapped as if its range reached 0:
  // a positive constant c normalizes to 1 ([0, c]: a homogeneous medium at the TF's top),
  // zero and negative constants to 0 ([c, 0] / [0, 1]: empty). So a constant float32 or
  // int16 volume renders as the box it fills instead of nothing.
  if (lo > 0) return [0, lo];
  if (lo < 0) return [lo, 0];
  return [0, 1];
}

/**
 * Normalized float32 copy of the data in [0, 1] (per voxel; CPU twins and histograms); NaN
 * and ±Inf become 0, as on the GPU (gpu/volume-format.ts), so they never reach a kernel.
 */
export function normalizedData(v: Volume): Float32Array {
  const [lo, hi] = normalizationRange(v);
  const scale = 1 / (hi - lo);
  const out = new Float32Array(v.data.length);
  for (let i = 0; i < out.length; i++) {
    const x = (v.data[i] - lo) * scale;
    out[i] = Number.isFinite(x) ? Math.min(1, Math.max(0, x)) : 0;
  }
  return out;
}

/** Physical extent scaled so the longest side is 1, centred at the origin (docs/design.md). */
export function volumeBox(v: Pick<Volume, 'dims' | 'spacing'>): {
  min: [number, number, number];
  max: [number, number, number];
  size: [number, number, number];
} {
  const ext = [0, 1, 2].map((i) => v.dims[i] * v.spacing[i]);
  const longest = Math.max(...ext);
  const size = ext.map((e) => e / longest) as [number, number, number];
  return {
    min: size.map((s) => -s / 2) as [number, number, number],
    max: size.map((s) => s / 2) as [number, number, number],
    size,
  };
}

/** A volume; `channels` > 1 makes a multichannel one whose `data` is interleaved (see Volume). */
export function createVolume(
  dims: [number, number, number],
  type: VoxelType,
  data?: VoxelArray,
  spacing: [number, number, number] = [1, 1, 1],
  channels = 1,
): Volume {
  const v: Volume = { dims, spacing, type, data: data ?? new ARRAY_OF[type](voxelCount(dims) * channels) };
  if (channels !== 1) v.channels = channels;
  validateVolume(v);
  return v;
}

/** Channels per voxel (1 for a scalar volume). */
export function channelCount(v: Pick<Volume, 'channels'>): number {
  return v.channels ?? 1;
}

const channelViews = new WeakMap<VoxelArray, Map<number, VoxelArray>>();

/**
 * Channel `c` as a scalar volume (its data de-interleaved once per array and channel, then
 * cached), with `valueRange` as given: what the CPU twins, histograms and majorant bounds
 * of one channel read. Channel 0 of a scalar volume is the volume's own data.
 */
export function channelVolume(v: Volume, c: number, valueRange?: [number, number]): Volume {
  const n = channelCount(v);
  if (!Number.isInteger(c) || c < 0 || c >= n)
    throw new VptError('invalid-scene', `Volume: channel ${c} does not exist (the volume has ${n})`);
  let data = v.data;
  if (n > 1) {
    let byChannel = channelViews.get(v.data);
    if (!byChannel) channelViews.set(v.data, (byChannel = new Map()));
    let d = byChannel.get(c);
    if (!d) {
      d = new ARRAY_OF[v.type](voxelCount(v.dims));
      for (let i = 0; i < d.length; i++) d[i] = v.data[c + n * i];
      byChannel.set(c, d);
    }
    data = d;
  }
  const out: Volume = { dims: v.dims, spacing: v.spacing, type: v.type, data };
  if (valueRange) out.valueRange = valueRange;
  else if (v.valueRange) out.valueRange = v.valueRange;
  if (v.name) out.name = v.name;
  return out;
}

/**
 * One multichannel volume from scalar volumes of the same grid and voxel type (several files
 * of one acquisition), interleaved; throws VptError('invalid-scene') naming the mismatch.
 */
export function interleaveChannels(volumes: readonly Volume[]): Volume {
  if (volumes.length < 1 || volumes.length > MAX_VOLUME_CHANNELS)
    throw new VptError(
      'invalid-scene',
      `Volume: ${volumes.length} channels given, 1 to ${MAX_VOLUME_CHANNELS} (MAX_VOLUME_CHANNELS) allowed`,
    );
  const first = volumes[0];
  volumes.forEach((v, k) => {
    validateVolume(v);
    if (channelCount(v) !== 1) throw new VptError('invalid-scene', `Volume: channel ${k} is itself multichannel`);
    if (v.type !== first.type)
      throw new VptError('invalid-scene', `Volume: channel ${k} is ${v.type}, channel 0 is ${first.type}`);
    if (v.dims.some((d, i) => d !== first.dims[i]))
      throw new VptError(
        'invalid-scene',
        `Volume: channel ${k} has dims [${v.dims.join(', ')}], channel 0 [${first.dims.join(', ')}] (channels share one grid)`,
      );
  });
  const n = volumes.length;
  if (n === 1) return first;
  const count = voxelCount(first.dims);
  const data = new ARRAY_OF[first.type](count * n);
  volumes.forEach((v, k) => {
    for (let i = 0; i < count; i++) data[k + n * i] = v.data[i];
  });
  return createVolume([...first.dims], first.type, data, [...first.spacing], n);
}
