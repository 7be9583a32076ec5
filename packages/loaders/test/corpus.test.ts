/**
 * The corpus test: other projects' test files (nibabel's, pydicom's, pydicom-data's, and the
 * NRRD files of pyradiomics and slicerio; see corpus/archives.json), fetched by
 * `pnpm corpus:fetch` into data/corpus/, each compared with what the format's own reader
 * makes of it. corpus/references.json (written by corpus/make_references.py with nibabel,
 * pydicom and pynrrd) holds per file either the voxels'
 * checksum (float32 values, x fastest, NaN as 0x7fc00000), range, spacing and origin, or
 * the typed refusal reasons expected; a key ending in '/' is a folder of pydicom's loaded
 * as one series. Skipped, saying so, when the corpus is not fetched.
 */
import fs from 'node:fs';
import path from 'node:path';
import { afterAll, describe, expect, it } from 'vitest';
import { loadVolume, LoaderError, type LoadedVolume } from '../src/index.js';
import { UNEXPECTED_PREFIX } from '../src/errors.js';
import { HERE, fileOf, sha256 } from './helpers.js';

const root = path.resolve(HERE, '../../..');
const corpus = path.join(root, 'data', 'corpus');
interface Loaded {
  dims: number[];
  sha256: string;
  min: number | null;
  max: number | null;
  spacing?: (number | null)[];
  origin?: number[];
  rowCol?: number[];
  /** The full 3×3 direction cosines, row-major (NIfTI: the affine's columns normalised). */
  direction?: number[];
  /** Values per voxel (an NRRD list/vector/colour axis), listed channel fastest. */
  channels?: number;
}
interface Reference {
  load?: Loaded;
  /** PALETTE COLOR: the stored indices, for the same file relabelled MONOCHROME2. */
  indices?: Loaded;
  refuse?: LoaderError['reason'][];
  why?: string;
  reader: string;
}
const references: Record<string, Reference> = JSON.parse(
  fs.readFileSync(path.join(HERE, 'corpus', 'references.json'), 'utf8'),
).files;

/**
 * Files that fail because of bugs being fixed in parallel (issue 25's NRRD/NIfTI items,
 * engineer "formats"); each names the issue item. Remove an entry once its fix is merged:
 * the test then fails if the entry is still listed but passes (a stale entry).
 */
const KNOWN_FAILURES: Record<string, string> = {
  // 'nibabel/tests/data/example.nii': 'issue 25: NIfTI sform vs pixdim spacing',
};

const fetched = fs.existsSync(corpus) && fs.readdirSync(corpus).some((n) => !n.startsWith('.'));
const NOT_FETCHED = 'skipped: data/corpus/ is not there, run `pnpm corpus:fetch`';

/** The reference checksum rule: float32 values, NaN canonical, little-endian bytes. */
function valuesChecksum(v: LoadedVolume): string {
  const f = Float32Array.from(v.data as ArrayLike<number>);
  const bits = new Uint32Array(f.buffer);
  for (let i = 0; i < f.length; i++) if (Number.isNaN(f[i])) bits[i] = 0x7fc00000;
  return sha256(f);
}

const formatOf = (rel: string) =>
  /\.(nii|nii\.gz|hdr)$/.test(rel)
    ? 'NIfTI'
    : /\.(nrrd|nhdr)$/.test(rel)
      ? 'NRRD'
      : rel.endsWith('/')
        ? 'DICOM series'
        : 'DICOM';
const table: Record<string, { tried: number; matched: number; refused: number; known: number }> = {};
const count = (rel: string, what: 'matched' | 'refused' | 'known') => {
  const row = (table[formatOf(rel)] ??= { tried: 0, matched: 0, refused: 0, known: 0 });
  row.tried++;
  row[what]++;
};

/** A key ending in '/' is a folder whose image files load together (a series); else one file. */
function sourceOf(rel: string): File | File[] {
  const read = (p: string) => fileOf(new Uint8Array(fs.readFileSync(path.join(corpus, p))), path.basename(p));
  if (!rel.endsWith('/')) return read(rel);
  return fs
    .readdirSync(path.join(corpus, rel))
    .filter((n) => !n.includes('.') && n !== 'DICOMDIR' && fs.statSync(path.join(corpus, rel, n)).isFile())
    .sort()
    .map((n) => read(rel + n));
}

async function outcome(rel: string): Promise<{ volume?: LoadedVolume; error?: unknown }> {
  try {
    return { volume: await loadVolume(sourceOf(rel), { worker: false }) };
  } catch (error) {
    return { error };
  }
}

/** Why `rel` does not match its reference, or null when it does. */
async function mismatch(rel: string, ref: Reference): Promise<string | null> {
  const { volume: v, error } = await outcome(rel);
  if (ref.refuse) {
    if (v) return `loaded (${v.dims.join('×')} ${v.type}) but ${ref.reader} refuses it: ${ref.why}`;
    if (!(error instanceof LoaderError)) return `untyped error ${String(error)}`;
    if (error.message.startsWith(UNEXPECTED_PREFIX)) return `unexpected error: ${error.message}`;
    if (!ref.refuse.includes(error.reason))
      return `refused with '${error.reason}' (${error.message}), expected one of ${ref.refuse.join(', ')} (${ref.why})`;
    return null;
  }
  const want = ref.load!;
  if (!v) return `refused (${error instanceof LoaderError ? error.reason : 'untyped'}: ${(error as Error)?.message})`;
  if (v.dims.join() !== want.dims.join()) return `dims ${v.dims.join('×')}, ${ref.reader} ${want.dims.join('×')}`;
  if ((v.channels ?? 1) !== (want.channels ?? 1))
    return `${v.channels ?? 1} channels, ${ref.reader} ${want.channels ?? 1}`;
  const sum = valuesChecksum(v);
  if (sum !== want.sha256) {
    const r = v.meta?.dataRange as { min: number; max: number } | undefined;
    return `voxels differ (range ${r?.min}..${r?.max}, ${ref.reader} ${want.min}..${want.max})`;
  }
  const near = (a: number, b: number) => Math.abs(a - b) <= 1e-4 * Math.max(1, Math.abs(b));
  for (let i = 0; i < 3; i++) {
    const s = want.spacing?.[i];
    if (s != null && !near(v.spacing[i], s))
      return `spacing ${v.spacing.join(',')}, ${ref.reader} ${want.spacing!.join(',')}`;
  }
  if (want.origin && !(v.origin && want.origin.every((o, i) => near(v.origin![i], o))))
    return `origin ${v.origin?.join(',') ?? 'none'}, ${ref.reader} ${want.origin.join(',')}`;
  if (want.rowCol) {
    // Orientation columns 0 and 1 (row-major 3×3): the row and column directions.
    const o = v.orientation;
    const cols = o ? [o[0], o[3], o[6], o[1], o[4], o[7]] : [];
    if (!o || !want.rowCol.every((x, i) => near(cols[i], x)))
      return `orientation ${o?.join(',') ?? 'none'}, ${ref.reader} rows/columns ${want.rowCol.join(',')}`;
  }
  if (want.direction) {
    const o = v.orientation ?? [1, 0, 0, 0, 1, 0, 0, 0, 1];
    if (!want.direction.every((x, i) => near(o[i], x)))
      return `orientation ${o.join(',')}, ${ref.reader} ${want.direction.map((x) => +x.toFixed(6)).join(',')}`;
  }
  return null;
}

/**
 * A PALETTE COLOR file with its PhotometricInterpretation relabelled MONOCHROME2 (same
 * length), so its stored indices load: the pixel decoding checked on the real file.
 */
function relabelled(rel: string): File {
  const bytes = new Uint8Array(fs.readFileSync(path.join(corpus, rel)));
  const from = new TextEncoder().encode('PALETTE COLOR');
  const to = new TextEncoder().encode('MONOCHROME2  ');
  let at = -1;
  for (let i = 0; i + from.length <= bytes.length && at < 0; i++) if (from.every((b, k) => bytes[i + k] === b)) at = i;
  if (at < 0) throw new Error(`${rel}: no "PALETTE COLOR" text`);
  bytes.set(to, at);
  return fileOf(bytes, path.basename(rel));
}

describe('corpus: other projects’ test files against their own readers', () => {
  it('the references cover DICOM, NIfTI and NRRD, loads and refusals', () => {
    const refs = Object.entries(references);
    for (const format of ['DICOM', 'NIfTI', 'NRRD'])
      expect(
        refs.some(([k, r]) => formatOf(k) === format && r.load),
        format,
      ).toBe(true);
    // An NRRD with values per voxel (3D Slicer's overlapping segments) loads as channels.
    expect(refs.some(([k, r]) => formatOf(k) === 'NRRD' && (r.load?.channels ?? 1) > 1)).toBe(true);
    expect(refs.some(([, r]) => r.refuse)).toBe(true);
    for (const k of Object.keys(KNOWN_FAILURES))
      expect(references[k], `known failure ${k} has a reference`).toBeDefined();
  });

  it.skipIf(!fetched)(
    `every file matches its reference or is refused typed${fetched ? '' : ` (${NOT_FETCHED})`}`,
    async () => {
      const failures: string[] = [];
      const stale: string[] = [];
      for (const [rel, ref] of Object.entries(references)) {
        if (!fs.existsSync(path.join(corpus, rel))) {
          failures.push(`${rel}: missing from data/corpus/ (run \`pnpm corpus:fetch -- --force\`)`);
          continue;
        }
        const why = await mismatch(rel, ref);
        if (KNOWN_FAILURES[rel]) {
          count(rel, 'known');
          if (!why) stale.push(`${rel}: listed as a known failure (${KNOWN_FAILURES[rel]}) but matches now`);
        } else if (why) failures.push(`${rel}: ${why}`);
        else count(rel, ref.refuse ? 'refused' : 'matched');
      }
      expect(failures, failures.join('\n')).toEqual([]);
      expect(stale, stale.join('\n')).toEqual([]);
    },
    300_000,
  );

  it.skipIf(!fetched)(
    `PALETTE COLOR files relabelled MONOCHROME2 load their stored indices as pydicom reads them${fetched ? '' : ` (${NOT_FETCHED})`}`,
    async () => {
      const palette = Object.entries(references).filter(([, r]) => r.indices);
      expect(palette.map(([k]) => k)).toContain('pydicom-data/OBXXXX1A_expb.dcm');
      for (const [rel, ref] of palette) {
        const v = await loadVolume(relabelled(rel), { worker: false });
        expect(v.dims, rel).toEqual(ref.indices!.dims);
        expect(valuesChecksum(v), `${rel}: stored indices`).toBe(ref.indices!.sha256);
      }
    },
  );

  afterAll(() => {
    if (!fetched) console.log(`corpus test ${NOT_FETCHED}`);
    else
      console.log(
        `corpus: ${Object.entries(table)
          .map(
            ([f, r]) =>
              `${f}: ${r.tried} tried, ${r.matched} matched, ${r.refused} refused typed, ${r.known} known failures`,
          )
          .join('; ')}`,
      );
  });
});
