import { LoaderError } from '../errors.js';
import type { LoadContext } from '../context.js';
import type { LoadedVolume } from '../types.js';
import { finishVolume } from '../convert/finish.js';
import { checkAvailable, checkDims, checkFits, SOURCE_BYTES, type SourceType } from '../convert/size.js';
import {
  chooseTypeOf,
  integralScaling,
  ownsMemory,
  readSamples,
  toVoxelArray,
  IDENTITY,
  OUTPUT_BYTES,
  type Scaling,
} from '../convert/voxels.js';
import { gunzip, isGzip } from '../io/gzip.js';
import { loadDependency } from '../io/deps.js';
import { axisCodes, directionCosines, isFiniteVector } from './orientation.js';

const HEADER = 348;
const MIN_OFFSET = 352; // header + the 4-byte extension flag
/** NIfTI-2 (2011): the same fields, 64-bit dims and doubles, in a 540-byte header with its magic at byte 4. */
const HEADER2 = 540;
const MIN_OFFSET2 = 544;

/** NIfTI-1 datatype codes vpt reads, and the type they are read as. */
const DATATYPES: Record<number, SourceType> = {
  2: 'uint8',
  4: 'int16',
  8: 'int32',
  16: 'float32',
  64: 'float64',
  256: 'int8',
  512: 'uint16',
  768: 'uint32',
};
/** Colour datatypes: each voxel's bytes (R, G, B[, A]) are its channels, uint8, interleaved as core's Volume holds them. */
const COLOR_TYPES: Record<number, { name: string; channels: number }> = {
  128: { name: 'RGB24', channels: 3 },
  2304: { name: 'RGBA32', channels: 4 },
};
/** Most channels a Volume holds (core's MAX_VOLUME_CHANNELS). */
const MAX_CHANNELS = 16;
const UNSUPPORTED_TYPES: Record<number, string> = {
  1: 'binary (1 bit)',
  32: 'complex64',
  1024: 'int64',
  1280: 'uint64',
  1536: 'float128',
  1792: 'complex128',
  2048: 'complex256',
};

/** Is this a NIfTI-1 header (magic "n+1\0" / "ni1\0" at byte 344) or a NIfTI-2 one ("n+2\0" / "ni2\0" at byte 4)? */
export function hasNiftiMagic(bytes: Uint8Array): boolean {
  const at = (i: number, version: number) =>
    bytes[i] === 0x6e &&
    (bytes[i + 1] === 0x2b || bytes[i + 1] === 0x69) &&
    bytes[i + 2] === version &&
    bytes[i + 3] === 0;
  return (bytes.length >= HEADER && at(344, 0x31)) || (bytes.length >= HEADER2 && at(4, 0x32));
}

interface NiftiHeader {
  littleEndian: boolean;
  dims: number[];
  datatypeCode: number;
  numBitsPerVoxel: number;
  pixDims: number[];
  vox_offset: number;
  scl_slope: number;
  scl_inter: number;
  xyzt_units: number;
  cal_min: number;
  cal_max: number;
  description: string;
  qform_code: number;
  sform_code: number;
  magic: string;
  /** NIfTI-2: the sform rows as read (doubles); NIfTI-1's are read from the bytes as float32. */
  affine?: number[][];
  getQformMat(): number[][];
}

interface Plan {
  header: NiftiHeader;
  dims: [number, number, number];
  source: SourceType;
  offset: number;
  count: number;
  extraVolumes: number;
  /** Volumes along dim[4], the time axis (1 for a 3D file). */
  timeSteps: number;
  /** Values per voxel: dim[5] (vector components, stored as volumes after all time steps), or a colour datatype's bytes. */
  channels: number;
  /** RGB24 / RGBA32: the channels are each voxel's bytes (interleaved); else dim[5] volumes (planar). */
  packed: boolean;
  /** A .hdr/.img pair (magic "ni1" / "ni2"): the data is in the .img file, from vox_offset. */
  pair: boolean;
  headerSize: number;
  version: 1 | 2;
}

/**
 * Read the 348-byte header with nifti-reader-js and check everything the data step relies
 * on. Only the header is handed to the library (its extension reader trusts sizes from the
 * file and can loop on a corrupt one); vpt does not need extensions.
 */
type NiftiModule = typeof import('nifti-reader-js');

function readPlan(head: Uint8Array, ctx: LoadContext, nifti: NiftiModule): Plan {
  const version = isNifti2(head) ? 2 : 1;
  const size = version === 2 ? HEADER2 : HEADER;
  if (head.length < size)
    throw new LoaderError(
      'truncated',
      `${ctx.name}: ${head.length} bytes is shorter than a NIfTI-${version} header (${size} bytes)`,
    );
  const view = new DataView(head.buffer, head.byteOffset, size);
  const sizeLE = view.getInt32(0, true),
    sizeBE = view.getInt32(0, false);
  if (sizeLE !== size && sizeBE !== size) {
    throw new LoaderError(
      'bad-magic',
      `${ctx.name} is not a NIfTI file: its first 4 bytes (sizeof_hdr) are not 348 (NIfTI-1) or 540 (NIfTI-2) in either byte order`,
    );
  }
  const header = (version === 2 ? new nifti.NIFTI2() : new nifti.NIFTI1()) as unknown as NiftiHeader & {
    readHeader(b: ArrayBuffer): void;
  };
  try {
    header.readHeader(head.slice(0, size).buffer);
  } catch (e) {
    throw new LoaderError(
      'bad-header',
      `${ctx.name}: the NIfTI header cannot be read (${(e as Error)?.message ?? e})`,
      { cause: e },
    );
  }
  if (version === 1) header.affine = undefined; // NIfTI-1's sform is read from the bytes (float32)
  if (version === 1 && (header.magic === '' || header.magic === undefined))
    throw new LoaderError(
      'unsupported',
      `${ctx.name} is an Analyze 7.5 header (no NIfTI magic at byte 344); vpt reads NIfTI-1 and NIfTI-2: convert it, e.g. with nibabel`,
    );
  const single = `n+${version}`,
    paired = `ni${version}`;
  // NIfTI-2's 8-byte magic continues "\0\r\n\x1a\n" (to catch text-mode transfers): the name is its first 3 printable characters.
  header.magic = String(header.magic ?? '')
    .replace(/[^\x20-\x7e]/g, '')
    .slice(0, 3);
  if (header.magic !== single && header.magic !== paired)
    throw new LoaderError(
      'bad-magic',
      `${ctx.name}: the NIfTI-${version} magic at byte ${version === 2 ? 4 : 344} is "${header.magic}", not "${single}" (one file) or "${paired}" (a .hdr/.img pair)`,
    );
  const pair = header.magic === paired;
  // CIFTI-2 (intent codes 3000–3099) is a matrix over surfaces and grayordinates in a NIfTI-2 shell, not a volume.
  const intent = (header as { intent_code?: number }).intent_code ?? 0;
  if (intent >= 3000 && intent <= 3099)
    throw new LoaderError(
      'unsupported',
      `${ctx.name} is CIFTI-2 (NIfTI intent code ${intent}), a matrix over surfaces and grayordinates, not a volume; vpt reads volumes`,
    );

  const d = header.dims;
  if (!(d[0] >= 1 && d[0] <= 7))
    throw new LoaderError('bad-header', `${ctx.name}: dim[0] = ${d[0]} must be 1..7 (the number of dimensions)`);
  const dims = [d[1], d[0] >= 2 ? d[2] : 1, d[0] >= 3 ? d[3] : 1];
  checkDims(dims, ctx, 'NIfTI header');
  let extraVolumes = 1;
  for (let i = 4; i <= d[0]; i++) {
    if (d[i] < 0) throw new LoaderError('bad-header', `${ctx.name}: dim[${i}] = ${d[i]} is negative`);
    extraVolumes *= Math.max(1, d[i]);
  }
  const color = COLOR_TYPES[header.datatypeCode];
  const source = color ? 'uint8' : DATATYPES[header.datatypeCode];
  if (!source) {
    const known = UNSUPPORTED_TYPES[header.datatypeCode];
    if (known)
      throw new LoaderError(
        'unsupported',
        `${ctx.name}: NIfTI datatype ${header.datatypeCode} (${known}) is not supported; vpt reads integer, float, RGB24 and RGBA32 data`,
      );
    throw new LoaderError(
      'bad-header',
      `${ctx.name}: NIfTI datatype code ${header.datatypeCode} is not a valid NIfTI-1 datatype`,
    );
  }
  const offset = header.vox_offset;
  // In a pair, vox_offset is where the data starts in the .img file (usually 0).
  const least = pair ? 0 : size;
  const standard = version === 2 ? MIN_OFFSET2 : MIN_OFFSET;
  if (!Number.isFinite(offset) || offset < least || !Number.isInteger(offset)) {
    throw new LoaderError(
      'bad-header',
      `${ctx.name}: vox_offset = ${offset} must be a whole number ≥ ${pair ? 0 : standard}`,
    );
  }
  if (!pair && offset < standard)
    ctx.warnings.push(`vox_offset ${offset} is below the ${standard} the NIfTI-${version} standard requires`);
  const count = dims[0] * dims[1] * dims[2];
  const timeSteps = d[0] >= 4 ? Math.max(1, d[4]) : 1;
  // dim[5]: values per voxel (vector components, NIFTI_INTENT_VECTOR and kin), each a run of dim[4] volumes.
  const components = d[0] >= 5 ? Math.max(1, d[5]) : 1;
  for (let i = 6; i <= d[0]; i++)
    if (d[i] > 1)
      throw new LoaderError(
        'unsupported',
        `${ctx.name}: dim[${i}] = ${d[i]}: vpt reads x, y, z, time (dim[4]) and vector components (dim[5]), not a 6th or 7th axis`,
      );
  if (color && components > 1)
    throw new LoaderError(
      'unsupported',
      `${ctx.name}: dim[5] = ${components} components of ${color.name} colours; vpt reads a colour or vector components, not both`,
    );
  const channels = color ? color.channels : components;
  if (channels > MAX_CHANNELS)
    throw new LoaderError(
      'unsupported',
      `${ctx.name}: dim[5] = ${components} values per voxel; vpt reads at most ${MAX_CHANNELS} channels (MAX_VOLUME_CHANNELS)`,
    );
  if (ctx.time >= timeSteps)
    throw new LoaderError(
      'bad-header',
      `${ctx.name}: time step ${ctx.time} does not exist (the file holds ${timeSteps} along dim[4], 0 to ${timeSteps - 1})`,
    );
  return {
    header,
    dims,
    source,
    offset,
    count,
    extraVolumes: extraVolumes * (color ? color.channels : 1),
    timeSteps,
    channels,
    packed: !!color,
    pair,
    headerSize: size,
    version,
  };
}

function scalingOf(h: NiftiHeader, ctx: LoadContext): Scaling {
  // Colour bytes are not scaled (the standard: scl_slope does not apply to RGB24/RGBA32; nibabel does the same).
  if (COLOR_TYPES[h.datatypeCode]) return IDENTITY;
  const { scl_slope: slope, scl_inter: inter } = h;
  // NIfTI-1: slope 0 means "no scaling"; a NaN/Inf pair is a broken header, ignored as nibabel does.
  if (slope === 0 || !Number.isFinite(slope)) {
    if (!Number.isFinite(slope)) ctx.warnings.push(`scl_slope = ${slope} ignored`);
    return IDENTITY;
  }
  if (!Number.isFinite(inter)) {
    // A valid slope with a NaN/Inf intercept cannot be meant: refused, as nibabel does.
    throw new LoaderError(
      'bad-header',
      `${ctx.name}: scl_slope = ${slope} is valid but scl_inter = ${inter} is not a finite number; fix the header's scaling`,
    );
  }
  return { slope, inter };
}

/** World placement: the sform when sform_code > 0, else the qform when qform_code > 0, else none (nibabel's order). */
function placement(
  h: NiftiHeader,
  head: Uint8Array,
  ctx: LoadContext,
): { orientation?: number[]; origin?: [number, number, number]; lengths?: number[]; xform: string } {
  const view = new DataView(head.buffer, head.byteOffset, HEADER);
  if (h.sform_code > 0) {
    const rows = h.affine
      ? h.affine.slice(0, 3).map((row) => row.slice(0, 4))
      : [0, 1, 2].map((r) => [0, 1, 2, 3].map((c) => view.getFloat32(280 + (4 * r + c) * 4, h.littleEndian)));
    const cos = rows.every(isFiniteVector) ? directionCosines([0, 1, 2].map((c) => rows.map((row) => row[c]))) : null;
    if (cos) {
      warnShear(cos.orientation, 'sform', ctx);
      return {
        orientation: cos.orientation,
        origin: [rows[0][3], rows[1][3], rows[2][3]],
        lengths: cos.lengths,
        xform: 'sform',
      };
    }
    ctx.warnings.push('the sform is degenerate; ignored');
  }
  if (h.qform_code > 0) {
    const q = h.getQformMat();
    const cos = q.slice(0, 3).every(isFiniteVector)
      ? directionCosines([0, 1, 2].map((c) => [q[0][c], q[1][c], q[2][c]]))
      : null;
    // The qform is a rotation times pixdim (and qfac), so pixdim already is its voxel size.
    if (cos) return { orientation: cos.orientation, origin: [q[0][3], q[1][3], q[2][3]], xform: 'qform' };
    ctx.warnings.push('the qform is degenerate; ignored');
  }
  return { xform: 'none' };
}

/** A sheared transform (axes not perpendicular) is kept exactly, but said: most viewers assume right angles. */
function warnShear(o: readonly number[], which: string, ctx: LoadContext): void {
  const col = (c: number) => [o[c], o[3 + c], o[6 + c]];
  const dot = (a: number[], b: number[]) => a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
  const worst = Math.max(Math.abs(dot(col(0), col(1))), Math.abs(dot(col(0), col(2))), Math.abs(dot(col(1), col(2))));
  if (worst > 1e-4)
    ctx.warnings.push(
      `the ${which} is sheared (its axes are ${(90 - (Math.asin(Math.min(1, worst)) * 180) / Math.PI).toFixed(2)}° apart at the least); orientation holds its unit, non-perpendicular axis directions`,
    );
}

function isNifti2(head: Uint8Array): boolean {
  if (head.length < 4) return false;
  const v = new DataView(head.buffer, head.byteOffset, 4);
  return v.getInt32(0, true) === HEADER2 || v.getInt32(0, false) === HEADER2;
}

/** Limit check before allocating, at the smallest size the result can have; finishVolume checks the exact one. */
function earlyFits(plan: Plan, ctx: LoadContext): void {
  const integral = integralScaling(scalingOf(plan.header, { ...ctx, warnings: [] }));
  const bytes =
    plan.source === 'uint8' && integral ? 1 : integral && SOURCE_BYTES[plan.source] <= 4 ? 2 : OUTPUT_BYTES.float32;
  checkFits(plan.dims, bytes * plan.channels, ctx);
}

/** One volume's bytes (one component of one time step; a colour file's whole colours). */
function volumeBytesOf(plan: Plan): number {
  return plan.count * SOURCE_BYTES[plan.source] * (plan.packed ? plan.channels : 1);
}

/** The file bytes (from the data's start) up to the end of time step `t`'s last component. */
function bytesThrough(plan: Plan, t: number): number {
  const components = plan.packed ? 1 : plan.channels;
  return volumeBytesOf(plan) * ((components - 1) * plan.timeSteps + t + 1);
}

const SPATIAL_UNITS: Record<number, string> = { 1: 'm', 2: 'mm', 3: 'µm' };
/** xyzt_units & 0x38: the time unit, as seconds per unit (NIfTI-1: 8 s, 16 ms, 24 µs). */
const TIME_UNITS: Record<number, number> = { 8: 1, 16: 1e-3, 24: 1e-6 };

/** Loads the .img beside a .hdr (by URL, or among the dropped files). */
export type PairResolver = (name: string) => Promise<Uint8Array>;

/** The .img name of a pair's .hdr (keeping the case of the extension and a .gz). */
export function pairImageName(hdrName: string): string {
  return hdrName.replace(
    /\.(hdr)(\.gz)?$/i,
    (_, h: string, gz?: string) => (h === 'HDR' ? '.IMG' : '.img') + (gz ?? ''),
  );
}

/** NIfTI-1 or NIfTI-2: a single file (.nii, .nii.gz) or a .hdr/.img pair (either may be gzip-compressed), either byte order. */
export async function decodeNifti(input: Uint8Array, ctx: LoadContext, resolve?: PairResolver): Promise<LoadedVolume> {
  const nifti = await loadDependency('nifti-reader-js', () => import('nifti-reader-js'));
  let bytes = input;
  let plan: Plan | undefined;
  // Peak inflated memory: at most limits.maxBytes of voxel data plus the header and extensions (≤ 1 MiB).
  // Step t of a 4D file lies after t volumes, each within maxBytes (earlyFits), which are inflated on the way.
  // With vector components (dim[5], stored after all time steps) the steps before the last component are inflated too.
  const stepsInflated = (plan?: Plan) => (plan && !plan.packed && plan.channels > 1 ? plan.timeSteps : ctx.time + 1);
  const maxOutputOf = (plan?: Plan) =>
    ctx.downsample ? Number.MAX_SAFE_INTEGER : (ctx.limits.maxBytes + (1 << 20)) * stepsInflated(plan);
  // The cap is checked against the header's announced size in onHead (it depends on dim[5]); before
  // the header only its first bytes are inflated.
  const capped = (p: Plan, keep: number): number => {
    const cap = maxOutputOf(p);
    if (keep > cap)
      throw new LoaderError(
        'limit',
        `${ctx.name}: its header announces ${keep} bytes, more than the ${cap} allowed (limits.maxBytes is ${ctx.limits.maxBytes})`,
      );
    return keep;
  };
  const planOf = (p: Plan) => ({
    keep: capped(p, p.offset + bytesThrough(p, ctx.time)),
    declared: p.offset + p.count * SOURCE_BYTES[p.source] * p.extraVolumes,
  });
  if (isGzip(input)) {
    // Inflate in steps: once the header is out it is checked, so a lying or oversize file
    // stops before the rest is inflated, and the output is allocated once at its exact size.
    bytes = await gunzip(input, ctx, {
      maxOutput: Number.MAX_SAFE_INTEGER,
      headBytes: MIN_OFFSET2, // enough for either version's header and extension flag
      onHead: (head) => {
        if (!hasNiftiMagic(head) && head.length >= HEADER && !isNifti2(head)) {
          throw new LoaderError(
            'bad-magic',
            `${ctx.name}: gzip-compressed data that is not NIfTI (no "n+1" magic at byte 344, no "n+2" at byte 4)`,
          );
        }
        plan = readPlan(head, ctx, nifti);
        earlyFits(plan, ctx);
        if (plan.pair) return plan.headerSize;
        // Keep up to the time step asked for; the others are declared data, not "bytes past the data".
        return planOf(plan);
      },
    });
  }
  plan ??= readPlan(bytes, ctx, nifti);
  const { header, dims, source, count } = plan;
  const C = plan.channels;
  const volumeBytes = volumeBytesOf(plan);
  // Time step t of component c starts (c·T + t) volumes into the data (x, y, z, then dim[4], then dim[5]).
  const components = plan.packed ? 1 : C;
  const offsetOf = (c: number) => plan!.offset + (c * plan!.timeSteps + ctx.time) * volumeBytes;
  const headerBytes = bytes;
  let inflated = bytes !== input;
  if (plan.pair) {
    const imgName = pairImageName(ctx.name);
    if (!resolve)
      throw new LoaderError(
        'unsupported',
        `${ctx.name} is the header of a .hdr/.img pair; load it by URL or together with ${imgName}`,
      );
    const img = await resolve(imgName);
    inflated = isGzip(img);
    bytes = inflated
      ? await gunzip(img, ctx, {
          maxOutput: Number.MAX_SAFE_INTEGER,
          onHead: () => planOf(plan!),
          headBytes: 0,
        })
      : img;
  }
  if (plan.timeSteps > 1)
    ctx.warnings.push(
      `the file holds ${plan.timeSteps} volumes along dim[4] (time); volume ${ctx.time} is loaded (LoadOptions.time picks the time step)`,
    );
  const scaling = scalingOf(header, ctx);
  checkAvailable(bytes.length - offsetOf(components - 1), volumeBytes, ctx);
  const extra = bytes.length - plan.offset - count * SOURCE_BYTES[source] * Math.max(1, plan.extraVolumes);
  if (!inflated && extra > 0)
    ctx.warnings.push(`${extra} bytes past the data the header declares are ignored; check the dims and datatype`);
  earlyFits(plan, ctx);
  ctx.progress('convert', 0, count * C);
  // A view would keep the other time steps' bytes alive beside it: one step of a 4D file is copied out.
  const view = ownsMemory(bytes, ctx.borrowed) && plan.timeSteps === 1 && components === 1;
  let samples = readSamples(bytes, offsetOf(0), count * (plan.packed ? C : 1), source, header.littleEndian, view);
  if (components > 1) {
    // dim[5] components are stored one volume after another: interleave them, channel fastest.
    const out = new (samples.constructor as new (n: number) => typeof samples)(count * C);
    for (let c = 0; c < C; c++) {
      const part = c === 0 ? samples : readSamples(bytes, offsetOf(c), count, source, header.littleEndian, true);
      for (let i = 0; i < count; i++) out[c + C * i] = part[i];
    }
    samples = out;
  }
  const type = chooseTypeOf(samples, source, scaling, ctx.warnings);
  const data = toVoxelArray(samples, type, scaling);
  ctx.progress('convert', count * C, count * C);
  // The header's xform is the placement (nibabel's affine): its column lengths are the voxel
  // sizes, even where pixdim says otherwise; pixdim only when there is no xform.
  const place = placement(header, headerBytes, ctx);
  const pixdim = [1, 2, 3].map((i) => Math.abs(header.pixDims[i]));
  // float32 sform rows give lengths a few ulps off pixdim; those agree, and pixdim is exact.
  const differs = !!place.lengths && pixdim.some((p, i) => !(Math.abs(p - place.lengths![i]) <= 1e-5 * Math.max(1, p)));
  const spacing = (differs ? place.lengths! : pixdim).map((s, i) => {
    if (Number.isFinite(s) && s > 0) return s;
    if (dims[i] > 1) ctx.warnings.push(`pixdim[${i + 1}] = ${header.pixDims[i + 1]} is not a positive size; 1 used`);
    return 1;
  }) as [number, number, number];
  if (differs)
    ctx.warnings.push(
      `pixdim [${pixdim.join(', ')}] differs from the ${place.xform}'s voxel sizes [${place.lengths!.map((l) => +l.toPrecision(7)).join(', ')}]; the ${place.xform}'s are used (as nibabel's affine does)`,
    );
  const meta: Record<string, unknown> = {
    space: 'RAS',
    xform: place.xform,
    sclSlope: scaling.slope,
    sclInter: scaling.inter,
    littleEndian: header.littleEndian,
    datatype: source,
    niftiVersion: plan.version,
    pixdim,
  };
  if (plan.pair) meta.pair = true;
  meta.timeSteps = plan.timeSteps;
  const intent = (header as { intent_code?: number }).intent_code ?? 0;
  if (intent) meta.intentCode = intent;
  if (C > 1) meta.channelSource = plan.packed ? COLOR_TYPES[header.datatypeCode].name : 'dim[5]';
  const secondsPerUnit = TIME_UNITS[header.xyzt_units & 0x38];
  const dt = header.pixDims[4];
  if (plan.timeSteps > 1 && secondsPerUnit && Number.isFinite(dt) && dt > 0) meta.stepSeconds = dt * secondsPerUnit;
  if (place.orientation) meta.axisCodes = axisCodes(place.orientation, 'RAS');
  const units = SPATIAL_UNITS[header.xyzt_units & 7];
  if (units) meta.spacingUnits = units;
  if (header.description) meta.description = header.description;
  if (Number.isFinite(header.cal_min) && Number.isFinite(header.cal_max) && header.cal_max > header.cal_min)
    meta.calRange = [header.cal_min, header.cal_max];
  return finishVolume(
    {
      format: 'nifti',
      dims,
      spacing,
      type,
      data,
      orientation: place.orientation,
      origin: place.origin,
      meta,
      ...(C > 1 ? { channels: C } : {}),
    },
    ctx,
  );
}
