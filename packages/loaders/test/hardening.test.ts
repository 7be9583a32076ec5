import zlib from 'node:zlib';
import { describe, expect, it } from 'vitest';
import { loadVolume } from '../src/index.js';
import { createContext } from '../src/context.js';
import { gunzip } from '../src/io/gzip.js';
import { dicomFile, expectLoaderError, fileOf, nrrdFile, type DicomSpec } from './helpers.js';

// Issue 15 item 7: no silent fallbacks in the loaders.
const NRRD = { type: 'uchar', dimension: '3', sizes: '2 2 2', encoding: 'raw' };
const warningsOf = (v: { meta?: { warnings?: unknown } }) => (v.meta?.warnings as string[] | undefined) ?? [];

describe('NRRD', () => {
  it.each(['nan', '0', 'inf', '-0'])('spacings %s is reported as a warning, 1 used', async (bad) => {
    const v = await loadVolume(nrrdFile({ ...NRRD, spacings: `1 ${bad} 2` }, new Uint8Array(8)));
    expect(v.spacing).toEqual([1, 1, 2]);
    expect(warningsOf(v).join('\n')).toMatch(
      new RegExp(`spacings\\[1\\] = .* is not a positive finite size; 1 used`, 'i'),
    );
  });
  it('collinear space directions are refused', async () => {
    const e = await expectLoaderError(
      loadVolume(nrrdFile({ ...NRRD, space: 'RAS', 'space directions': '(1,0,0) (2,0,0) (0,0,1)' }, new Uint8Array(8))),
      'bad-header',
    );
    expect(e.message).toMatch(/collinear or coplanar/);
  });
  it('data past the declared size is loaded with a warning naming the byte count', async () => {
    const v = await loadVolume(nrrdFile(NRRD, new Uint8Array(8 + 1000)));
    expect(v.dims).toEqual([2, 2, 2]);
    expect(warningsOf(v).join('\n')).toMatch(/1000 bytes past the data the header declares are ignored/);
  });
  it('a byte skip past the end reports no negative byte count', async () => {
    const e = await expectLoaderError(
      loadVolume(nrrdFile({ ...NRRD, 'byte skip': '100' }, new Uint8Array(8))),
      'truncated',
    );
    expect(e.message).not.toMatch(/-\d/);
    expect(e.message).toMatch(/needs 8 bytes but only 0 are there/);
  });
});

describe('raw sidecar', () => {
  const raw = new Uint8Array(8);
  const load = (sidecar: object) => loadVolume([fileOf(JSON.stringify(sidecar), 'v.json'), fileOf(raw, 'v.raw')]);
  it('dims given as strings are refused', async () => {
    const e = await expectLoaderError(load({ dims: ['2', '2', '2'], voxel_type: 'uint8' }), 'bad-header');
    expect(e.message).toMatch(/dims \["2","2","2"\] must be numbers, not strings/);
  });
  it.each([[[3, 3]], [['0', '1']], [[0, NaN]], [[1]]])('value_range %j is refused', async (vr) => {
    const e = await expectLoaderError(load({ dims: [2, 2, 2], voxel_type: 'uint8', value_range: vr }), 'bad-header');
    expect(e.message).toMatch(/value_range .* must be two different finite numbers/);
  });
  it('a valid value_range is kept', async () => {
    expect((await load({ dims: [2, 2, 2], voxel_type: 'uint8', value_range: [0, 7] })).meta?.value_range).toEqual([
      0, 7,
    ]);
  });
});

describe('DICOM PixelSpacing present but invalid is reported as invalid, not missing', () => {
  const slice = (k: number, pixelSpacing?: [number, number]): DicomSpec => ({
    rows: 2,
    cols: 2,
    iop: [1, 0, 0, 0, 1, 0],
    pixelSpacing,
    ipp: [0, 0, k],
    pixels: new Uint16Array(4),
    instance: k,
  });
  it.each([[[NaN, NaN]], [[-1, -1]], [[0, 0]]] as [[number, number]][])('%j', async (ps) => {
    const v = await loadVolume([0, 1].map((k) => fileOf(dicomFile(slice(k, ps)), `s${k}.dcm`)));
    const w = warningsOf(v).join('\n');
    expect(w).toMatch(/invalid PixelSpacing .* \(must be two positive numbers\); 1 used in-plane/);
    expect(w).not.toMatch(/no PixelSpacing/);
  });
  it('absent is still "no PixelSpacing"', async () => {
    const v = await loadVolume([0, 1].map((k) => fileOf(dicomFile(slice(k)), `s${k}.dcm`)));
    expect(warningsOf(v).join('\n')).toMatch(/no PixelSpacing/);
  });
});

describe('gzip bomb', () => {
  it('peak inflated memory stays within 9/8 of the cap, and the bomb is a limit error', async () => {
    const bomb = new Uint8Array(zlib.gzipSync(new Uint8Array(64 << 20))); // 64 MiB of zeros, ~64 KiB compressed
    const maxBytes = 1 << 20;
    const ctx = createContext('bomb.gz', { limits: { maxBytes } });
    const stats = { peakBytes: 0 };
    await expect(gunzip(bomb, ctx, { maxOutput: maxBytes, stats })).rejects.toMatchObject({ reason: 'limit' });
    expect(stats.peakBytes).toBeGreaterThan(0);
    expect(stats.peakBytes).toBeLessThanOrEqual((maxBytes * 9) / 8);
  });
  it('a gzip NRRD whose stream inflates far past the size its header announces keeps the announced bytes and says how many it ignored', async () => {
    const maxBytes = 2 << 20;
    // The header announces 1 MiB (fits); the stream holds 48 MiB.
    const e = await loadVolume(
      nrrdFile(
        { type: 'uchar', dimension: '3', sizes: '1024 1024 1', encoding: 'gzip' },
        new Uint8Array(zlib.gzipSync(new Uint8Array(48 << 20))),
      ),
      { limits: { maxBytes } },
    );
    expect(e.dims).toEqual([1024, 1024, 1]);
    expect(warningsOf(e).join('\n')).toMatch(/49283072 inflated bytes past the data the header declares are ignored/);
  });
});
