import { validateVolume, type VoxelArray, type VoxelType } from '@vpt/core';
import { toLabelVolume } from '@vpt/core/labels';
import { LoaderError } from '../errors.js';
import type { LoadContext } from '../context.js';
import type { LoadedVolume } from '../types.js';
import { checkFits, downsampleFactors } from './size.js';
import { OUTPUT_ARRAY, OUTPUT_BYTES, scanRange } from './voxels.js';

export interface DecodedVolume {
  format: string;
  dims: [number, number, number];
  spacing: [number, number, number];
  type: VoxelType;
  data: VoxelArray;
  orientation?: number[];
  origin?: [number, number, number];
  meta?: Record<string, unknown>;
  /** Values per voxel, interleaved channel fastest (core's Volume.channels; default 1). */
  channels?: number;
}

/**
 * The common last step of every format: apply the limits (downsample or fail), count
 * NaN/±Inf, record the finite data range and any warnings, and check the result against
 * core's rules so a loader bug can never hand the renderer an invalid Volume.
 */
export function finishVolume(v: DecodedVolume, ctx: LoadContext): LoadedVolume {
  const meta: Record<string, unknown> = { ...(v.meta ?? {}) };
  let { dims, spacing, data, origin } = v;
  const C = v.channels ?? 1;
  if (checkFits(dims, OUTPUT_BYTES[v.type] * C, ctx) === 'downsample') {
    const factors = downsampleFactors(dims, OUTPUT_BYTES[v.type] * C, ctx.limits);
    const shrunk = ctx.labels
      ? subsample(data, dims, factors)
      : C > 1
        ? downsampleChannels(data, dims, factors, v.type, C)
        : downsample(data, dims, factors, v.type);
    meta.downsampled = { factors, originalDims: dims, originalSpacing: spacing };
    if (origin && v.orientation) {
      // The first output voxel's centre is the centre of the first input block.
      const shift = [0, 1, 2].map((i) => ((factors[i] - 1) / 2) * spacing[i]);
      const R = v.orientation;
      origin = [0, 1, 2].map(
        (r) => origin![r] + R[3 * r] * shift[0] + R[3 * r + 1] * shift[1] + R[3 * r + 2] * shift[2],
      ) as [number, number, number];
    }
    dims = shrunk.dims;
    spacing = spacing.map((s, i) => s * factors[i]) as [number, number, number];
    data = shrunk.data;
    ctx.warnings.push(`downsampled by [${factors.join(', ')}] to fit the limits`);
  }
  let type = v.type;
  if (ctx.labels) {
    // Label ids: core's rule (integers in [0, 65535], the narrowest of uint8 / uint16), no value range.
    try {
      ({ type, data } = toLabelVolume({ dims, spacing, type, data }, `${ctx.name} (a label volume)`));
    } catch (e) {
      throw new LoaderError('invalid-data', (e as Error).message, { cause: e });
    }
    meta.labels = true;
  }
  if (type === 'float32') {
    // Documented behaviour: NaN/±Inf voxels load as they are (core's normalizedData
    // turns them into 0, and the normalization range ignores them); the count says how many.
    const range = scanRange(data);
    meta.nonFiniteCount = range.nonFinite;
    if (range.nonFinite > 0) ctx.warnings.push(`${range.nonFinite} voxels are NaN or ±Infinity; they render as 0`);
    if (range.min <= range.max) meta.dataRange = [range.min, range.max];
  } else {
    // Integer data cannot hold NaN: the range is worked out when first read, so a load does
    // no per-voxel pass of its own (core scans again for normalization anyway).
    lazyDataRange(meta, data);
  }
  if (ctx.warnings.length) meta.warnings = [...ctx.warnings];
  const out: LoadedVolume = { format: v.format, dims, spacing, type, data, meta, name: ctx.name };
  if (C > 1) out.channels = C;
  if (v.orientation) out.orientation = v.orientation;
  if (origin) out.origin = origin;
  try {
    validateVolume(out);
  } catch (e) {
    throw new LoaderError('invalid-data', `${ctx.name}: the loaded volume is not valid (${(e as Error).message})`, {
      cause: e,
    });
  }
  return out;
}

/** `meta.dataRange` as a getter that scans once, on first read, then holds the value (enumerable, so it is cloned). */
function lazyDataRange(meta: Record<string, unknown>, data: VoxelArray): void {
  Object.defineProperty(meta, 'dataRange', {
    enumerable: true,
    configurable: true,
    get() {
      const r = scanRange(data);
      const value = r.min <= r.max ? [r.min, r.max] : undefined;
      Object.defineProperty(meta, 'dataRange', { value, enumerable: true, configurable: true, writable: true });
      return value;
    },
  });
}

/** Each channel of interleaved data box-averaged as one scalar volume is, then interleaved again. */
function downsampleChannels(
  data: VoxelArray,
  dims: readonly number[],
  f: readonly number[],
  type: VoxelType,
  C: number,
): { dims: [number, number, number]; data: VoxelArray } {
  const n = data.length / C;
  let out: VoxelArray | undefined;
  let od: [number, number, number] = [1, 1, 1];
  for (let c = 0; c < C; c++) {
    const one = new OUTPUT_ARRAY[type](n);
    for (let i = 0; i < n; i++) one[i] = data[c + C * i];
    const shrunk = downsample(one, dims, f, type);
    od = shrunk.dims;
    out ??= new OUTPUT_ARRAY[type](shrunk.data.length * C);
    for (let i = 0; i < shrunk.data.length; i++) out[c + C * i] = shrunk.data[i];
  }
  return { dims: od, data: out! };
}

/** Each `f`-sized block's first voxel (a label volume's downsample: ids are never averaged). */
export function subsample(
  data: VoxelArray,
  dims: readonly number[],
  f: readonly number[],
): { dims: [number, number, number]; data: VoxelArray } {
  const [nx, ny] = dims;
  const od = [0, 1, 2].map((i) => Math.ceil(dims[i] / f[i])) as [number, number, number];
  const out = new (data.constructor as new (n: number) => VoxelArray)(od[0] * od[1] * od[2]);
  let j = 0;
  for (let z = 0; z < od[2]; z++)
    for (let y = 0; y < od[1]; y++)
      for (let x = 0; x < od[0]; x++) out[j++] = data[x * f[0] + nx * (y * f[1] + ny * z * f[2])];
  return { dims: od, data: out };
}

/** Box-average `f`-sized blocks (partial blocks at the far edges average what they hold); NaN/±Inf are skipped. */
export function downsample(
  data: VoxelArray,
  dims: readonly number[],
  f: readonly number[],
  type: VoxelType,
): { dims: [number, number, number]; data: VoxelArray } {
  const [nx, ny, nz] = dims;
  const od = [0, 1, 2].map((i) => Math.ceil(dims[i] / f[i])) as [number, number, number];
  const n = od[0] * od[1] * od[2];
  const sum = new Float64Array(n);
  const count = new Uint32Array(n);
  const ox = new Uint32Array(nx);
  for (let x = 0; x < nx; x++) ox[x] = Math.floor(x / f[0]);
  let i = 0;
  for (let z = 0; z < nz; z++) {
    const oz = Math.floor(z / f[2]) * od[1];
    for (let y = 0; y < ny; y++) {
      const row = (oz + Math.floor(y / f[1])) * od[0];
      for (let x = 0; x < nx; x++, i++) {
        const v = data[i];
        if (v - v !== 0) continue; // NaN or ±Inf
        sum[row + ox[x]] += v;
        count[row + ox[x]]++;
      }
    }
  }
  const out = new OUTPUT_ARRAY[type](n);
  const integer = type !== 'float32';
  for (let j = 0; j < n; j++) {
    const mean = count[j] ? sum[j] / count[j] : integer ? 0 : NaN;
    out[j] = integer ? Math.round(mean) : mean;
  }
  return { dims: od, data: out };
}
