import fs from 'node:fs';
import path from 'node:path';
import { gzipSync } from 'node:zlib';
import { describe, expect, it } from 'vitest';
import { TimeSeriesCache, loadVolume, openTimeSeries } from '../src/index.js';
import { HERE, bytesIn, expectLoaderError, fileOf, niftiFile, sha256 } from './helpers.js';
import { pattern, tempDir, writeZarrFolder } from './zarr-fixtures.js';

/** A LoaderError of this reason whose message says this. */
async function refused(p: Promise<unknown>, reason: Parameters<typeof expectLoaderError>[1], says: RegExp) {
  expect((await expectLoaderError(p, reason)).message).toMatch(says);
}

const DIMS = [5, 4, 3] as const;
const N = DIMS[0] * DIMS[1] * DIMS[2];

/** Step t's voxels: distinct per voxel and per step. */
function stepValues(t: number): Uint16Array {
  return Uint16Array.from({ length: N }, (_, i) => 1000 * t + 7 * i + 1);
}

/** A 4D NIfTI-1 file (uint16) of `steps` volumes, pixdim[4] = 250 ms, xyzt_units mm + ms. */
function nifti4d(steps: number): Uint8Array {
  const data = new Uint8Array(N * 2 * steps);
  for (let t = 0; t < steps; t++) data.set(bytesIn(stepValues(t), true), t * N * 2);
  const file = niftiFile({
    dims: [4, ...DIMS, steps, 1, 1, 1],
    datatype: 512,
    bitpix: 16,
    data,
    pixdim: [1, 1, 1, 1, 250, 1, 1, 1],
  });
  file[123] = 2 | 16; // mm, ms
  return file;
}

describe('time series: 4D NIfTI', () => {
  for (const gz of [false, true]) {
    it(`reads every step of a 4D file${gz ? ' (gzip)' : ''} with LoadOptions.time and openTimeSeries`, async () => {
      const raw = nifti4d(3);
      const bytes = gz ? new Uint8Array(gzipSync(raw)) : raw;
      const name = gz ? 'four.nii.gz' : 'four.nii';
      for (let t = 0; t < 3; t++) {
        const v = await loadVolume(fileOf(bytes, name), { time: t });
        expect(v.dims).toEqual([...DIMS]);
        expect(Array.from(v.data)).toEqual(Array.from(stepValues(t)));
        expect(v.meta?.timeSteps).toBe(3);
        expect(v.meta?.stepSeconds).toBeCloseTo(0.25, 9);
      }
      const series = await openTimeSeries(fileOf(bytes, name));
      expect(series.steps).toBe(3);
      expect(series.stepSeconds).toBeCloseTo(0.25, 9);
      for (const t of [2, 0, 1]) expect(Array.from((await series.loadStep(t)).data)).toEqual(Array.from(stepValues(t)));
      // One step's voxels hold their own memory, not the whole file's.
      expect((await series.loadStep(1)).data.buffer.byteLength).toBe(N * 2);
      await refused(loadVolume(fileOf(bytes, name), { time: 3 }), 'bad-header', /time step 3 does not exist/);
    });
  }

  it('a 3D source refuses a step above 0, and a bad step is refused by name', async () => {
    const three = niftiFile({ dims: [...DIMS], datatype: 512, bitpix: 16, data: bytesIn(stepValues(0), true) });
    expect((await openTimeSeries(fileOf(three, 'a.nii'))).steps).toBe(1);
    await refused(loadVolume(fileOf(three, 'a.nii'), { time: 1 }), 'bad-header', /holds 1 along dim\[4\]/);
    await refused(loadVolume(fileOf(three, 'a.nii'), { time: -1 }), 'bad-header', /whole number ≥ 0/);
  });
});

describe('time series: OME-Zarr t axis', () => {
  it('steps along t are the images written, and LoadOptions.time picks one', async () => {
    const dir = path.join(tempDir(), 't.ome.zarr');
    const images = [0, 1, 2, 3].map((t) => [pattern([8, 6, 4], 'uint16', t)]);
    await writeZarrFolder(dir, { dims: [8, 6, 4], type: 'uint16', spacing: [1, 1, 2], images }, { chunk: [4, 4, 4] });
    const series = await openTimeSeries(dir);
    expect(series.steps).toBe(4);
    for (const t of [3, 1, 0, 2]) expect(Array.from((await series.loadStep(t)).data)).toEqual(Array.from(images[t][0]));
    expect(Array.from((await loadVolume(dir, { time: 2 })).data)).toEqual(Array.from(images[2][0]));
    // zarr.time, where given, wins over LoadOptions.time.
    expect(Array.from((await loadVolume(dir, { time: 2, zarr: { time: 1 } })).data)).toEqual(Array.from(images[1][0]));
    await refused(series.loadStep(4), 'bad-header', /time step 4 does not exist/);
  });
});

describe('time series: a list of files', () => {
  it('one file per step, refusing a step of another grid', async () => {
    const files = [0, 1, 2].map((t) =>
      fileOf(
        niftiFile({ dims: [...DIMS], datatype: 512, bitpix: 16, data: bytesIn(stepValues(t), true) }),
        `s${t}.nii`,
      ),
    );
    const series = await openTimeSeries(files);
    expect(series.steps).toBe(3);
    for (const t of [1, 2, 0]) expect(Array.from((await series.loadStep(t)).data)).toEqual(Array.from(stepValues(t)));
    const other = fileOf(
      niftiFile({ dims: [3, 4, 5], datatype: 512, bitpix: 16, data: bytesIn(stepValues(0), true) }),
      'other.nii',
    );
    const mixed = await openTimeSeries([files[0], other]);
    await refused(mixed.loadStep(1), 'invalid-data', /unlike step 0's 5×4×3 uint16/);
    await expectLoaderError(openTimeSeries([]), 'empty');
  });

  it('a cache over a 4D file holds at most its budget and the next steps', async () => {
    const series = await openTimeSeries(fileOf(nifti4d(6), 'six.nii'));
    const cache = new TimeSeriesCache(series, { budgetBytes: 3 * N * 2, prefetch: 5 });
    await cache.get(4);
    await cache.whenPrefetched();
    expect(cache.residentSteps()).toEqual([0, 4, 5]);
    expect(cache.bytesHeld()).toBeLessThanOrEqual(3 * N * 2);
    expect(Array.from((await cache.get(5)).data)).toEqual(Array.from(stepValues(5)));
  });
});

// nibabel's example4d.nii.gz (128 × 96 × 24 × 2, nibabel's docs): step 0 is the volume the
// corpus references (nibabel's get_fdata()[..., 0]); step 1 is the file's second volume.
const EXAMPLE4D = path.join(HERE, '..', '..', '..', 'data', 'corpus', 'nibabel', 'tests', 'data', 'example4d.nii.gz');
const REFS = path.join(HERE, 'corpus', 'references.json');
describe.skipIf(!fs.existsSync(EXAMPLE4D))('time series: nibabel example4d.nii.gz', () => {
  it('has two steps; step 0 is the reference volume, step 1 another of the same grid', async () => {
    const bytes = new Uint8Array(fs.readFileSync(EXAMPLE4D));
    const series = await openTimeSeries(fileOf(bytes, 'example4d.nii.gz'));
    expect(series.steps).toBe(2);
    const ref = JSON.parse(fs.readFileSync(REFS, 'utf8')).files['nibabel/tests/data/example4d.nii.gz'].load;
    const s0 = await series.loadStep(0);
    expect(sha256(Float32Array.from(s0.data as ArrayLike<number>))).toBe(ref.sha256);
    const s1 = await series.loadStep(1);
    expect(s1.dims).toEqual(ref.dims);
    expect(sha256(Float32Array.from(s1.data as ArrayLike<number>))).not.toBe(ref.sha256);
  });
});
