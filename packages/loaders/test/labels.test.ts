import { afterAll, describe, expect, it } from 'vitest';
import fs from 'node:fs';
import path from 'node:path';
import { loadVolume, LoaderError, parseOmeMultiscales } from '../src/index.js';
import { bytesIn, fileOf, niftiFile, nrrdFile } from './helpers.js';
import { tempDir, writeZarrFolder } from './zarr-fixtures.js';

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

describe('OME-Zarr label groups (labels/<name>)', () => {
  const TMP = tempDir('vpt-zarr-labels-');
  afterAll(() => fs.rmSync(TMP, { recursive: true, force: true }));

  it('image-label colours and names come with the ids', async () => {
    const dir = path.join(TMP, 'image.ome.zarr', 'labels', 'organs');
    await writeZarrFolder(dir, {
      dims: [N, N, N],
      type: 'uint16',
      spacing: [1, 1, 1],
      images: [[Uint16Array.from(ids)]],
    });
    const attrsFile = path.join(dir, '.zattrs');
    const attrs = JSON.parse(fs.readFileSync(attrsFile, 'utf8'));
    attrs['image-label'] = {
      version: '0.4',
      colors: [
        { 'label-value': 1, rgba: [255, 0, 0, 255] },
        { 'label-value': 2, rgba: [0, 128, 255, 0] },
        { 'label-value': 3, rgba: [1, 2] },
      ],
      properties: [{ 'label-value': 1, name: 'liver' }],
    };
    fs.writeFileSync(attrsFile, JSON.stringify(attrs));
    const v = await loadVolume(dir, { worker: false, format: 'ome-zarr', labels: true });
    // uint16 ids stay uint16 (only other types are narrowed).
    expect(v.type).toBe('uint16');
    expect(Array.from(v.data)).toEqual(ids);
    const meta = v.meta?.zarr as { imageLabel?: unknown; warnings: string[] };
    expect(meta.imageLabel).toEqual([
      { id: 1, rgba: [255, 0, 0, 255], name: 'liver' },
      { id: 2, rgba: [0, 128, 255, 0] },
    ]);
    expect(meta.warnings.join(' ')).toMatch(/1 "image-label" entries are not a label value/);
    // v0.5 keeps it under "ome".
    const ms = parseOmeMultiscales(
      {
        ome: {
          version: '0.5',
          multiscales: attrs.multiscales,
          'image-label': { colors: [{ 'label-value': 4, rgba: [1, 2, 3, 4] }] },
        },
      },
      'v05',
    );
    expect(ms.imageLabel).toEqual([{ id: 4, rgba: [1, 2, 3, 4] }]);
  });
});
