import { LoaderError } from '../errors.js';
import type { LoadContext } from '../context.js';
import type { LoadedVolume } from '../types.js';
import { finishVolume } from '../convert/finish.js';
import { checkAvailable, checkDims, checkFits, SOURCE_BYTES, type SourceType } from '../convert/size.js';
import {
  chooseTypeOf,
  ownsMemory,
  readSamples,
  toVoxelArray,
  IDENTITY,
  OUTPUT_BYTES,
  SOURCE_ARRAY,
  type SourceArray,
} from '../convert/voxels.js';
import { gunzip } from '../io/gzip.js';
import { directionCosines, isFiniteVector } from './orientation.js';

/*
 * NRRD (teem's "nearly raw raster data", https://teem.sourceforge.net/nrrd/format.html).
 * The header is a few lines of "field: value" text; the npm packages that parse it are
 * unmaintained (nrrd-js, 2016) and read neither gzip nor detached data, so this short
 * reader follows the spec directly and leaves gzip to fflate.
 */

const MAX_HEADER = 1 << 20; // 1 MiB of header text is far past any real file

const TYPES: Record<string, SourceType> = {};
for (const [type, names] of Object.entries({
  int8: ['signed char', 'int8', 'int8_t'],
  uint8: ['uchar', 'unsigned char', 'uint8', 'uint8_t'],
  int16: ['short', 'short int', 'signed short', 'signed short int', 'int16', 'int16_t'],
  uint16: ['ushort', 'unsigned short', 'unsigned short int', 'uint16', 'uint16_t'],
  int32: ['int', 'signed int', 'int32', 'int32_t'],
  uint32: ['uint', 'unsigned int', 'uint32', 'uint32_t'],
  float32: ['float'],
  float64: ['double'],
}))
  for (const n of names) TYPES[n] = type as SourceType;

const UNSUPPORTED_TYPES = [
  'longlong',
  'long long',
  'long long int',
  'signed long long',
  'signed long long int',
  'int64',
  'int64_t',
  'ulonglong',
  'unsigned long long',
  'unsigned long long int',
  'uint64',
  'uint64_t',
  'block',
];

export interface NrrdHeader {
  fields: Record<string, string>;
  keyValues: Record<string, string>;
  /** Byte offset of the data in the same file (after the blank line). */
  dataStart: number;
}

export function hasNrrdMagic(bytes: Uint8Array): boolean {
  return (
    bytes.length >= 8 &&
    String.fromCharCode(...bytes.subarray(0, 7)) === 'NRRD000' &&
    bytes[7] >= 0x30 &&
    bytes[7] <= 0x39
  );
}

/** Split the header text into fields (`name: value`) and key/values (`key:=value`). */
export function parseNrrdHeader(bytes: Uint8Array, ctx: LoadContext): NrrdHeader {
  if (!hasNrrdMagic(bytes))
    throw new LoaderError('bad-magic', `${ctx.name} is not NRRD: it does not start with "NRRD000x"`);
  // The header ends at the first empty line (or at the end of a detached .nhdr).
  let end = -1,
    dataStart = bytes.length;
  const limit = Math.min(bytes.length, MAX_HEADER);
  for (let i = 0; i < limit; i++) {
    if (bytes[i] !== 0x0a) continue;
    if (bytes[i + 1] === 0x0a) {
      end = i;
      dataStart = i + 2;
      break;
    }
    if (bytes[i + 1] === 0x0d && bytes[i + 2] === 0x0a) {
      end = i;
      dataStart = i + 3;
      break;
    }
  }
  if (end < 0) {
    if (bytes.length > MAX_HEADER)
      throw new LoaderError(
        'bad-header',
        `${ctx.name}: no empty line ends the NRRD header within its first ${MAX_HEADER} bytes`,
      );
    end = bytes.length;
  }
  const text = new TextDecoder('latin1').decode(bytes.subarray(0, end));
  const fields: Record<string, string> = {};
  const keyValues: Record<string, string> = {};
  const lines = text.split(/\r?\n/);
  for (let n = 1; n < lines.length; n++) {
    const line = lines[n];
    if (line === '' || line.startsWith('#')) continue;
    const kv = line.indexOf(':=');
    const colon = line.indexOf(': ');
    if (kv >= 0 && (colon < 0 || kv < colon)) {
      keyValues[line.slice(0, kv)] = line.slice(kv + 2);
      continue;
    }
    if (colon < 0)
      throw new LoaderError(
        'bad-header',
        `${ctx.name}: NRRD header line ${n + 1} "${line.slice(0, 60)}" is not "field: value"`,
      );
    fields[line.slice(0, colon).trim().toLowerCase()] = line.slice(colon + 2).trim();
  }
  return { fields, keyValues, dataStart };
}

/** Data past the size the header declares is ignored, with a warning (it may mean wrong dims). */
function warnExtra(extra: number, ctx: LoadContext): void {
  if (extra > 0)
    ctx.warnings.push(`${extra} bytes past the data the header declares are ignored; check the sizes and type`);
}

function numbers(text: string | undefined): number[] {
  return text === undefined ? [] : text.trim().split(/\s+/).map(Number);
}

/** `(1,0,0) (0,1,0) none …` → vectors of `spaceDim` numbers (null for "none"); a 2D space's gain z = 0. */
function rawVectors(text: string, ctx: LoadContext, field: string, spaceDim = 3): (number[] | null)[] {
  const out: (number[] | null)[] = [];
  const re = /\(([^)]*)\)|none/g;
  let m: RegExpExecArray | null;
  while ((m = re.exec(text))) out.push(m[1] === undefined ? null : m[1].split(',').map(Number));
  if (out.some((v) => v && (v.length !== spaceDim || !isFiniteVector(v)))) {
    throw new LoaderError(
      'bad-header',
      `${ctx.name}: NRRD "${field}: ${text.slice(0, 80)}" must hold vectors of ${spaceDim} numbers (the space dimension)`,
    );
  }
  // A 2D space (x, y) is embedded in 3D at z = 0.
  return out.map((v) => (v && v.length < 3 ? [...v, 0, 0].slice(0, 3) : v));
}

/** The spatial part (x, y, z) of each vector: a space-time space's vectors drop their time part. */
function vectors(text: string, ctx: LoadContext, field: string, spaceDim = 3): (number[] | null)[] {
  return rawVectors(text, ctx, field, spaceDim).map((v) => (v ? v.slice(0, 3) : v));
}

/**
 * The space's dimension: "space dimension" (2 or 3), or 3 for a named space, 4 for a named
 * space-time one ("right-anterior-superior-time"…: x, y, z and time), whose vectors have a
 * fourth, time, component. An unnamed 4D space is refused.
 */
function spaceDimension(fields: Record<string, string>, ctx: LoadContext): number {
  const named = fields.space?.toLowerCase();
  if (named !== undefined && !(named in SPACES))
    throw new LoaderError(
      'unsupported',
      `${ctx.name}: NRRD space "${fields.space}" is not supported; vpt reads 2D, 3D and 3D-with-time spaces (${Object.keys(SPACES).join(', ')})`,
    );
  const given = fields['space dimension'];
  if (named !== undefined && SPACE_TIME.has(named)) {
    if (given !== undefined && Number(given) !== 4)
      throw new LoaderError(
        'bad-header',
        `${ctx.name}: NRRD space "${fields.space}" is a space-time (4D) but "space dimension" is ${given}`,
      );
    return 4;
  }
  if (given === undefined) return 3;
  const n = Number(given);
  if (n !== 2 && n !== 3)
    throw new LoaderError(
      'unsupported',
      `${ctx.name}: NRRD "space dimension: ${given}" is not supported; vpt reads 2D and 3D spaces, and the named 3D-with-time ones (space dimension 4)`,
    );
  return n;
}

/** NRRD axis kinds that are positions in space (teem's nrrdKindDomain / nrrdKindSpace). */
const SPATIAL_KINDS = new Set(['domain', 'space']);
/** Kinds of an axis along which the file holds several volumes in time (teem's nrrdKindTime). */
const TIME_KINDS = new Set(['time']);
/**
 * Kinds of an axis that holds several values per voxel which vpt reads as channels
 * (teem's list, point, vector and colour kinds): a multichannel volume, channel fastest.
 */
const CHANNEL_KINDS = new Set([
  'list',
  'point',
  'vector',
  'covariant-vector',
  'normal',
  '2-vector',
  '3-color',
  'rgb-color',
  'hsv-color',
  'xyz-color',
  '4-color',
  'rgba-color',
  '3-vector',
  '3-gradient',
  '3-normal',
  '4-vector',
]);
/** Most channels a Volume holds (core's MAX_VOLUME_CHANNELS). */
const MAX_CHANNELS = 16;

/** Which file axes are x, y, z, the channel axis and the time axis (at most one each). */
export interface NrrdLayout {
  spatial: number[];
  /** The axis of the values per voxel (channels), if any longer than 1. */
  channelAxis?: number;
  /** The axis of the time steps, if any longer than 1. */
  timeAxis?: number;
  channels: number;
  timeSteps: number;
}

/**
 * Which axes are the volume's x, y, z, which one (if any) holds channels and which one time
 * steps. An axis is spatial when its space direction is a spatial vector (not "none"), else
 * when its kind is domain or space (the first three; a fourth domain axis is time), else (no
 * directions, no kinds) the first three axes longer than 1. Of the other axes, length-1 ones
 * are dropped wherever they are; a longer one is time when its kind is time or domain (or,
 * in a space-time space, its direction has only a time part), channels when its kind is a
 * list, point, vector or colour kind; an axis of no (or an unknown) kind is channels before
 * the last spatial axis (values per voxel, NRRD's usual order) and time after it.
 */
function volumeAxes(fields: Record<string, string>, sizes: number[], spaceDim: number, ctx: LoadContext): NrrdLayout {
  const n = sizes.length;
  const kinds = fields.kinds?.trim().split(/\s+/);
  const kindAt = (i: number) => (kinds && kinds.length === n ? kinds[i].toLowerCase() : '');
  // Axes the header itself says are time (a space-time direction with only its time part).
  const timeByDirection = new Set<number>();
  let spatial: boolean[];
  if (fields['space directions']) {
    const dirs = rawVectors(fields['space directions'], ctx, 'space directions', spaceDim);
    if (dirs.length !== n)
      throw new LoaderError(
        'bad-header',
        `${ctx.name}: NRRD space directions has ${dirs.length} entries for ${n} axes`,
      );
    spatial = dirs.map((v, i) => {
      if (!v) return false;
      if (spaceDim === 4 && v[0] === 0 && v[1] === 0 && v[2] === 0) {
        timeByDirection.add(i);
        return false;
      }
      return true;
    });
  } else if (kinds && kinds.length === n) {
    spatial = kinds.map((k) => SPATIAL_KINDS.has(k.toLowerCase()));
    if (spatial.filter(Boolean).length > 3) {
      // "domain domain domain domain" (x, y, z, t): "space" axes first, else the first three.
      const space = kinds.map((k) => k.toLowerCase() === 'space');
      const nSpace = space.filter(Boolean).length;
      if (nSpace >= 1 && nSpace <= 3) spatial = space;
      else {
        let left = 3;
        spatial = spatial.map((s) => s && left-- > 0);
      }
    }
  } else {
    // No geometry at all: the first three axes longer than 1 (all of them when there are fewer).
    const long = sizes.filter((s) => s > 1).length;
    if (n <= 3) spatial = sizes.map(() => true);
    else if (long <= 3) {
      // Drop length-1 axes, leading first, until three are left (as before).
      spatial = sizes.map(() => true);
      for (let i = 0, left = n; i < n && left > 3; i++)
        if (sizes[i] === 1) {
          spatial[i] = false;
          left--;
        }
      for (let i = n - 1, left = spatial.filter(Boolean).length; i >= 0 && left > 3; i--)
        if (sizes[i] === 1 && spatial[i]) {
          spatial[i] = false;
          left--;
        }
    } else {
      let left = 3;
      spatial = sizes.map((s) => s > 1 && left-- > 0);
    }
  }
  const kindOf = (i: number) => (kindAt(i) ? `"${kinds![i]}"` : `${i}th`);
  const idx = spatial.flatMap((s, i) => (s ? [i] : []));
  if (idx.length > 3)
    throw new LoaderError(
      'unsupported',
      `${ctx.name}: a NRRD with ${idx.length} spatial axes (sizes ${sizes.join(' ')}) is not supported; vpt reads 1D to 3D volumes`,
    );
  if (idx.length === 0)
    throw new LoaderError('bad-header', `${ctx.name}: no NRRD axis is spatial (space directions or kinds)`);
  const layout: NrrdLayout = { spatial: idx, channels: 1, timeSteps: 1 };
  for (let i = 0; i < n; i++) {
    if (spatial[i] || sizes[i] === 1) continue;
    const kind = kindAt(i);
    const role: 'time' | 'channel' | 'refused' =
      timeByDirection.has(i) || TIME_KINDS.has(kind) || SPATIAL_KINDS.has(kind)
        ? 'time'
        : CHANNEL_KINDS.has(kind)
          ? 'channel'
          : kind === '' || kind === '???' || kind === 'none'
            ? i < idx[idx.length - 1]
              ? 'channel'
              : 'time'
            : 'refused';
    if (role === 'refused')
      throw new LoaderError(
        'unsupported',
        `${ctx.name}: NRRD axis ${i} (kind ${kindOf(i)}, size ${sizes[i]}) holds ${sizes[i]} values per voxel of a kind vpt does not read (tensors, complex numbers…); vpt reads scalars, channels (list, vector, colour kinds) and time steps`,
      );
    const field = role === 'time' ? 'timeAxis' : 'channelAxis';
    const other = layout[field];
    if (other !== undefined)
      throw new LoaderError(
        'unsupported',
        `${ctx.name}: NRRD axes ${other} (kind ${kindOf(other)}, size ${sizes[other]}) and ${i} (kind ${kindOf(i)}, size ${sizes[i]}) are both ${role === 'time' ? 'time axes' : 'values per voxel'}; vpt reads one channel axis and one time axis`,
      );
    layout[field] = i;
    if (role === 'time') layout.timeSteps = sizes[i];
    else {
      if (sizes[i] > MAX_CHANNELS)
        throw new LoaderError(
          'unsupported',
          `${ctx.name}: NRRD axis ${i} (kind ${kindOf(i)}) holds ${sizes[i]} values per voxel; vpt reads at most ${MAX_CHANNELS} channels (MAX_VOLUME_CHANNELS)`,
        );
      layout.channels = sizes[i];
    }
  }
  return layout;
}

/** ISIZE, the last 4 bytes of a gzip member: its inflated length mod 2^32 (RFC 1952 §2.3.1). */
function gzipTrailerSize(gz: Uint8Array): number {
  if (gz.length < 18) return 0;
  const t = gz.length - 4;
  return (gz[t] | (gz[t + 1] << 8) | (gz[t + 2] << 16) | (gz[t + 3] << 24)) >>> 0;
}

const SPACES: Record<string, string> = {
  'right-anterior-superior': 'RAS',
  ras: 'RAS',
  'left-anterior-superior': 'LAS',
  las: 'LAS',
  'left-posterior-superior': 'LPS',
  lps: 'LPS',
  'scanner-xyz': 'scanner-xyz',
  '3d-right-handed': '3D-right-handed',
  '3d-left-handed': '3D-left-handed',
  'right-anterior-superior-time': 'RAS',
  rast: 'RAS',
  'left-anterior-superior-time': 'LAS',
  last: 'LAS',
  'left-posterior-superior-time': 'LPS',
  lpst: 'LPS',
  'scanner-xyz-time': 'scanner-xyz',
  '3d-right-handed-time': '3D-right-handed',
  '3d-left-handed-time': '3D-left-handed',
};
/** The named spaces with a time axis (space dimension 4). */
const SPACE_TIME = new Set([
  'right-anterior-superior-time',
  'rast',
  'left-anterior-superior-time',
  'last',
  'left-posterior-superior-time',
  'lpst',
  'scanner-xyz-time',
  '3d-right-handed-time',
  '3d-left-handed-time',
]);

export interface DetachedResolver {
  /** Bytes of a file named relative to the header (a URL next to it, or one of the dropped files). */
  (name: string): Promise<Uint8Array>;
}

/** NRRD with raw, gzip, ascii or hex encoding, attached or detached data, spatial axes via space directions or spacings. */
export async function decodeNrrd(
  bytes: Uint8Array,
  ctx: LoadContext,
  resolve?: DetachedResolver,
): Promise<LoadedVolume> {
  const { fields, keyValues, dataStart } = parseNrrdHeader(bytes, ctx);
  const need = (f: string) => {
    const v = fields[f];
    if (v === undefined) throw new LoaderError('bad-header', `${ctx.name}: the NRRD header has no "${f}" field`);
    return v;
  };
  const typeName = need('type').toLowerCase();
  const source = TYPES[typeName];
  if (!source) {
    if (UNSUPPORTED_TYPES.includes(typeName))
      throw new LoaderError(
        'unsupported',
        `${ctx.name}: NRRD type "${typeName}" is not supported; vpt reads 8/16/32-bit integer, float and double`,
      );
    throw new LoaderError('bad-header', `${ctx.name}: "${typeName}" is not an NRRD type`);
  }
  const dimension = Number(need('dimension'));
  const sizes = numbers(need('sizes'));
  if (!Number.isInteger(dimension) || dimension < 1 || sizes.length !== dimension) {
    throw new LoaderError(
      'bad-header',
      `${ctx.name}: NRRD dimension ${fields.dimension} does not match sizes "${fields.sizes}"`,
    );
  }
  const spaceDim = spaceDimension(fields, ctx);
  if (!sizes.every((s) => Number.isInteger(s) && s >= 0))
    throw new LoaderError('bad-header', `${ctx.name}: NRRD sizes "${fields.sizes}" must be whole numbers`);
  const layout = volumeAxes(fields, sizes, spaceDim, ctx);
  const axes = layout.spatial;
  const dims = [0, 1, 2].map((i) => (i < axes.length ? sizes[axes[i]] : 1));
  checkDims(dims, ctx, 'NRRD header');
  if (sizes.includes(0))
    throw new LoaderError('empty', `${ctx.name}: NRRD sizes "${fields.sizes}" hold no samples (an axis of size 0)`);
  const count = dims[0] * dims[1] * dims[2];
  const C = layout.channels;
  const T = layout.timeSteps;
  // Without a time axis a step above 0 is refused by loadVolume (no meta.timeSteps): one volume.
  if (layout.timeAxis !== undefined && ctx.time >= T)
    throw new LoaderError(
      'bad-header',
      `${ctx.name}: time step ${ctx.time} does not exist (the NRRD holds ${T} along its time axis (axis ${layout.timeAxis}), 0 to ${T - 1})`,
    );
  if (T > 1)
    ctx.warnings.push(
      `the file holds ${T} volumes along its time axis (axis ${layout.timeAxis}); volume ${ctx.time} is loaded (LoadOptions.time picks the time step)`,
    );
  const size = SOURCE_BYTES[source];
  const endian = (fields.endian ?? 'little').toLowerCase();
  if (endian !== 'little' && endian !== 'big')
    throw new LoaderError('bad-header', `${ctx.name}: NRRD endian "${fields.endian}" must be little or big`);
  if (size > 1 && fields.endian === undefined)
    ctx.warnings.push('the NRRD header has no endian field; little-endian assumed');

  const encoding = (fields.encoding ?? '').toLowerCase();
  const outBytes = source === 'uint8' ? 1 : SOURCE_BYTES[source] <= 2 ? 2 : 4;
  checkFits(dims, Math.min(outBytes, OUTPUT_BYTES.float32) * C, ctx);

  // Samples in the file: axis a's stride is the product of the sizes before it (axis 0 fastest).
  const strides: number[] = [];
  let total = 1;
  for (const s of sizes) {
    strides.push(total);
    total *= s;
  }
  // The samples of time step ctx.time span [lo, hi): one contiguous run when time is the slowest axis.
  const lo = layout.timeAxis === undefined ? 0 : ctx.time * strides[layout.timeAxis];
  const hi = lo + 1 + sizes.reduce((n, s, a) => (a === layout.timeAxis ? n : n + (s - 1) * strides[a]), 0);
  const values = count * C;
  // Steps inflated to reach this one: those before it when time is the slowest axis, else all.
  const timeSlowest = layout.timeAxis === undefined || sizes.every((s, a) => a <= layout.timeAxis! || s === 1);
  const stepsInflated = timeSlowest ? ctx.time + 1 : T;

  // Where the data is: after the header, or a detached file.
  const dataFile = fields['data file'] ?? fields.datafile;
  let data = bytes.subarray(dataStart);
  if (dataFile !== undefined) {
    if (/^LIST\b/.test(dataFile) || /%/.test(dataFile) || /\s/.test(dataFile.trim())) {
      throw new LoaderError(
        'unsupported',
        `${ctx.name}: NRRD "data file: ${dataFile}" names several files; vpt reads one detached data file`,
      );
    }
    if (!resolve) {
      throw new LoaderError(
        'unsupported',
        `${ctx.name}: the data is in a separate file "${dataFile}"; load the header by URL, or drop both files together`,
      );
    }
    data = await resolve(dataFile);
  }
  const lineSkip = Number(fields['line skip'] ?? fields.lineskip ?? 0);
  const byteSkip = Number(fields['byte skip'] ?? fields.byteskip ?? 0);
  if (!Number.isInteger(lineSkip) || lineSkip < 0 || !Number.isInteger(byteSkip) || byteSkip < -1) {
    throw new LoaderError(
      'bad-header',
      `${ctx.name}: NRRD line skip ${lineSkip} / byte skip ${byteSkip} must be whole numbers ≥ 0 (byte skip may be -1)`,
    );
  }
  for (let l = 0; l < lineSkip; l++) {
    const nl = data.indexOf(0x0a);
    if (nl < 0)
      throw new LoaderError(
        'truncated',
        `${ctx.name}: the data ends before the ${lineSkip} lines "line skip" asks to skip`,
      );
    data = data.subarray(nl + 1);
  }

  const dataBytes = total * size;
  // One step of several, or channels not already interleaved, are copied out of the file's bytes.
  const whole = T === 1 && isInterleaved(layout, sizes, strides, dims) && hi - lo === values;
  let samples: SourceArray;
  ctx.progress('convert', 0, values);
  if (encoding === 'raw') {
    if (byteSkip === -1) {
      checkAvailable(data.length, dataBytes, ctx);
      data = data.subarray(data.length - dataBytes);
    } else {
      checkAvailable(data.length - byteSkip, dataBytes, ctx);
      warnExtra(data.length - byteSkip - dataBytes, ctx);
      data = data.subarray(byteSkip);
    }
    samples = readSamples(
      data,
      lo * size,
      hi - lo,
      source,
      endian === 'little',
      whole && ownsMemory(data, ctx.borrowed),
    );
  } else if (encoding === 'gzip' || encoding === 'gz') {
    const skip = Math.max(0, byteSkip);
    const inflated = await gunzip(data, ctx, {
      // Peak inflated memory is bounded by limits.maxBytes per step up to the one asked for (plus the skipped bytes).
      maxOutput: ctx.downsample ? Number.MAX_SAFE_INTEGER : skip + ctx.limits.maxBytes * stepsInflated,
      // The header already says the size: allocate once, and stop at it (the end of the step asked for).
      // "byte skip: -1" means the data is the *last* dataBytes of the inflated stream, so the
      // whole stream is kept: its length is the gzip trailer's ISIZE (checked after inflating).
      headBytes: 0,
      onHead: () =>
        byteSkip === -1
          ? Math.max(dataBytes, gzipTrailerSize(data))
          : { keep: byteSkip + hi * size, declared: byteSkip + dataBytes },
    });
    const from = byteSkip === -1 ? Math.max(0, inflated.length - dataBytes) : byteSkip;
    if (byteSkip !== -1 && inflated.length >= from + dataBytes) warnExtra(inflated.length - from - dataBytes, ctx);
    checkAvailable(inflated.length - from, byteSkip === -1 ? dataBytes : hi * size, ctx);
    samples = readSamples(inflated, from + lo * size, hi - lo, source, endian === 'little', whole);
  } else if (encoding === 'ascii' || encoding === 'text' || encoding === 'txt') {
    samples = parseAscii(data, hi, source, ctx).subarray(lo);
  } else if (encoding === 'hex') {
    samples = readSamples(parseHex(data, hi * size, ctx), lo * size, hi - lo, source, endian === 'little');
  } else if (encoding === 'bzip2' || encoding === 'bz2') {
    throw new LoaderError(
      'unsupported',
      `${ctx.name}: NRRD bzip2 encoding is not supported; re-save with gzip or raw encoding (e.g. unu save -e gzip)`,
    );
  } else {
    throw new LoaderError(
      'bad-header',
      `${ctx.name}: NRRD encoding "${fields.encoding ?? ''}" is not raw, gzip, ascii, hex or bzip2`,
    );
  }
  if (!(hi - lo === values && isInterleaved(layout, sizes, strides, dims)))
    samples = gather(samples, layout, strides, dims);

  const type = chooseTypeOf(samples, source, IDENTITY, ctx.warnings);
  const voxels = toVoxelArray(samples, type, IDENTITY);
  ctx.progress('convert', values, values);

  // Geometry: space directions (columns of the index→world matrix) or spacings.
  let spacing: [number, number, number] = [1, 1, 1];
  let orientation: number[] | undefined;
  let origin: [number, number, number] | undefined;
  const meta: Record<string, unknown> = { encoding, datatype: source, endianness: endian };
  if (layout.timeAxis !== undefined) {
    meta.timeSteps = T;
    meta.timeAxis = layout.timeAxis;
    const stepSeconds = timeStep(fields, layout.timeAxis);
    if (stepSeconds !== undefined) meta.stepSeconds = stepSeconds;
  }
  if (layout.channelAxis !== undefined) {
    meta.channelAxis = layout.channelAxis;
    const kind = fields.kinds?.trim().split(/\s+/)[layout.channelAxis];
    if (kind) meta.channelKind = kind;
  }
  if (fields['space directions']) {
    const dirs = vectors(fields['space directions'], ctx, 'space directions', spaceDim);
    const spatial = axes.map((a) => dirs[a]!);
    const cols = [0, 1, 2].map((i) => spatial[i] ?? [0, 0, 0]);
    // A 1D or 2D image: the missing axes are unit vectors perpendicular to the given ones.
    if (spatial.length === 1)
      cols[1] = cross(cols[0], Math.abs(cols[0][0]) < 0.9 * Math.hypot(...cols[0]) ? [1, 0, 0] : [0, 1, 0]);
    if (spatial.length < 3) cols[2] = cross(cols[0], cols[1]);
    const cos = directionCosines(cols);
    if (!cos) throw new LoaderError('bad-header', `${ctx.name}: NRRD space directions has a zero-length axis`);
    // Collinear (or coplanar) axes span no volume: index → world is not invertible.
    const o = cos.orientation;
    const det =
      o[0] * (o[4] * o[8] - o[5] * o[7]) - o[1] * (o[3] * o[8] - o[5] * o[6]) + o[2] * (o[3] * o[7] - o[4] * o[6]);
    if (!(Math.abs(det) > 1e-6))
      throw new LoaderError(
        'bad-header',
        `${ctx.name}: NRRD space directions "${fields['space directions'].slice(0, 80)}" are collinear or coplanar (the axes span no volume)`,
      );
    orientation = cos.orientation;
    spacing = cos.lengths.map((l, i) => (i < spatial.length ? l : 1)) as [number, number, number];
  } else if (fields.spacings) {
    const s = numbers(fields.spacings);
    spacing = [0, 1, 2].map((i) => {
      if (i >= axes.length) return 1;
      const v = Math.abs(s[axes[i]]);
      if (Number.isFinite(v) && v > 0) return v;
      // As NIfTI does for pixdim: say so rather than silently use 1.
      if (dims[i] > 1 || s[axes[i]] !== undefined)
        ctx.warnings.push(`NRRD spacings[${axes[i]}] = ${s[axes[i]]} is not a positive finite size; 1 used`);
      return 1;
    }) as [number, number, number];
  }
  if (fields['space origin']) {
    const o = vectors(fields['space origin'], ctx, 'space origin', spaceDim)[0];
    if (o) origin = [o[0], o[1], o[2]];
  }
  const space = fields.space?.toLowerCase();
  if (space) meta.space = SPACES[space] ?? fields.space;
  if (fields['space units']) meta.spaceUnits = fields['space units'];
  if (Object.keys(keyValues).length) meta.keyValues = keyValues;
  return finishVolume(
    {
      format: 'nrrd',
      dims: dims as [number, number, number],
      spacing,
      type,
      data: voxels,
      orientation,
      origin,
      meta,
      ...(C > 1 ? { channels: C } : {}),
    },
    ctx,
  );
}

/** Are the step's samples already value(c, x, y, z) = src[c + C·(x + NX·(y + NY·z))] (channel fastest, x, y, z)? */
function isInterleaved(layout: NrrdLayout, sizes: number[], strides: number[], dims: number[]): boolean {
  const want = outputStrides(layout, dims);
  const axes = [layout.channelAxis, ...layout.spatial];
  return axes.every((a, k) => a === undefined || sizes[a] === 1 || strides[a] === want[k]);
}

/** Strides of channel, x, y, z in the interleaved output. */
function outputStrides(layout: NrrdLayout, dims: number[]): number[] {
  const C = layout.channels;
  return [1, C, C * dims[0], C * dims[0] * dims[1]];
}

/**
 * The step's samples (starting at its first one) reordered to channel fastest, then x, y, z:
 * the order core's multichannel Volume holds (a channel axis last, or a time axis between
 * the others, is a strided read).
 */
function gather(src: SourceArray, layout: NrrdLayout, strides: number[], dims: number[]): SourceArray {
  const C = layout.channels;
  const sc = layout.channelAxis === undefined ? 0 : strides[layout.channelAxis];
  const [sx, sy, sz] = [0, 1, 2].map((i) => (i < layout.spatial.length ? strides[layout.spatial[i]] : 0));
  const [nx, ny, nz] = dims;
  const out = new (src.constructor as new (n: number) => SourceArray)(C * nx * ny * nz);
  let i = 0;
  for (let z = 0; z < nz; z++)
    for (let y = 0; y < ny; y++) {
      const row = y * sy + z * sz;
      for (let x = 0; x < nx; x++) {
        const at = row + x * sx;
        for (let c = 0; c < C; c++) out[i++] = src[at + c * sc];
      }
    }
  return out;
}

/** Seconds per time step: the time axis's spacing in a time unit the header names ("units"), else none. */
function timeStep(fields: Record<string, string>, axis: number): number | undefined {
  const spacing = Number(fields.spacings?.trim().split(/\s+/)[axis]);
  const unit = fields.units
    ?.match(/"([^"]*)"/g)
    ?.[axis]?.replace(/"/g, '')
    .trim()
    .toLowerCase();
  const perUnit: Record<string, number> = {
    s: 1,
    sec: 1,
    second: 1,
    seconds: 1,
    ms: 1e-3,
    msec: 1e-3,
    us: 1e-6,
    µs: 1e-6,
  };
  const k = unit === undefined ? undefined : perUnit[unit];
  return k !== undefined && Number.isFinite(spacing) && spacing > 0 ? spacing * k : undefined;
}

function cross(a: number[], b: number[]): number[] {
  const c = [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]];
  const l = Math.hypot(c[0], c[1], c[2]);
  return l > 0 ? c.map((x) => x / l) : [0, 0, 1];
}

function parseAscii(data: Uint8Array, count: number, source: SourceType, ctx: LoadContext): SourceArray {
  const words = new TextDecoder('latin1')
    .decode(data)
    .split(/[\s,]+/)
    .filter(Boolean);
  if (words.length < count)
    throw new LoaderError(
      'truncated',
      `${ctx.name}: the ASCII data holds ${words.length} values, the header announces ${count}`,
    );
  const out = new Float64Array(count);
  for (let i = 0; i < count; i++) {
    const x = Number(words[i]);
    if (Number.isNaN(x) && !/^[-+]?nan$/i.test(words[i]))
      throw new LoaderError('invalid-data', `${ctx.name}: ASCII value ${i} "${words[i].slice(0, 20)}" is not a number`);
    out[i] = x;
  }
  // Through the declared type, so integer data wraps and rounds as a binary file would.
  const typed = new SOURCE_ARRAY[source](count);
  typed.set(out);
  return typed;
}

function parseHex(data: Uint8Array, need: number, ctx: LoadContext): Uint8Array {
  const out = new Uint8Array(need);
  let n = 0,
    hi = -1;
  for (let i = 0; i < data.length && n < need; i++) {
    const c = data[i];
    const v =
      c >= 0x30 && c <= 0x39 ? c - 0x30 : c >= 0x61 && c <= 0x66 ? c - 0x57 : c >= 0x41 && c <= 0x46 ? c - 0x37 : -1;
    if (v < 0) {
      if (c === 0x20 || c === 0x0a || c === 0x0d || c === 0x09) continue;
      throw new LoaderError('invalid-data', `${ctx.name}: byte ${i} of the hex data is not a hex digit`);
    }
    if (hi < 0) hi = v;
    else {
      out[n++] = (hi << 4) | v;
      hi = -1;
    }
  }
  if (n < need)
    throw new LoaderError('truncated', `${ctx.name}: the hex data holds ${n} bytes, the header announces ${need}`);
  return out;
}
