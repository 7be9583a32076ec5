/**
 * NRRD and NIfTI files with a channel axis (values per voxel) or a time axis, written by the
 * reference writers (pynrrd, nibabel: fixtures/multiaxis/make_fixtures.py), against the
 * voxels the reference readers return (fixtures/multiaxis/expected.json), channel fastest.
 */
import fs from 'node:fs';
import path from 'node:path';
import zlib from 'node:zlib';
import { describe, expect, it } from 'vitest';
import { loadVolume, openTimeSeries, type LoadedVolume } from '../src/index.js';
import {
  bytesIn,
  checkOutcome,
  expectLoaderError,
  fileOf,
  FIXTURES,
  niftiFile,
  nrrdFile,
  rng,
  serve,
} from './helpers.js';

const DIR = path.join(FIXTURES, 'multiaxis');
interface Expected {
  dims: number[];
  channels: number;
  timeSteps: number;
  spacing: number[];
  steps: number[][];
}
const expected: { readers: Record<string, string>; files: Record<string, Expected> } = JSON.parse(
  fs.readFileSync(path.join(DIR, 'expected.json'), 'utf8'),
);
const file = (name: string) => fileOf(new Uint8Array(fs.readFileSync(path.join(DIR, name))), name);

function expectStep(v: LoadedVolume, want: Expected, t: number, name: string): void {
  expect(v.dims, name).toEqual(want.dims);
  expect(v.channels ?? 1, name).toBe(want.channels);
  want.spacing.forEach((s, i) => expect(v.spacing[i], `${name} spacing[${i}]`).toBeCloseTo(s, 6));
  // float32 of the reference's value (pynrrd / nibabel give the stored type, or float64 for scaled data).
  expect(Array.from(v.data), `${name} step ${t}`).toEqual(Array.from(Float32Array.from(want.steps[t])));
}

describe('multiaxis fixtures against the reference readers', () => {
  it('every file and every step loads to the reference voxels (channel fastest)', async () => {
    expect(Object.keys(expected.files).length).toBeGreaterThanOrEqual(9);
    for (const [name, want] of Object.entries(expected.files)) {
      for (let t = 0; t < want.timeSteps; t++) {
        const v = await loadVolume(file(name), { time: t });
        expectStep(v, want, t, name);
        if (want.timeSteps > 1) expect(v.meta?.timeSteps, name).toBe(want.timeSteps);
      }
    }
  });

  it('a step past the end is refused naming it, and a file without a time axis refuses time 1', async () => {
    const e = await expectLoaderError(loadVolume(file('time-last.nrrd'), { time: 5 }), 'bad-header');
    expect(e.message).toMatch(/time step 5 does not exist/);
    await expectLoaderError(loadVolume(file('vector-first.nrrd'), { time: 1 }), 'unsupported');
  });

  it('openTimeSeries over a 4D NRRD and a 4D NIfTI gives every step', async () => {
    for (const name of ['time-last.nrrd', 'time4d.nii.gz', 'list-time.nrrd', 'vector-time.nii']) {
      const want = expected.files[name];
      const series = await openTimeSeries(file(name));
      expect(series.steps, name).toBe(want.timeSteps);
      for (let t = 0; t < series.steps; t++) expectStep(await series.loadStep(t), want, t, name);
    }
  });
});

describe('a one-file series is read once', () => {
  /** A File whose every read (stream, arrayBuffer) is counted. */
  function countedFile(name: string): { file: File; reads: () => number } {
    let reads = 0;
    class Counted extends File {
      override stream() {
        reads++;
        return super.stream();
      }
      override arrayBuffer() {
        reads++;
        return super.arrayBuffer();
      }
    }
    const file = new Counted([fs.readFileSync(path.join(DIR, name))], name);
    return { file, reads: () => reads };
  }

  it('by URL: one request for every step (NIfTI gzip, NRRD gzip, a 5D NIfTI)', async () => {
    const server = await serve(DIR);
    try {
      for (const name of ['time4d.nii.gz', 'time-last.nrrd', 'vector-time.nii']) {
        const before = server.requests.length;
        const series = await openTimeSeries(server.url + name);
        const want = expected.files[name];
        for (let t = series.steps - 1; t >= 0; t--) expectStep(await series.loadStep(t), want, t, name);
        expect(server.requests.slice(before), name).toEqual([`/${name}`]);
      }
    } finally {
      await server.close();
    }
  });

  it('a gzip-encoded NRRD is inflated once (raw for every step), line skip and byte skip kept', async () => {
    const name = 'time-last.nrrd';
    const want = expected.files[name];
    const series = await openTimeSeries(file(name));
    for (let t = 0; t < series.steps; t++) {
      const v = await series.loadStep(t);
      expectStep(v, want, t, name);
      expect(v.meta?.encoding).toBe('raw');
    }
    const small = await openTimeSeries(file(name), { keepBytes: 300 });
    expect((await small.loadStep(1)).meta?.encoding).toBe('gzip');
    // A text line before the gzip stream ("line skip: 1") and two bytes before the samples ("byte skip: 2").
    const values = new Uint8Array(2 * 2 * 2 * 3).map((_, i) => 3 * i);
    const gz = zlib.gzipSync(new Uint8Array([7, 7, ...values]));
    const head = nrrdFile(
      {
        type: 'uint8',
        dimension: '4',
        sizes: '2 2 2 3',
        kinds: 'domain domain domain time',
        encoding: 'gzip',
        'line skip': '1',
        'byte skip': '2',
      },
      new Uint8Array([...new TextEncoder().encode('a line\n'), ...gz]),
    );
    const skipped = await openTimeSeries(fileOf(head, 'skip.nrrd'));
    for (let t = 0; t < 3; t++) {
      const v = await skipped.loadStep(t);
      expect(v.meta?.encoding).toBe('raw');
      expect(Array.from(v.data)).toEqual(Array.from(values.subarray(8 * t, 8 * t + 8)));
    }
  });

  it('from a File: read once; past keepBytes it is read again per step, with the same voxels', async () => {
    const name = 'time4d.nii.gz';
    const want = expected.files[name];
    const once = countedFile(name);
    const series = await openTimeSeries(once.file);
    for (let t = 0; t < series.steps; t++) expectStep(await series.loadStep(t), want, t, name);
    expect(once.reads()).toBe(1);
    // keepBytes below the compressed size: nothing is kept, each later step reads the file again.
    const again = countedFile(name);
    const small = await openTimeSeries(again.file, { keepBytes: 64 });
    for (let t = 0; t < small.steps; t++) expectStep(await small.loadStep(t), want, t, name);
    expect(again.reads()).toBe(small.steps);
    // keepBytes above the compressed size but below the inflated one: the gzip bytes are kept.
    const gz = countedFile(name);
    const inflatedSize = 352 + 4 * 3 * 2 * 6 * 4;
    const compressed = await openTimeSeries(gz.file, { keepBytes: inflatedSize - 1 });
    for (let t = 0; t < compressed.steps; t++) expectStep(await compressed.loadStep(t), want, t, name);
    expect(gz.reads()).toBe(1);
  });
});

describe('channel and time axes: orders and layouts', () => {
  // 2 × 3 × 2 voxels of 3 channels: value(c, x, y, z) = 100·c + x + 10·y + 1000·z... as uint16 (z < 2).
  const dims = [2, 3, 2];
  const C = 3;
  const want = new Uint16Array(C * 12);
  for (let z = 0, i = 0; z < 2; z++)
    for (let y = 0; y < 3; y++)
      for (let x = 0; x < 2; x++) for (let c = 0; c < C; c++) want[i++] = 100 * c + x + 10 * y + 1000 * z;
  /** The same voxels stored with the channel axis at file position `at` (0 = fastest). */
  function stored(at: number): { sizes: number[]; data: Uint16Array } {
    const order = ['x', 'y', 'z'];
    order.splice(at, 0, 'c');
    const size: Record<string, number> = { c: C, x: dims[0], y: dims[1], z: dims[2] };
    const sizes = order.map((a) => size[a]);
    const data = new Uint16Array(C * 12);
    const idx: Record<string, number> = {};
    for (let n = 0; n < data.length; n++) {
      let r = n;
      for (const a of order) {
        idx[a] = r % size[a];
        r = Math.floor(r / size[a]);
      }
      data[n] = 100 * idx.c + idx.x + 10 * idx.y + 1000 * idx.z;
    }
    return { sizes, data };
  }

  it('a channel axis at any position gives the same interleaved volume (vector, RGB-color, 3-vector, list)', async () => {
    const kinds = ['vector', 'RGB-color', '3-vector', 'list'];
    for (let at = 0; at <= 3; at++) {
      const { sizes, data } = stored(at);
      const kindList = ['domain', 'domain', 'domain'];
      kindList.splice(at, 0, kinds[at]);
      for (const encoding of ['raw', 'gzip']) {
        const payload = bytesIn(data, true);
        const v = await loadVolume(
          nrrdFile(
            {
              type: 'ushort',
              dimension: '4',
              sizes: sizes.join(' '),
              kinds: kindList.join(' '),
              endian: 'little',
              encoding,
            },
            encoding === 'gzip' ? new Uint8Array(zlib.gzipSync(payload)) : payload,
          ),
        );
        expect(v.dims, `at ${at}`).toEqual(dims);
        expect(v.channels, `at ${at}`).toBe(C);
        expect(Array.from(v.data), `channel axis at ${at}, ${encoding}`).toEqual(Array.from(want));
      }
    }
  });

  it('a channel axis with a "none" space direction, before or (with its kind) after the spatial ones', async () => {
    for (const at of [0, 3]) {
      const { sizes, data } = stored(at);
      const dirs = ['(1,0,0)', '(0,2,0)', '(0,0,3)'];
      dirs.splice(at, 0, 'none');
      const v = await loadVolume(
        nrrdFile(
          {
            type: 'ushort',
            dimension: '4',
            sizes: sizes.join(' '),
            space: 'left-posterior-superior',
            'space directions': dirs.join(' '),
            // An axis of no kind after the spatial ones is time (x, y, z, t); a kind says channels.
            ...(at === 3 ? { kinds: 'domain domain domain RGB-color' } : {}),
            endian: 'little',
            encoding: 'raw',
          },
          bytesIn(data, true),
        ),
      );
      expect(v.channels).toBe(C);
      expect(v.spacing).toEqual([1, 2, 3]);
      expect(Array.from(v.data)).toEqual(Array.from(want));
    }
  });

  it('a space-time NRRD: the axis whose direction has only a time part is time', async () => {
    const values = new Uint8Array(2 * 2 * 2 * 3).map((_, i) => i);
    const fields = {
      type: 'uint8',
      dimension: '4',
      sizes: '2 2 2 3',
      space: 'right-anterior-superior-time',
      'space directions': '(1,0,0,0) (0,1,0,0) (0,0,1,0) (0,0,0,0.5)',
      'space origin': '(1,2,3,0)',
      encoding: 'raw',
    };
    for (let t = 0; t < 3; t++) {
      const v = await loadVolume(nrrdFile(fields, values), { time: t });
      expect(v.dims).toEqual([2, 2, 2]);
      expect(v.meta?.timeSteps).toBe(3);
      expect(v.origin).toEqual([1, 2, 3]);
      expect(Array.from(v.data)).toEqual(Array.from(values.subarray(8 * t, 8 * t + 8)));
    }
  });

  it('a time axis with spacing in seconds gives stepSeconds', async () => {
    const v = await loadVolume(
      nrrdFile(
        {
          type: 'uint8',
          dimension: '4',
          sizes: '2 1 1 4',
          kinds: 'domain domain domain time',
          spacings: '1 1 1 250',
          units: '"mm" "mm" "mm" "ms"',
          encoding: 'raw',
        },
        new Uint8Array(8),
      ),
    );
    expect(v.meta?.stepSeconds).toBe(0.25);
  });

  it('NIfTI dim[5] components are interleaved channel fastest, for every time step', async () => {
    // dims 2×1×1, T = 3, C = 2, float32: the value of (x, t, c) is 100·c + 10·t + x.
    const T = 3;
    const data = new Float32Array(2 * T * 2);
    for (let c = 0; c < 2; c++)
      for (let t = 0; t < T; t++) for (let x = 0; x < 2; x++) data[x + 2 * (t + T * c)] = 100 * c + 10 * t + x;
    const bytes = niftiFile({ dims: [5, 2, 1, 1, T, 2, 1, 1], datatype: 16, bitpix: 32, data: bytesIn(data, true) });
    for (const input of [bytes, new Uint8Array(zlib.gzipSync(bytes))])
      for (let t = 0; t < T; t++) {
        const v = await loadVolume(fileOf(input, 'v.nii'), { time: t });
        expect(v.channels).toBe(2);
        expect(Array.from(v.data)).toEqual([10 * t, 100 + 10 * t, 10 * t + 1, 100 + 10 * t + 1]);
      }
  });
});

describe('channel and time axes: lying or cut headers are typed errors naming the field', () => {
  it('NRRD', async () => {
    const base = { type: 'uint8', dimension: '4', encoding: 'raw' };
    // A channel axis of 17 values: more than a Volume holds.
    let e = await expectLoaderError(
      loadVolume(nrrdFile({ ...base, sizes: '17 2 2 2', kinds: 'list domain domain domain' }, new Uint8Array(136))),
      'unsupported',
    );
    expect(e.message).toMatch(/at most 16 channels/);
    // Two channel axes, two time axes.
    e = await expectLoaderError(
      loadVolume(
        nrrdFile(
          { ...base, dimension: '5', sizes: '2 2 2 2 2', kinds: 'vector RGB-color domain domain domain' },
          new Uint8Array(32),
        ),
      ),
      'unsupported',
    );
    expect(e.message).toMatch(/axes 0 .* and 1 .* values per voxel/);
    e = await expectLoaderError(
      loadVolume(
        nrrdFile(
          { ...base, dimension: '5', sizes: '2 2 2 2 2', kinds: 'space space space time time' },
          new Uint8Array(32),
        ),
      ),
      'unsupported',
    );
    expect(e.message).toMatch(/time axes/);
    // Sizes announcing more steps than the data holds: truncated, raw and gzip.
    const fields = { ...base, sizes: '2 2 2 4', kinds: 'domain domain domain time' };
    e = await expectLoaderError(loadVolume(nrrdFile(fields, new Uint8Array(24))), 'truncated');
    expect(e.message).toMatch(/needs 32 bytes/);
    // gzip is inflated only up to the step asked for: step 0 is there, step 3 is not.
    const gz = nrrdFile({ ...fields, encoding: 'gzip' }, new Uint8Array(zlib.gzipSync(new Uint8Array(24))));
    expect((await loadVolume(gz)).dims).toEqual([2, 2, 2]);
    await expectLoaderError(loadVolume(gz, { time: 3 }), 'truncated');
    // A non-integer or negative size; a space-time space whose "space dimension" disagrees.
    e = await expectLoaderError(loadVolume(nrrdFile({ ...base, sizes: '2 2 2 1.5' }, new Uint8Array(8))), 'bad-header');
    expect(e.message).toMatch(/sizes/);
    e = await expectLoaderError(
      loadVolume(
        nrrdFile(
          { ...base, sizes: '2 2 2 2', space: 'right-anterior-superior-time', 'space dimension': '3' },
          new Uint8Array(16),
        ),
      ),
      'bad-header',
    );
    expect(e.message).toMatch(/space dimension/);
    // A channel axis of size 0.
    await expectLoaderError(
      loadVolume(nrrdFile({ ...base, sizes: '0 2 2 2', kinds: 'vector domain domain domain' }, new Uint8Array(8))),
      'empty',
    );
  });

  it('NIfTI', async () => {
    const data = new Uint8Array(2 * 2 * 2 * 3);
    // RGB24 with too few bytes for its colours.
    let e = await expectLoaderError(
      loadVolume(niftiFile({ dims: [3, 2, 2, 2, 1, 1, 1, 1], datatype: 128, bitpix: 24, data: data.subarray(0, 16) })),
      'truncated',
    );
    expect(e.message).toMatch(/needs 24 bytes/);
    // dim[5] = 17 components; a colour with components; a 6th axis.
    e = await expectLoaderError(
      loadVolume(niftiFile({ dims: [5, 1, 1, 1, 1, 17, 1, 1], datatype: 2, bitpix: 8, data: new Uint8Array(17) })),
      'unsupported',
    );
    expect(e.message).toMatch(/dim\[5\] = 17/);
    e = await expectLoaderError(
      loadVolume(niftiFile({ dims: [5, 1, 1, 1, 1, 2, 1, 1], datatype: 128, bitpix: 24, data: new Uint8Array(6) })),
      'unsupported',
    );
    expect(e.message).toMatch(/dim\[5\]/);
    e = await expectLoaderError(
      loadVolume(niftiFile({ dims: [6, 1, 1, 1, 1, 1, 2, 1], datatype: 2, bitpix: 8, data: new Uint8Array(2) })),
      'unsupported',
    );
    expect(e.message).toMatch(/dim\[6\] = 2/);
    // Components announced past the data: the last component's step is cut short.
    e = await expectLoaderError(
      loadVolume(niftiFile({ dims: [5, 2, 2, 2, 1, 3, 1, 1], datatype: 2, bitpix: 8, data: data.subarray(0, 20) })),
      'truncated',
    );
    expect(e.message).toMatch(/voxel data/);
  });
});

describe('channel and time axes: fuzzed headers', () => {
  it('400 random 4D/5D NRRD and NIfTI layouts give a valid volume or a typed error', async () => {
    const kinds = ['domain', 'space', 'time', 'list', 'vector', 'RGB-color', '3D-symmetric-matrix', 'complex', '???'];
    const outcomes: Record<string, number> = {};
    for (let i = 0; i < 400; i++) {
      const r = rng(24_000 + i);
      const pick = <T>(a: readonly T[]) => a[Math.floor(r() * a.length)];
      const n = 4 + Math.floor(r() * 2);
      const sizes = Array.from({ length: n }, () => Math.floor(r() * 5));
      const declared = sizes.reduce((a, b) => a * Math.max(1, b), 1);
      const data = new Uint8Array(Math.floor(declared * (0.5 + r())));
      const time = Math.floor(r() * 3);
      let source: Uint8Array;
      if (r() < 0.6) {
        const fields: Record<string, string> = {
          type: pick(['uint8', 'short', 'float']),
          dimension: String(n),
          sizes: sizes.join(' '),
          encoding: pick(['raw', 'gzip']),
          endian: 'little',
        };
        if (r() < 0.7) fields.kinds = sizes.map(() => pick(kinds)).join(' ');
        if (r() < 0.3)
          fields['space directions'] = sizes
            .map((_, k) => (r() < 0.3 ? 'none' : `(${k === 0 ? 1 : 0},${k === 1 ? 1 : 0},${k === 2 ? 1 : 0})`))
            .join(' ');
        const payload = fields.encoding === 'gzip' ? new Uint8Array(zlib.gzipSync(data)) : data;
        source = nrrdFile(fields, payload);
      } else {
        const dims = [n, ...sizes, 1, 1, 1].slice(0, 8);
        const type = pick([
          [2, 8],
          [4, 16],
          [128, 24],
          [2304, 32],
        ] as const);
        source = niftiFile({ dims, datatype: type[0], bitpix: type[1], data });
        if (r() < 0.3) source = new Uint8Array(zlib.gzipSync(source));
      }
      let outcome: { volume?: LoadedVolume; error?: unknown };
      try {
        outcome = { volume: await loadVolume(source, { time }) };
      } catch (error) {
        outcome = { error };
      }
      const kind = checkOutcome(outcome);
      outcomes[kind] = (outcomes[kind] ?? 0) + 1;
    }
    // Both loads and refusals happen (the generator is not degenerate).
    expect(outcomes.volume).toBeGreaterThan(10);
    expect(Object.keys(outcomes).length).toBeGreaterThan(3);
  });
});
