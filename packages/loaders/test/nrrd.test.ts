import fs from 'node:fs';
import path from 'node:path';
import zlib from 'node:zlib';
import { afterAll, beforeAll, describe, expect, it } from 'vitest';
import { loadVolume } from '../src/index.js';
import {
  FIXTURES,
  bytesIn,
  concatBytes,
  expectLoaderError,
  fileOf,
  fixture,
  normalizedChecksum,
  nrrdFile,
  serve,
  sha256,
  type TestServer,
} from './helpers.js';

const TWIN = 'mri_brain_nibabel_anatomical_33x41x25_int16';
const twinMeta = JSON.parse(new TextDecoder().decode(fixture(`${TWIN}.json`)));
const twinBytes = fixture(`${TWIN}.raw`);
const twinValues = new Int16Array(twinBytes.buffer.slice(0));

// The raw twin written as NRRD the way teem/Slicer write it: LAS directions, 2 mm voxels.
const FIELDS = {
  type: 'short',
  dimension: '3',
  space: 'left-anterior-superior',
  sizes: '33 41 25',
  'space directions': '(2,0,0) (0,2,0) (0,0,2)',
  kinds: 'domain domain domain',
  'space origin': '(32,-40,-16)',
};

describe('NRRD: the raw twin in every encoding', () => {
  it.each([
    ['raw, little-endian', { ...FIELDS, endian: 'little', encoding: 'raw' }, bytesIn(twinValues, true)],
    ['raw, big-endian', { ...FIELDS, endian: 'big', encoding: 'raw' }, bytesIn(twinValues, false)],
    [
      'gzip',
      { ...FIELDS, endian: 'little', encoding: 'gzip' },
      new Uint8Array(zlib.gzipSync(bytesIn(twinValues, true))),
    ],
    [
      'gzip, big-endian',
      { ...FIELDS, endian: 'big', encoding: 'gz' },
      new Uint8Array(zlib.gzipSync(bytesIn(twinValues, false))),
    ],
    ['ascii', { ...FIELDS, encoding: 'ascii' }, new TextEncoder().encode(Array.from(twinValues).join(' ') + '\n')],
  ])('%s', async (_, fields, data) => {
    const v = await loadVolume(fileOf(nrrdFile(fields, data), 'twin.nrrd'));
    expect(v.format).toBe('nrrd');
    expect(v.dims).toEqual(twinMeta.dims);
    expect(v.spacing).toEqual(twinMeta.spacing);
    expect(v.type).toBe('int16');
    expect(sha256(v.data)).toBe(twinMeta.sha256);
    expect(v.orientation).toEqual([1, 0, 0, 0, 1, 0, 0, 0, 1]);
    expect(v.origin).toEqual([32, -40, -16]);
    expect(v.meta?.space).toBe('LAS');
  });

  it('space directions give spacing (vector lengths) and direction cosines, not just the diagonal', async () => {
    // An oblique grid: axis i along (3,4,0) (length 5), j along (0,0,2), k along (-4·0.5, 3·0.5, 0) (length 2.5).
    const v = await loadVolume(
      nrrdFile(
        {
          type: 'uchar',
          dimension: '3',
          sizes: '2 2 2',
          encoding: 'raw',
          space: 'RAS',
          'space directions': '(3,4,0) (0,0,2) (-2,1.5,0)',
        },
        new Uint8Array(8),
      ),
    );
    expect(v.spacing).toEqual([5, 2, 2.5]);
    const o = v.orientation!;
    const expected = [0.6, 0, -0.8, 0.8, 0, 0.6, 0, 1, 0];
    o.forEach((x, i) => expect(x).toBeCloseTo(expected[i], 12));
  });

  it('a detached header (.nhdr) loads with its data file, dropped together or by URL', async () => {
    const nhdr = nrrdFile(
      { ...FIELDS, endian: 'little', encoding: 'raw', 'data file': `${TWIN}.raw` },
      new Uint8Array(0),
    );
    const v = await loadVolume([fileOf(nhdr, 'twin.nhdr'), fileOf(twinBytes, `${TWIN}.raw`)]);
    expect(sha256(v.data)).toBe(twinMeta.sha256);
    const dir = fs.mkdtempSync(path.join(process.env.TMPDIR ?? '/tmp', 'vpt-nrrd-'));
    const server = await serve(dir, { 'twin.nhdr': nhdr, [`${TWIN}.raw`]: twinBytes });
    try {
      const w = await loadVolume(`${server.url}twin.nhdr`);
      expect(normalizedChecksum(w)).toBe(normalizedChecksum(v));
    } finally {
      await server.close();
      fs.rmSync(dir, { recursive: true });
    }
  });

  it('spacings without space directions; a 4D file with one value per voxel; a 2D image', async () => {
    const v = await loadVolume(
      nrrdFile(
        { type: 'float', dimension: '3', sizes: '2 1 1', encoding: 'raw', endian: 'little', spacings: '0.5 0.25 3' },
        bytesIn(new Float32Array([1, 2]), true),
      ),
    );
    expect(v.spacing).toEqual([0.5, 0.25, 3]);
    expect(v.orientation).toBeUndefined();
    const w = await loadVolume(
      nrrdFile({ type: 'uint8', dimension: '4', sizes: '1 2 2 1', encoding: 'raw' }, new Uint8Array([9, 8, 7, 6])),
    );
    expect(w.dims).toEqual([2, 2, 1]);
    const flat = await loadVolume(
      nrrdFile({ type: 'uint8', dimension: '2', sizes: '3 1', encoding: 'raw' }, new Uint8Array([1, 2, 3])),
    );
    expect(flat.dims).toEqual([3, 1, 1]);
  });
});

describe('NRRD: bad input', () => {
  const ok = { type: 'short', dimension: '3', sizes: '4 3 2', endian: 'little', encoding: 'raw' };
  const data = bytesIn(
    new Int16Array(24).map((_, i) => i),
    true,
  );
  const load = (fields: Record<string, string>, d: Uint8Array = data) =>
    loadVolume(fileOf(nrrdFile(fields, d), 'x.nrrd'));

  it('each gets the reason a person can act on', async () => {
    await expectLoaderError(load({ ...ok, sizes: '4 3 2' }, data.subarray(0, 10)), 'truncated');
    const gz = new Uint8Array(zlib.gzipSync(data));
    await expectLoaderError(load({ ...ok, encoding: 'gzip' }, gz.subarray(0, gz.length - 10)), 'truncated');
    await expectLoaderError(load({ ...ok, sizes: '4 0 2' }), 'empty');
    await expectLoaderError(load({ ...ok, sizes: '100000 100000 100000' }), 'overflow');
    await expectLoaderError(load({ ...ok, sizes: '4 3' }), 'bad-header');
    await expectLoaderError(load({ ...ok, sizes: '4 x 2' }), 'bad-header');
    await expectLoaderError(load({ ...ok, type: 'complex' }), 'bad-header');
    await expectLoaderError(load({ ...ok, type: 'int64' }), 'unsupported');
    await expectLoaderError(load({ ...ok, encoding: 'bzip2' }), 'unsupported');
    await expectLoaderError(load({ ...ok, encoding: 'zstd' }), 'bad-header');
    // Four axes without kinds or directions: x, y, z and time (2 steps), so 24 samples are too few.
    await expectLoaderError(load({ ...ok, dimension: '4', sizes: '3 4 3 2' }), 'truncated');
    await expectLoaderError(load({ ...ok, dimension: '5', sizes: '3 4 3 2 2' }), 'unsupported');
    const { type: _t, ...noType } = ok;
    const missing = await expectLoaderError(load(noType), 'bad-header');
    expect(missing.message).toContain('"type"');
    await expectLoaderError(load({ ...ok, 'space directions': '(1,0,0) (0,0,0) (0,0,1)' }), 'bad-header');
    await expectLoaderError(load({ ...ok, 'space directions': '(1,0) (0,1,0) (0,0,1)' }), 'bad-header');
    await expectLoaderError(
      loadVolume(fileOf(nrrdFile({ ...ok, 'data file': 'elsewhere.raw' }, new Uint8Array(0)), 'x.nhdr')),
      'unsupported',
    );
    await expectLoaderError(
      loadVolume([
        fileOf(nrrdFile({ ...ok, 'data file': 'elsewhere.raw' }, new Uint8Array(0)), 'x.nhdr'),
        fileOf(data, 'other.raw'),
      ]),
      'not-found',
    );
    await expectLoaderError(
      loadVolume(new TextEncoder().encode('NRRX0004\ntype: short\n\n'), { format: 'nrrd' }),
      'bad-magic',
    );
  });

  it('a volume beyond the limits names the limit', async () => {
    const e = await expectLoaderError(
      loadVolume(fileOf(nrrdFile(ok, data), 'x.nrrd'), { limits: { maxTextureDimension3D: 3 } }),
      'limit',
    );
    expect(e.message).toContain('maxTextureDimension3D = 3');
  });
});

describe('NRRD over HTTP', () => {
  let server: TestServer;
  beforeAll(async () => {
    server = await serve(FIXTURES, {
      'a.nrrd': nrrdFile(
        { type: 'uchar', dimension: '3', sizes: '2 2 2', encoding: 'raw' },
        new Uint8Array([1, 2, 3, 4, 5, 6, 7, 8]),
      ),
    });
  });
  afterAll(async () => {
    await server.close();
  });
  it('loads by URL', async () => {
    const v = await loadVolume(`${server.url}a.nrrd`);
    expect(Array.from(v.data)).toEqual([1, 2, 3, 4, 5, 6, 7, 8]);
  });
});

/** Reference voxels from pynrrd/nibabel (fixtures/make_reference.py). */
const reference = JSON.parse(new TextDecoder().decode(fixture('reference.json'))) as Record<
  string,
  { dims: number[]; sha256: string; nonzero?: number }
>;

describe('NRRD: files from pynrrd and layouts other writers use', () => {
  it('gzip with "byte skip: -1" keeps the last bytes of the stream (pynrrd BallBinary30x30x30_byteskip_minus_one_nifti.nhdr)', async () => {
    const ref = reference['pynrrd/BallBinary30x30x30_byteskip_minus_one_nifti.nhdr'];
    const v = await loadVolume([
      fileOf(fixture('pynrrd/BallBinary30x30x30_byteskip_minus_one_nifti.nhdr'), 'ball.nhdr'),
      fileOf(fixture('pynrrd/BallBinary30x30x30.nii.gz'), 'BallBinary30x30x30.nii.gz'),
    ]);
    expect(v.dims).toEqual(ref.dims);
    expect(v.type).toBe('int16');
    expect(Array.from(v.data).filter((x) => x !== 0).length).toBe(ref.nonzero);
    expect(sha256(v.data)).toBe(ref.sha256);
    expect(v.meta?.warnings).toBeUndefined();
  });

  it('gzip with "byte skip: -1" on a stream longer than the data keeps its tail, with no warning', async () => {
    const values = new Int16Array(24).map((_, i) => 3 * i - 20);
    const junk = new Uint8Array(1000).fill(0x5a);
    const gz = new Uint8Array(zlib.gzipSync(concatBytes([junk, bytesIn(values, true)])));
    const v = await loadVolume(
      nrrdFile(
        { type: 'short', dimension: '3', sizes: '4 3 2', endian: 'little', encoding: 'gzip', 'byte skip': '-1' },
        gz,
      ),
    );
    expect(Array.from(v.data)).toEqual(Array.from(values));
    expect(v.meta?.warnings).toBeUndefined();
  });

  it('a 4D NRRD whose length-1 axis is last, with a "none" direction (pynrrd test_simple4d_raw.nrrd)', async () => {
    const ref = reference['pynrrd/test_simple4d_raw.nrrd'];
    const v = await loadVolume(fileOf(fixture('pynrrd/test_simple4d_raw.nrrd'), 'test_simple4d_raw.nrrd'));
    expect(v.dims).toEqual(ref.dims);
    // pynrrd's double, read as float32 by vpt: compare the value, not the bytes.
    expect(v.spacing).toEqual([1.5, 1.5, 1]); // the lengths of its space directions
    const four = await loadVolume(
      nrrdFile({ type: 'uint8', dimension: '4', sizes: '2 2 1 1', encoding: 'raw' }, new Uint8Array([9, 8, 7, 6])),
    );
    expect(four.dims).toEqual([2, 2, 1]);
    expect(Array.from(four.data)).toEqual([9, 8, 7, 6]);
  });

  it('an (x, y, z, t) NRRD loads its first volume and says it is a time series, not values per voxel', async () => {
    const values = new Uint8Array(2 * 2 * 2 * 13).map((_, i) => i);
    const layouts: Record<string, string>[] = [
      { kinds: 'domain domain domain time' },
      { 'space directions': '(1,0,0) (0,1,0) (0,0,2) none', space: 'right-anterior-superior' },
    ];
    for (const fields of layouts) {
      const v = await loadVolume(
        nrrdFile({ type: 'uint8', dimension: '4', sizes: '2 2 2 13', encoding: 'raw', ...fields }, values),
      );
      expect(v.dims).toEqual([2, 2, 2]);
      expect(v.channels).toBeUndefined();
      expect(v.meta?.timeSteps).toBe(13);
      expect(Array.from(v.data)).toEqual(Array.from(values.subarray(0, 8)));
      const warnings = String(v.meta?.warnings);
      expect(warnings).toMatch(/13 volumes/);
      expect(warnings).not.toMatch(/per voxel/);
    }
    // Values per voxel of a tensor kind stay refused, and the message says so (colours are channels: nrrd-4d.test.ts).
    const tensor = await expectLoaderError(
      loadVolume(
        nrrdFile(
          {
            type: 'uint8',
            dimension: '4',
            sizes: '6 2 2 2',
            encoding: 'raw',
            kinds: '3D-symmetric-matrix domain domain domain',
          },
          new Uint8Array(48),
        ),
      ),
      'unsupported',
    );
    expect(tensor.message).toMatch(/6 values per voxel/);
    expect(tensor.message).toContain('3D-symmetric-matrix');
  });

  it('a 2D NRRD in a 2D space ("space dimension: 2") places its pixels in the z = 0 plane', async () => {
    const values = new Float32Array([1, 2, 3, 4, 5, 6]);
    const v = await loadVolume(
      nrrdFile(
        {
          type: 'float',
          dimension: '2',
          'space dimension': '2',
          sizes: '3 2',
          'space directions': '(0,0.5) (-2,0)',
          'space origin': '(10,20)',
          endian: 'little',
          encoding: 'raw',
        },
        bytesIn(values, true),
      ),
    );
    expect(v.dims).toEqual([3, 2, 1]);
    expect(Array.from(v.data)).toEqual(Array.from(values));
    expect(v.spacing).toEqual([0.5, 2, 1]);
    // Columns: x runs along +y, y along −x, the normal is their cross product (+z).
    expect(v.orientation?.map((x) => x + 0)).toEqual([0, -1, 0, 1, 0, 0, 0, 0, 1]); // + 0: −0 is 0
    expect(v.origin).toEqual([10, 20, 0]);
    await expectLoaderError(
      loadVolume(
        nrrdFile(
          { type: 'uchar', dimension: '2', 'space dimension': '4', sizes: '1 1', encoding: 'raw' },
          new Uint8Array(1),
        ),
      ),
      'unsupported',
    );
  });
});

describe('NRRD: 32-bit integers', () => {
  it('int32 beyond ±2^24 says it rounds as float32, as the OME-Zarr reader does', async () => {
    const big = new Int32Array([-(2 ** 30), 1, 2, 3]);
    const v = await loadVolume(
      nrrdFile({ type: 'int', dimension: '1', sizes: '4', endian: 'little', encoding: 'raw' }, bytesIn(big, true)),
    );
    expect(v.type).toBe('float32');
    expect(Array.from(v.data)).toEqual(Array.from(big).map(Math.fround));
    expect(String(v.meta?.warnings)).toMatch(/int32 data is read as float32.*2\^24 round/);
  });

  it('big-endian 16-, 32- and 64-bit samples read as the values written', async () => {
    const cases: [string, Int16Array | Uint32Array | Float32Array | Float64Array][] = [
      ['short', new Int16Array([-32768, -2, 0x1234, 32767])],
      ['uint', new Uint32Array([0, 1, 0x89abcdef, 0xffffffff])],
      ['float', new Float32Array([-1.5, 0, 3.25e-20, 6.5e30])],
      ['double', new Float64Array([-0.1, 1e-300, 123456.789, Math.PI])],
    ];
    for (const [type, values] of cases) {
      const v = await loadVolume(
        nrrdFile({ type, dimension: '1', sizes: '4', endian: 'big', encoding: 'raw' }, bytesIn(values, false)),
      );
      expect(Array.from(v.data), type).toEqual(Array.from(values).map(Math.fround));
    }
  });
});
