import type { VoxelType } from '@vpt/core';
import { LoaderError } from '../errors.js';
import type { LoadContext } from '../context.js';
import type { LoadedVolume } from '../types.js';
import { finishVolume } from '../convert/finish.js';
import { checkDims, checkFits, type SourceType } from '../convert/size.js';
import {
  chooseType,
  convertInto,
  integralScaling,
  IDENTITY,
  readSamples,
  scaledRange,
  scanRange,
  OUTPUT_ARRAY,
  OUTPUT_BYTES,
  type Scaling,
  type SourceArray,
} from '../convert/voxels.js';
import { fflate, loadDependency } from '../io/deps.js';
import { directionCosines } from './orientation.js';
import { finite, numbersOf, presentText, reader, type DataSet } from './dicom-elements.js';
import { applyModalityLut, readModalityLut, type ModalityLut } from './dicom-modality-lut.js';
import { enhancedFrames, hasFunctionalGroups } from './dicom-functional-groups.js';
import { readDoseGrid } from './dicom-rt-dose.js';

/** Transfer syntaxes with native (uncompressed) pixel data, and whether it is little-endian. */
const NATIVE: Record<string, { little: boolean; name: string }> = {
  '1.2.840.10008.1.2': { little: true, name: 'Implicit VR Little Endian' },
  '1.2.840.10008.1.2.1': { little: true, name: 'Explicit VR Little Endian' },
  '1.2.840.10008.1.2.1.99': { little: true, name: 'Deflated Explicit VR Little Endian' },
  '1.2.840.10008.1.2.2': { little: false, name: 'Explicit VR Big Endian' },
};

const COMPRESSED: [RegExp, string][] = [
  [/^1\.2\.840\.10008\.1\.2\.4\.5[0-9]$/, 'JPEG'],
  [/^1\.2\.840\.10008\.1\.2\.4\.(57|70)$/, 'JPEG Lossless'],
  [/^1\.2\.840\.10008\.1\.2\.4\.8[01]$/, 'JPEG-LS'],
  [/^1\.2\.840\.10008\.1\.2\.4\.9[0-3]$/, 'JPEG 2000'],
  [/^1\.2\.840\.10008\.1\.2\.4\.20[1-3]$/, 'High-Throughput JPEG 2000'],
  [/^1\.2\.840\.10008\.1\.2\.4\.1\d\d$/, 'MPEG/HEVC video'],
  [/^1\.2\.840\.10008\.1\.2\.5$/, 'RLE Lossless'],
];

export function hasDicomMagic(bytes: Uint8Array): boolean {
  return (
    bytes.length >= 132 && bytes[128] === 0x44 && bytes[129] === 0x49 && bytes[130] === 0x43 && bytes[131] === 0x4d
  );
}

export interface DicomFile {
  name: string;
  bytes: Uint8Array;
}

interface Slice {
  name: string;
  rows: number;
  cols: number;
  /** Frames this slice stands for: >1 only for a classic multi-frame file loaded as one block. */
  frames: number;
  /** Index of this slice's (first) frame in `pixels`: an enhanced file's frames are slices of their own. */
  frame: number;
  bitsAllocated: number;
  bitsStored: number;
  signed: boolean;
  photometric: string;
  scaling: Scaling;
  /** Modality LUT Sequence: replaces the rescale. */
  lut?: ModalityLut;
  pixelSpacing?: [number, number];
  /** The PixelSpacing text when present but not two positive finite numbers (reported, then 1 used). */
  badPixelSpacing?: string;
  ipp?: number[];
  iop?: number[];
  series: string;
  instance: number;
  thickness?: number;
  between?: number;
  little: boolean;
  pixels: Uint8Array;
  modality?: string;
  syntax: string;
  /** RT Dose: each frame's offset along the normal (Grid Frame Offset Vector). */
  frameOffsets?: number[];
}

type Parser = typeof import('dicom-parser');

function thrownMessage(e: unknown): string {
  if (typeof e === 'string') return e;
  if (e && typeof e === 'object') {
    const o = e as { message?: string; exception?: unknown };
    if (o.exception !== undefined) return thrownMessage(o.exception);
    if (typeof o.message === 'string') return o.message;
  }
  return String(e);
}

/**
 * Parse one file with dicom-parser into its slices: one for a single-frame or classic
 * multi-frame file, one per frame of the first volume of an enhanced file; none for a
 * DICOM file without pixel data (a DICOMDIR, a report).
 */
function parseFile(
  file: DicomFile,
  parser: Parser,
  inflateRaw: (b: Uint8Array) => Uint8Array,
  ctx: LoadContext,
): Slice[] {
  const where = `${ctx.name}${file.name && file.name !== ctx.name ? ` (${file.name})` : ''}`;
  if (!hasDicomMagic(file.bytes)) {
    throw new LoaderError('bad-magic', `${where} is not a DICOM Part 10 file: no "DICM" at byte 128`);
  }
  let ds: DataSet;
  try {
    ds = parser.parseDicom(file.bytes, {
      // Deflated transfer syntax: the data set after the meta group is raw deflate (fflate).
      inflater: (arr: Uint8Array, position: number) => {
        const inflated = inflateRaw(arr.subarray(position));
        const full = new Uint8Array(position + inflated.length);
        full.set(arr.subarray(0, position));
        full.set(inflated, position);
        return full;
      },
    } as never);
  } catch (e) {
    const msg = thrownMessage(e);
    const reason = /overr(ead|un)|beyond|end of|past|eof|truncat/i.test(msg) ? 'truncated' : 'bad-header';
    throw new LoaderError(
      reason,
      `${where}: the DICOM data cannot be parsed (${msg})${reason === 'truncated' ? '; the file is cut short' : ''}`,
      { cause: e },
    );
  }
  const r = reader(ds);
  const syntax = (r.str('x00020010') ?? '').replace(/\0/g, '').trim();
  const pixel = ds.elements.x7fe00010;
  if (!pixel) return [];
  const native = NATIVE[syntax];
  if (!native) {
    const known = COMPRESSED.find(([re]) => re.test(syntax));
    if (known || pixel.encapsulatedPixelData) {
      throw new LoaderError(
        'unsupported',
        `${where} uses the compressed transfer syntax ${syntax || '(none given)'}${known ? ` (${known[1]})` : ''}; ` +
          'vpt reads uncompressed DICOM (Implicit/Explicit VR Little Endian, Explicit VR Big Endian, Deflated): decompress it first, e.g. gdcmconv --raw or dcmdjpeg',
      );
    }
    throw new LoaderError('bad-header', `${where}: transfer syntax "${syntax}" is unknown`);
  }
  if (pixel.encapsulatedPixelData)
    throw new LoaderError(
      'bad-header',
      `${where}: the pixel data is encapsulated although the transfer syntax (${native.name}) is uncompressed`,
    );
  const rows = r.u16('x00280010');
  const cols = r.u16('x00280011');
  const bitsAllocated = r.u16('x00280100');
  const samples = r.u16('x00280002') ?? 1;
  if (!finite(rows) || !finite(cols) || !finite(bitsAllocated)) {
    throw new LoaderError('bad-header', `${where}: Rows, Columns or BitsAllocated is missing`);
  }
  if (samples !== 1)
    throw new LoaderError('unsupported', `${where}: ${samples} samples per pixel (colour) is not a scalar volume`);
  const photometric = (r.str('x00280004') ?? '').trim();
  if (photometric === 'PALETTE COLOR')
    throw new LoaderError(
      'unsupported',
      `${where}: PALETTE COLOR pixels are indices into a colour table, not a scalar quantity; vpt reads MONOCHROME1/MONOCHROME2 images`,
    );
  if (bitsAllocated !== 8 && bitsAllocated !== 16 && bitsAllocated !== 32) {
    throw new LoaderError(
      'unsupported',
      `${where}: ${bitsAllocated} bits allocated per pixel is not supported (8, 16 or 32)`,
    );
  }
  const bitsStoredRaw = r.u16('x00280101');
  const bitsStored =
    finite(bitsStoredRaw) && bitsStoredRaw >= 1 && bitsStoredRaw <= bitsAllocated ? bitsStoredRaw : bitsAllocated;
  const framesText = presentText(ds, 'x00280008')?.replace(/\0/g, '').trim();
  if (framesText !== undefined && framesText !== '' && !/^\+?\d+$/.test(framesText))
    throw new LoaderError('bad-header', `${where}: NumberOfFrames "${framesText}" is not a whole number`);
  const frames = framesText ? Math.max(1, parseInt(framesText, 10)) : 1;
  let slope = r.num('x00281053');
  let inter = r.num('x00281052');
  if (!finite(slope) || slope === 0) slope = 1;
  if (!finite(inter)) inter = 0;
  const dose = readDoseGrid(ds, frames);
  if (dose.scale !== undefined) {
    slope *= dose.scale;
    inter *= dose.scale;
  }
  const ps = numbersOf(ds, 'x00280030', 2);
  const need = rows * cols * frames * (bitsAllocated / 8);
  const array = ds.byteArray as Uint8Array;
  const available = Math.min(pixel.length, array.length - pixel.dataOffset);
  if (!(available >= need)) {
    throw new LoaderError(
      'truncated',
      `${where}: the pixel data holds ${Math.max(0, available)} bytes; ${rows}×${cols}${frames > 1 ? `×${frames}` : ''} pixels of ${bitsAllocated} bits need ${need}; the file is cut short or its header is wrong`,
    );
  }
  let pixels = array.subarray(pixel.dataOffset, pixel.dataOffset + need);
  if (!native.little && bitsAllocated === 8 && pixel.vr === 'OW') {
    // Big endian OW holds 16-bit words: 8-bit pixels come byte-swapped in pairs (PS3.5 8.1.1, 8.2);
    // an odd count's last pixel sits in the padding word's second byte.
    const padded = Math.min(need + (need & 1), available);
    pixels = swapBytePairs(array.subarray(pixel.dataOffset, pixel.dataOffset + padded)).subarray(0, need);
  }
  const signed = r.u16('x00280103') === 1;
  const lut = readModalityLut(ds, native.little, signed, where);
  const thickness = r.num('x00180050');
  const between = r.num('x00180088');
  const instance = r.int('x00200013');
  const base: Slice = {
    name: file.name,
    rows,
    cols,
    frames,
    frame: 0,
    bitsAllocated,
    bitsStored,
    signed,
    photometric,
    // A Modality LUT replaces the rescale (PS3.3 C.11.1: the two are mutually exclusive).
    scaling: lut ? IDENTITY : { slope, inter },
    lut,
    pixelSpacing: ps && ps[0] > 0 && ps[1] > 0 ? [ps[0], ps[1]] : undefined,
    badPixelSpacing: ps && ps[0] > 0 && ps[1] > 0 ? undefined : presentText(ds, 'x00280030'),
    ipp: numbersOf(ds, 'x00200032', 3),
    iop: numbersOf(ds, 'x00200037', 6),
    series: (r.str('x0020000e') ?? '').trim(),
    instance: finite(instance) ? instance : 0,
    thickness: finite(thickness) && thickness > 0 ? thickness : undefined,
    between: finite(between) && between > 0 ? between : undefined,
    little: native.little,
    pixels,
    modality: r.str('x00080060')?.trim(),
    syntax,
    frameOffsets: dose.frameOffsets,
  };
  if (!hasFunctionalGroups(ds)) return [base];
  // Enhanced multi-frame: every frame a slice with its own position, orientation, spacing
  // and rescale, so the series logic below sorts and spaces them.
  return enhancedFrames(ds, frames, where, ctx).map((g) => ({
    ...base,
    frames: 1,
    frame: g.frame,
    instance: g.frame,
    ipp: g.ipp ?? base.ipp,
    iop: g.iop ?? base.iop,
    pixelSpacing: g.pixelSpacing ?? base.pixelSpacing,
    badPixelSpacing: g.pixelSpacing ? undefined : base.badPixelSpacing,
    thickness: g.thickness ?? base.thickness,
    between: g.between ?? base.between,
    scaling: lut ? IDENTITY : (g.scaling ?? base.scaling),
    frameOffsets: undefined,
  }));
}

function swapBytePairs(b: Uint8Array): Uint8Array {
  const out = new Uint8Array(b.length);
  for (let i = 0; i + 1 < b.length; i += 2) {
    out[i] = b[i + 1];
    out[i + 1] = b[i];
  }
  if (b.length & 1) out[b.length - 1] = b[b.length - 1];
  return out;
}

const cross = (a: number[], b: number[]) => [
  a[1] * b[2] - a[2] * b[1],
  a[2] * b[0] - a[0] * b[2],
  a[0] * b[1] - a[1] * b[0],
];
const dot = (a: number[], b: number[]) => a[0] * b[0] + a[1] * b[1] + a[2] * b[2];

/** Values of one frame: stored values, then the Modality LUT when there is one (the rescale comes later). */
function framePixels(s: Slice, frame: number): SourceArray {
  const stored = storedPixels(s, frame);
  return s.lut ? applyModalityLut(stored, s.lut) : stored;
}

/** Stored pixels of one frame, BitsStored applied (masked, sign-extended when signed). */
function storedPixels(s: Slice, frame: number): SourceArray {
  const plane = s.rows * s.cols;
  const size = s.bitsAllocated / 8;
  const unsigned: SourceType = size === 1 ? 'uint8' : size === 2 ? 'uint16' : 'uint32';
  const raw = readSamples(s.pixels, frame * plane * size, plane, unsigned, s.little);
  if (!s.signed && s.bitsStored === s.bitsAllocated) return raw;
  if (s.signed && s.bitsStored === s.bitsAllocated) {
    return size === 1
      ? new Int8Array(raw.buffer)
      : size === 2
        ? new Int16Array(raw.buffer)
        : new Int32Array(raw.buffer);
  }
  const bits = s.bitsStored;
  const mask = bits >= 32 ? 0xffffffff : 2 ** bits - 1;
  const out = s.signed ? new (size === 1 ? Int8Array : size === 2 ? Int16Array : Int32Array)(plane) : raw;
  for (let i = 0; i < plane; i++) {
    let v = (raw[i] as number) & mask;
    if (s.signed && v >= 2 ** (bits - 1)) v -= 2 ** bits;
    out[i] = v;
  }
  return out;
}

function sourceTypeOf(s: Slice): SourceType {
  if (s.lut) return s.lut.bits === 8 ? 'uint8' : 'uint16';
  const size = s.bitsAllocated / 8;
  if (s.signed) return size === 1 ? 'int8' : size === 2 ? 'int16' : 'int32';
  return size === 1 ? 'uint8' : size === 2 ? 'uint16' : 'uint32';
}

/** Geometry of the ordered slices: the z spacing from the positions, the direction cosines, the origin. */
interface Geometry {
  order: Slice[];
  zSpacing: number;
  orientation?: number[];
  origin?: [number, number, number];
  sortedBy: string;
}

/**
 * A multi-frame RT Dose grid: frame k lies at ImagePositionPatient + offset_k · normal, so
 * the z spacing is the mean offset step; offsets that decrease turn the third axis around.
 */
function doseGridGeometry(s: Slice, orientation: number[], ctx: LoadContext): Geometry {
  const off = s.frameOffsets!;
  const gaps = off.slice(1).map((o, i) => o - off[i]);
  const mean = (off[off.length - 1] - off[0]) / gaps.length;
  if (!(Math.abs(mean) > 0) || gaps.some((g) => Math.sign(g) !== Math.sign(mean)))
    throw new LoaderError(
      'invalid-data',
      `${ctx.name}: the Grid Frame Offset Vector (${off.join('\\')}) does not run one way; the frames are no stack`,
    );
  if (Math.max(...gaps.map(Math.abs)) - Math.min(...gaps.map(Math.abs)) > 0.05 * Math.abs(mean))
    ctx.warnings.push(`the dose grid's frame offsets are unevenly spaced; their mean step ${Math.abs(mean)} is used`);
  const o = orientation.slice();
  if (mean < 0) for (const i of [2, 5, 8]) o[i] = 0 - o[i]; // 0 - x: no -0 for a zero component
  // The first frame lies at ImagePositionPatient whether the offsets are relative to it
  // (first offset 0) or, as the retired form has them, absolute z values (PS3.3 C.8.8.3.2).
  const origin = s.ipp!.slice(0, 3) as [number, number, number];
  return { order: [s], zSpacing: Math.abs(mean), orientation: o, origin, sortedBy: 'Grid Frame Offset Vector' };
}

function arrange(slices: Slice[], ctx: LoadContext): Geometry {
  const first = slices[0];
  const iop = first.iop;
  const normal = iop ? cross(iop.slice(0, 3), iop.slice(3, 6)) : undefined;
  const cos = iop && normal ? directionCosines([iop.slice(0, 3), iop.slice(3, 6), normal]) : null;
  if (slices.length === 1 && first.frameOffsets && first.ipp && cos)
    return doseGridGeometry(first, cos.orientation, ctx);
  if (slices.length === 1) {
    const z = first.between ?? first.thickness ?? 1;
    if (first.frames > 1 && first.between === undefined)
      ctx.warnings.push(`multi-frame spacing taken from ${first.thickness ? 'SliceThickness' : 'nothing (1 used)'}`);
    return {
      order: slices,
      zSpacing: z,
      orientation: cos?.orientation,
      origin: first.ipp as [number, number, number] | undefined,
      sortedBy: 'single file',
    };
  }
  const positioned =
    cos && normal && slices.every((s) => s.ipp && s.iop && s.iop.every((v, i) => Math.abs(v - iop![i]) < 1e-3));
  if (positioned) {
    const n = cos.orientation.filter((_, i) => i % 3 === 2); // the unit normal (third column)
    const keyed = slices.map((s) => ({ s, d: dot(s.ipp!, n) })).sort((a, b) => a.d - b.d);
    const gaps = keyed.slice(1).map((k, i) => k.d - keyed[i].d);
    const dup = gaps.findIndex((g) => g < 1e-4);
    if (dup >= 0) {
      throw new LoaderError(
        'invalid-data',
        `${ctx.name}: ${keyed[dup].s.name || 'a slice'} and ${keyed[dup + 1].s.name || 'another'} lie at the same position along the slice normal (${keyed[dup].d.toFixed(3)}); ` +
          'the files hold more than one volume (echoes, time points, a repeated scan): load one of them',
      );
    }
    const mean = (keyed[keyed.length - 1].d - keyed[0].d) / gaps.length;
    const spread = Math.max(...gaps) - Math.min(...gaps);
    if (spread > 0.05 * mean)
      ctx.warnings.push(
        `slice spacing varies from ${Math.min(...gaps).toFixed(3)} to ${Math.max(...gaps).toFixed(3)} (a missing slice?); the mean ${mean.toFixed(3)} is used`,
      );
    const thick = first.thickness;
    if (thick !== undefined && Math.abs(thick - mean) > 0.01 * mean)
      ctx.warnings.push(
        `SliceThickness ${thick} differs from the spacing of the positions ${mean.toFixed(4)}; the positions are used`,
      );
    const origin = keyed[0].s.ipp! as [number, number, number];
    return {
      order: keyed.map((k) => k.s),
      zSpacing: mean,
      orientation: cos.orientation,
      origin: [origin[0], origin[1], origin[2]],
      sortedBy: 'position along the slice normal',
    };
  }
  const oneFile = slices.every((s) => s.name === first.name && s.pixels === first.pixels);
  ctx.warnings.push(
    `the ${oneFile ? 'frames' : 'slices'} carry no usable ImagePositionPatient/ImageOrientationPatient; sorted by ${oneFile ? 'frame order' : 'InstanceNumber'}, spacing from SpacingBetweenSlices or SliceThickness`,
  );
  const order = [...slices].sort((a, b) => a.instance - b.instance);
  return { order, zSpacing: first.between ?? first.thickness ?? 1, sortedBy: 'InstanceNumber' };
}

/**
 * The slices of one orientation. A localizer (scout) series holds slices in several
 * planes; stacking them would make a volume out of unrelated images, so the largest group
 * of equally oriented slices is kept (the first such group on a tie), and said; when every
 * slice has an orientation of its own there is no stack, and that is an error.
 */
function sameOrientation(slices: Slice[], ctx: LoadContext): Slice[] {
  if (slices.length < 2 || !slices.every((s) => s.iop)) return slices;
  const groups: Slice[][] = [];
  for (const s of slices) {
    const g = groups.find((x) => x[0].iop!.every((v, i) => Math.abs(v - s.iop![i]) < 1e-3));
    if (g) g.push(s);
    else groups.push([s]);
  }
  if (groups.length === 1) return slices;
  const largest = groups.reduce((a, b) => (b.length > a.length ? b : a));
  if (largest.length === 1)
    throw new LoaderError(
      'invalid-data',
      `${ctx.name}: each of the ${slices.length} slices lies in its own orientation (ImageOrientationPatient; a localizer or a radial series), so there is no stack to make a volume of; load one file at a time`,
    );
  ctx.warnings.push(
    `the slices lie in ${groups.length} different orientations (ImageOrientationPatient; a localizer?); ` +
      `the ${largest.length} oriented ${largest[0].iop!.map((v) => +v.toFixed(3)).join('\\')} are loaded, the other ${slices.length - largest.length} left out`,
  );
  return largest;
}

/** A DICOM series (one or more files, or one multi-frame file) as one volume. */
export async function decodeDicom(files: DicomFile[], ctx: LoadContext): Promise<LoadedVolume> {
  const mod = await loadDependency('dicom-parser', () => import('dicom-parser'));
  const parser = ((mod as { default?: Parser }).default ?? mod) as Parser;
  const { inflateSync } = await fflate();
  const inflateRaw = (b: Uint8Array) => {
    try {
      return inflateSync(b);
    } catch (e) {
      throw new LoaderError('invalid-data', `${ctx.name}: the deflated DICOM data is corrupt (${thrownMessage(e)})`, {
        cause: e,
      });
    }
  };
  const parsed: Slice[] = [];
  let skipped = 0;
  ctx.progress('parse', 0, files.length);
  for (let i = 0; i < files.length; i++) {
    ctx.checkAborted();
    const slices = parseFile(files[i], parser, inflateRaw, ctx);
    if (slices.length) parsed.push(...slices);
    else skipped++;
    ctx.progress('parse', i + 1, files.length);
  }
  if (!parsed.length)
    throw new LoaderError('empty', `${ctx.name}: none of the ${files.length} DICOM file(s) holds pixel data`);

  // A dropped folder may hold several series: keep the largest, say so.
  const bySeries = new Map<string, Slice[]>();
  for (const s of parsed) bySeries.set(s.series, [...(bySeries.get(s.series) ?? []), s]);
  const series = [...bySeries.values()].sort((a, b) => b.length - a.length);
  if (series.length > 1)
    ctx.warnings.push(`the files hold ${series.length} series; the largest (${series[0].length} slices) is loaded`);
  const slices = sameOrientation(series[0], ctx);
  const first = slices[0];
  for (const s of slices) {
    if (
      s.rows !== first.rows ||
      s.cols !== first.cols ||
      s.bitsAllocated !== first.bitsAllocated ||
      s.signed !== first.signed
    ) {
      throw new LoaderError(
        'invalid-data',
        `${ctx.name}: ${s.name || 'a slice'} is ${s.cols}×${s.rows}, ${s.bitsAllocated}-bit${s.signed ? ' signed' : ''}, unlike ${first.name || 'the first'} (${first.cols}×${first.rows}, ${first.bitsAllocated}-bit${first.signed ? ' signed' : ''}); the files are not one series`,
      );
    }
  }
  if (slices.length > 1 && slices.some((s) => s.frames > 1)) {
    throw new LoaderError(
      'unsupported',
      `${ctx.name}: a series of several multi-frame files is not supported; load one file at a time`,
    );
  }
  const geometry = arrange(slices, ctx);
  const depth = slices.length === 1 ? first.frames : slices.length;
  const dims = [first.cols, first.rows, depth];
  checkDims(dims, ctx, 'DICOM header');
  const source = sourceTypeOf(first);
  const integral = slices.every((s) => integralScaling(s.scaling));
  checkFits(dims, integral ? Math.min(2, OUTPUT_BYTES.int16) : 4, ctx);

  // Two passes: find the scaled range of every frame (to choose the narrowest exact type),
  // then convert into one array, so only one slice at a time is held twice.
  const frames: { s: Slice; f: number }[] =
    geometry.order.length === 1 && first.frames > 1
      ? Array.from({ length: first.frames }, (_, f) => ({ s: first, f }))
      : geometry.order.map((s) => ({ s, f: s.frame }));
  let lo = Infinity,
    hi = -Infinity;
  for (const { s, f } of frames) {
    const r = scaledRange(scanRange(framePixels(s, f)), s.scaling);
    lo = Math.min(lo, r.min);
    hi = Math.max(hi, r.max);
  }
  const type: VoxelType = chooseType(source, { min: lo, max: hi }, integral);
  const plane = first.rows * first.cols;
  const data = new OUTPUT_ARRAY[type](plane * frames.length);
  ctx.progress('convert', 0, frames.length);
  frames.forEach(({ s, f }, k) => {
    convertInto(framePixels(s, f), s.scaling, data, k * plane);
    ctx.progress('convert', k + 1, frames.length);
  });

  if (first.badPixelSpacing !== undefined)
    ctx.warnings.push(
      `invalid PixelSpacing "${first.badPixelSpacing}" (must be two positive numbers); 1 used in-plane`,
    );
  else if (!first.pixelSpacing) ctx.warnings.push('no PixelSpacing; 1 used in-plane');
  const [rowSpacing, colSpacing] = first.pixelSpacing ?? [1, 1];
  const spacing: [number, number, number] = [colSpacing, rowSpacing, geometry.zSpacing];
  const meta: Record<string, unknown> = {
    space: 'LPS',
    sortedBy: geometry.sortedBy,
    transferSyntax: first.syntax,
    photometric: first.photometric,
    rescale: first.lut
      ? 'Modality LUT Sequence'
      : slices.every((s) => s.scaling.slope === first.scaling.slope && s.scaling.inter === first.scaling.inter)
        ? first.scaling
        : 'per slice',
    files: [...new Set(geometry.order.map((s) => s.name))],
  };
  if (first.modality) meta.modality = first.modality;
  if (skipped) meta.skippedFiles = skipped;
  if (first.photometric === 'MONOCHROME1')
    ctx.warnings.push('MONOCHROME1: low values are displayed bright in DICOM viewers; the values are kept as stored');
  return finishVolume(
    {
      format: 'dicom',
      dims: dims as [number, number, number],
      spacing,
      type,
      data,
      orientation: geometry.orientation,
      origin: geometry.origin,
      meta,
    },
    ctx,
  );
}
