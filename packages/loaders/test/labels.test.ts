import { describe, expect, it } from 'vitest';
import { loadVolume, LoaderError } from '../src/index.js';
import { bytesIn, fileOf, niftiFile, nrrdFile } from './helpers.js';

// Segmentations load as label volumes with `labels: true`: ids kept (uint8 / uint16, the narrowest
// that holds them), never normalized or averaged; values that are not ids fail typed.
const N = 6;
const ids = Array.from({ length: N * N * N }, (_, i) => (i % 7 === 0 ? 0 : (i % 5) + 1));

describe('label volumes from NIfTI and NRRD', () => {
  it('a NIfTI int16 segmentation loads as uint8 ids, the same ids', async () => {
    const data = bytesIn(Int16Array.from(ids), true);
    const file = niftiFile({ dims: [N, N, N], datatype: 4, bitpix: 16, data });
    const plain = await loadVolume(fileOf(file, 'seg.nii'), { worker: false });
    expect(plain.type).toBe('int16');
    const v = await loadVolume(fileOf(file, 'seg.nii'), { worker: false, labels: true });
    expect(v.type).toBe('uint8');
    expect(Array.from(v.data)).toEqual(ids);
    expect(v.meta?.labels).toBe(true);
    expect((v as { valueRange?: unknown }).valueRange).toBeUndefined();
  });

  it('a NIfTI int32 atlas with ids above 255 loads as uint16', async () => {
    const big = ids.map((x) => (x ? x * 1000 : 0));
    const file = niftiFile({ dims: [N, N, N], datatype: 8, bitpix: 32, data: bytesIn(Int32Array.from(big), true) });
    const v = await loadVolume(fileOf(file, 'atlas.nii'), { worker: false, labels: true });
    expect(v.type).toBe('uint16');
    expect(Array.from(v.data)).toEqual(big);
  });

  it('a float NIfTI of integer ids loads as ids; a fractional value fails with invalid-data', async () => {
    const file = niftiFile({ dims: [N, N, N], datatype: 16, bitpix: 32, data: bytesIn(Float32Array.from(ids), true) });
    const v = await loadVolume(fileOf(file, 'seg.nii'), { worker: false, labels: true });
    expect(v.type).toBe('uint8');
    expect(Array.from(v.data)).toEqual(ids);
    const frac = Float32Array.from(ids);
    frac[3] = 2.5;
    const bad = niftiFile({ dims: [N, N, N], datatype: 16, bitpix: 32, data: bytesIn(frac, true) });
    const e = await loadVolume(fileOf(bad, 'bad.nii'), { worker: false, labels: true }).catch((x: unknown) => x);
    expect(e).toBeInstanceOf(LoaderError);
    expect((e as LoaderError).reason).toBe('invalid-data');
    expect((e as Error).message).toMatch(/bad\.nii \(a label volume\): voxel 3 holds 2\.5, not a label id/);
  });

  it('an NRRD segmentation (short) loads as uint8 ids', async () => {
    const file = nrrdFile(
      { type: 'short', dimension: '3', sizes: `${N} ${N} ${N}`, encoding: 'raw', endian: 'little' },
      bytesIn(Int16Array.from(ids), true),
    );
    const v = await loadVolume(fileOf(file, 'seg.nrrd'), { worker: false, labels: true });
    expect(v.type).toBe('uint8');
    expect(Array.from(v.data)).toEqual(ids);
  });

  it('a downsample picks ids (each block’s first voxel), never averages them', async () => {
    // Ids 1 and 3 alternate along x: a box average of a pair would make 2, an id that is not there.
    const alt = Array.from({ length: 8 * 8 * 8 }, (_, i) => (i % 2 ? 3 : 1));
    const file = niftiFile({ dims: [8, 8, 8], datatype: 2, bitpix: 8, data: Uint8Array.from(alt) });
    const opts = { worker: false, downsample: true, limits: { maxBytes: 8 * 8 * 8 - 1 } } as const;
    const averaged = await loadVolume(fileOf(file, 'seg.nii'), opts);
    expect(new Set(averaged.data)).toContain(2);
    const picked = await loadVolume(fileOf(file, 'seg.nii'), { ...opts, labels: true });
    expect(picked.dims).toEqual([4, 4, 4]);
    expect(new Set(picked.data)).toEqual(new Set([1]));
  });
});
