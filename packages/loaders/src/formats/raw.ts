import type { VoxelType } from '@vpt/core';
import { LoaderError } from '../errors.js';
import type { LoadContext } from '../context.js';
import type { LoadedVolume, RawOptions } from '../types.js';
import { finishVolume } from '../convert/finish.js';
import { checkDims, checkFits, SOURCE_BYTES } from '../convert/size.js';
import { OUTPUT_BYTES, readSamples, toVoxelArray } from '../convert/voxels.js';
import { orientationFromAxisCodes } from './orientation.js';

const RAW_TYPES: readonly VoxelType[] = ['uint8', 'uint16', 'int16', 'float32'];

/** A raw description after checking: what the bytes need to be read. */
export interface RawDescription extends Required<RawOptions> {
  /** The raw file's name (a sidecar's `file`), resolved against the sidecar. */
  file?: string;
  meta: Record<string, unknown>;
}

/** Check options.raw (or a sidecar's fields); anything wrong is a 'bad-header' error naming the field. */
export function checkRawOptions(raw: Partial<RawOptions> | undefined, ctx: LoadContext, source = 'options.raw'): Required<RawOptions> {
  if (!raw || typeof raw !== 'object') {
    throw new LoaderError('bad-header', `${ctx.name}: raw data has no header; pass options.raw = { dims: [NX, NY, NZ], type } or a JSON sidecar next to it`);
  }
  // Numbers only: "dims": ["256", …] is a mistake to report, not to convert silently.
  if (Array.isArray(raw.dims) && raw.dims.some((d) => typeof d !== 'number')) {
    throw new LoaderError('bad-header', `${ctx.name}: ${source} dims ${JSON.stringify(raw.dims)} must be numbers, not strings`);
  }
  const dims = Array.isArray(raw.dims) ? raw.dims.map(Number) : [];
  checkDims(dims, ctx, source);
  if (!RAW_TYPES.includes(raw.type as VoxelType)) {
    throw new LoaderError('bad-header', `${ctx.name}: ${source} type "${String(raw.type)}" is not one of ${RAW_TYPES.join(', ')}`);
  }
  const spacing = raw.spacing === undefined ? [1, 1, 1] : Array.isArray(raw.spacing) && raw.spacing.every((x) => typeof x === 'number') ? raw.spacing.map(Number) : [];
  if (spacing.length !== 3 || spacing.some((s) => !Number.isFinite(s) || s <= 0)) {
    throw new LoaderError('bad-header', `${ctx.name}: ${source} spacing [${String(raw.spacing)}] must be three positive numbers`);
  }
  const endianness = raw.endianness ?? 'little';
  if (endianness !== 'little' && endianness !== 'big') {
    throw new LoaderError('bad-header', `${ctx.name}: ${source} endianness "${String(endianness)}" must be "little" or "big"`);
  }
  return { dims: dims as [number, number, number], type: raw.type as RawOptions['type'], spacing: spacing as [number, number, number], endianness };
}

/**
 * Parse a JSON sidecar in the format of the project's data folder: dims, voxel_type,
 * endianness, spacing (plus file, value_range, sha256… kept in meta).
 */
export function parseSidecar(text: string, ctx: LoadContext): RawDescription {
  let json: Record<string, unknown>;
  try {
    json = JSON.parse(text);
  } catch (e) {
    throw new LoaderError('bad-header', `${ctx.name}: the sidecar is not valid JSON (${(e as Error).message})`, { cause: e });
  }
  if (!json || typeof json !== 'object' || Array.isArray(json)) throw new LoaderError('bad-header', `${ctx.name}: the sidecar must be a JSON object`);
  if (json.layout !== undefined && typeof json.layout === 'string' && !/x fastest/i.test(json.layout)) {
    throw new LoaderError('unsupported', `${ctx.name}: layout "${json.layout}" is not supported; vpt reads x-fastest data (index = x + NX·(y + NY·z))`);
  }
  const raw = checkRawOptions({
    dims: json.dims as RawOptions['dims'],
    type: (json.voxel_type ?? json.type) as RawOptions['type'],
    spacing: json.spacing as RawOptions['spacing'],
    endianness: json.endianness as RawOptions['endianness'],
  }, ctx, 'sidecar');
  const vr = json.value_range;
  // An inverted range (min > max) is a deliberate inverted mapping; an empty or non-numeric one is a mistake.
  if (vr !== undefined && (!Array.isArray(vr) || vr.length !== 2 || !vr.every((x) => typeof x === 'number' && Number.isFinite(x)) || vr[0] === vr[1])) {
    throw new LoaderError('bad-header', `${ctx.name}: sidecar value_range ${JSON.stringify(vr)} must be two different finite numbers`);
  }
  const meta: Record<string, unknown> = {};
  for (const key of ['title', 'modality', 'units', 'spacing_units', 'orientation', 'value_range', 'sha256', 'license', 'source']) {
    if (json[key] !== undefined) meta[key === 'spacing_units' ? 'spacingUnits' : key] = json[key];
  }
  if (json.axes !== undefined) {
    // "axes": 'PIR'… — the anatomical direction each index axis runs toward (RAS+ world).
    if (typeof json.axes !== 'string' || !orientationFromAxisCodes(json.axes)) {
      throw new LoaderError('bad-header', `${ctx.name}: sidecar axes ${JSON.stringify(json.axes)} must be three letters, one of R/L, A/P and S/I each (like "RAS" or "PIR")`);
    }
    meta.axisCodes = json.axes.toUpperCase();
    meta.space = 'RAS';
  }
  const file = typeof json.file === 'string' && json.file ? json.file : undefined;
  return { ...raw, file, meta };
}

/** dims and type from a name like `head_256x256x108_int16.raw` (the data folder's pattern). */
export function rawFromName(name: string): RawOptions | undefined {
  const m = /(\d+)x(\d+)x(\d+)_(uint8|uint16|int16|float32)\.raw$/i.exec(name);
  return m ? { dims: [Number(m[1]), Number(m[2]), Number(m[3])], type: m[4].toLowerCase() as RawOptions['type'] } : undefined;
}

/** Headerless raw voxels: the byte count must match dims × type exactly. */
export function decodeRaw(bytes: Uint8Array, raw: Required<RawOptions>, ctx: LoadContext, meta: Record<string, unknown> = {}): LoadedVolume {
  const { dims, type } = raw;
  checkDims(dims, ctx, 'raw description');
  const count = dims[0] * dims[1] * dims[2];
  const need = count * SOURCE_BYTES[type];
  if (bytes.length < need) {
    throw new LoaderError('truncated', `${ctx.name}: dims [${dims.join(' × ')}] of ${type} need ${need} bytes but the file has ${bytes.length}; it is cut short, or the dims/type are wrong`);
  }
  if (bytes.length > need) {
    const fits = RAW_TYPES.filter((t) => count * SOURCE_BYTES[t] === bytes.length);
    throw new LoaderError('bad-header', `${ctx.name}: the file has ${bytes.length} bytes but dims [${dims.join(' × ')}] of ${type} need ${need}`
      + (fits.length ? `; did you mean type ${fits.join(' or ')}?` : '; check the dims and type'));
  }
  checkFits(dims, OUTPUT_BYTES[type], ctx);
  ctx.progress('convert', 0, count);
  const data = toVoxelArray(readSamples(bytes, 0, count, type, raw.endianness === 'little'), type);
  ctx.progress('convert', count, count);
  return finishVolume({
    format: 'raw', dims: [...dims], spacing: [...raw.spacing], type, data,
    orientation: typeof meta.axisCodes === 'string' ? orientationFromAxisCodes(meta.axisCodes) ?? undefined : undefined,
    meta: { ...meta, endianness: raw.endianness },
  }, ctx);
}
