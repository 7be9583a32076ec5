import { afterAll, beforeAll, describe, expect, it } from 'vitest';
import { normalizedData } from '@vpt/core';
import { loadVolume, type LoadProgress } from '../src/index.js';
import {
  FIXTURES,
  bytesIn,
  expectLoaderError,
  fileOf,
  fixture,
  normalizedChecksum,
  serve,
  sha256,
  type TestServer,
} from './helpers.js';

const ANAT = 'mri_brain_nibabel_anatomical_33x41x25_int16';
const sidecar = (name: string) => JSON.parse(new TextDecoder().decode(fixture(`${name}.json`)));

describe('raw + JSON sidecar', () => {
  it("loads the sidecar and its raw file (dropped together) with the sidecar's dims, spacing, type and exact bytes", async () => {
    const meta = sidecar(ANAT);
    const v = await loadVolume([
      fileOf(fixture(`${ANAT}.json`), `${ANAT}.json`),
      fileOf(fixture(`${ANAT}.raw`), `${ANAT}.raw`),
    ]);
    expect(v.format).toBe('raw');
    expect(v.dims).toEqual(meta.dims);
    expect(v.spacing).toEqual(meta.spacing);
    expect(v.type).toBe('int16');
    expect(v.data).toBeInstanceOf(Int16Array);
    // The data's bytes hash to the sha256 recorded by whoever made the dataset.
    expect(sha256(v.data)).toBe(meta.sha256);
    expect(v.meta?.dataRange).toEqual(meta.value_range);
  });

  it.each(['uint8', 'uint16', 'int16', 'float32'] as const)(
    'reads %s in both byte orders to the same values',
    async (type) => {
      const C = { uint8: Uint8Array, uint16: Uint16Array, int16: Int16Array, float32: Float32Array }[type];
      const values = [0, 1, 7, 100, 200, 255];
      if (type !== 'uint8') values.push(1000, type === 'int16' || type === 'float32' ? -1234 : 40000);
      if (type === 'float32') values.push(0.5, -3.25e-3, 1e20);
      const expected = new C(2 * 3 * 4);
      for (let i = 0; i < expected.length; i++) expected[i] = values[i % values.length];
      for (const endianness of ['little', 'big'] as const) {
        const v = await loadVolume(bytesIn(expected, endianness === 'little'), {
          raw: { dims: [2, 3, 4], type, endianness, spacing: [1, 2, 3] },
        });
        expect(v.type).toBe(type);
        expect(Array.from(v.data)).toEqual(Array.from(expected));
        expect(v.spacing).toEqual([1, 2, 3]);
      }
    },
  );

  it('a big-endian copy of the raw twin equals the little-endian original', async () => {
    const le = await loadVolume(fixture(`${ANAT}.raw`), { raw: { dims: [33, 41, 25], type: 'int16' } });
    const swapped = bytesIn(new Int16Array(fixture(`${ANAT}.raw`).buffer), false);
    const be = await loadVolume(swapped, { raw: { dims: [33, 41, 25], type: 'int16', endianness: 'big' } });
    expect(normalizedChecksum(be)).toBe(normalizedChecksum(le));
  });

  it('float32 NaN/Inf voxels load, are counted in meta.nonFiniteCount, and normalize to 0', async () => {
    const f = new Float32Array([0, 1, NaN, 2, Infinity, 3, -Infinity, 4]);
    const v = await loadVolume(new Uint8Array(f.buffer), { raw: { dims: [2, 2, 2], type: 'float32' } });
    expect(v.meta?.nonFiniteCount).toBe(3);
    expect(v.meta?.dataRange).toEqual([0, 4]);
    const n = normalizedData(v);
    expect(Array.from(n)).toEqual([0, 0.25, 0, 0.5, 0, 0.75, 0, 1]);
  });

  it("takes dims and type from the data folder's file-name pattern when there is no sidecar", async () => {
    const v = await loadVolume(fileOf(fixture(`${ANAT}.raw`), `${ANAT}.raw`));
    expect(v.dims).toEqual([33, 41, 25]);
    expect(v.type).toBe('int16');
  });

  describe('bad input', () => {
    it('truncated data, extra bytes, zero dims, overflowing dims, no description, a broken sidecar', async () => {
      const bytes = fixture(`${ANAT}.raw`);
      const raw = { dims: [33, 41, 25] as [number, number, number], type: 'int16' as const };
      const cut = await expectLoaderError(loadVolume(bytes.subarray(0, 1000), { raw }), 'truncated');
      expect(cut.message).toMatch(/67650 bytes but the file has 1000/);
      const long = await expectLoaderError(loadVolume(bytes, { raw: { ...raw, type: 'uint8' } }), 'bad-header');
      expect(long.message).toMatch(/did you mean type uint16 or int16/);
      await expectLoaderError(loadVolume(bytes, { raw: { ...raw, dims: [33, 0, 25] } }), 'empty');
      await expectLoaderError(loadVolume(bytes, { raw: { ...raw, dims: [65536, 65536, 2] } }), 'overflow');
      await expectLoaderError(loadVolume(bytes, { raw: { ...raw, dims: [33, -41, 25] } }), 'bad-header');
      await expectLoaderError(loadVolume(bytes, { raw: { ...raw, type: 'int64' as never } }), 'bad-header');
      await expectLoaderError(loadVolume(fileOf(bytes, 'volume.raw')), 'bad-header');
      await expectLoaderError(loadVolume(new Uint8Array(0), { raw }), 'empty');
      await expectLoaderError(loadVolume([fileOf('{"dims": [1, 2', 'x.json'), fileOf(bytes, 'x.raw')]), 'bad-header');
      await expectLoaderError(
        loadVolume([fileOf('{"dims": [33, 41, 25], "voxel_type": "int16"}', 'x.json'), fileOf(bytes, 'y.raw')]),
        'not-found',
      );
      await expectLoaderError(loadVolume(new Uint8Array([1, 2, 3, 4])), 'bad-magic');
    });

    it('a volume beyond the limits fails naming the limit, or is downsampled by box averaging when asked', async () => {
      const dims: [number, number, number] = [5, 4, 3];
      const data = new Uint16Array(60).map((_, i) => i * 10);
      const bytes = new Uint8Array(data.buffer);
      const tex = await expectLoaderError(
        loadVolume(bytes, { raw: { dims, type: 'uint16' }, limits: { maxTextureDimension3D: 4 } }),
        'limit',
      );
      expect(tex.message).toContain('maxTextureDimension3D = 4');
      const mem = await expectLoaderError(
        loadVolume(bytes, { raw: { dims, type: 'uint16' }, limits: { maxBytes: 100 } }),
        'limit',
      );
      expect(mem.message).toContain('maxBytes = 100');

      const v = await loadVolume(bytes, {
        raw: { dims, type: 'uint16', spacing: [1, 1, 2] },
        limits: { maxTextureDimension3D: 4 },
        downsample: true,
      });
      expect(v.dims).toEqual([3, 4, 3]); // x shrunk by 2 (5 → 3, the last block holds one column)
      expect(v.spacing).toEqual([2, 1, 2]);
      const at = (x: number, y: number, z: number) => data[x + 5 * (y + 4 * z)];
      for (let z = 0; z < 3; z++)
        for (let y = 0; y < 4; y++)
          for (let x = 0; x < 3; x++) {
            const block = [2 * x, 2 * x + 1].filter((i) => i < 5).map((i) => at(i, y, z));
            expect(v.data[x + 3 * (y + 4 * z)]).toBe(Math.round(block.reduce((a, b) => a + b) / block.length));
          }
      expect(v.meta?.downsampled).toMatchObject({ factors: [2, 1, 1], originalDims: dims });
      const small = await loadVolume(bytes, {
        raw: { dims, type: 'uint16' },
        limits: { maxBytes: 30 },
        downsample: true,
      });
      expect(small.data.byteLength).toBeLessThanOrEqual(30);
    });

    it('an aborted signal rejects with reason aborted', async () => {
      const ac = new AbortController();
      ac.abort();
      await expectLoaderError(
        loadVolume(fixture(`${ANAT}.raw`), { raw: { dims: [33, 41, 25], type: 'int16' }, signal: ac.signal }),
        'aborted',
      );
    });
  });
});

describe('raw over HTTP', () => {
  let server: TestServer;
  beforeAll(async () => {
    server = await serve(FIXTURES, { 'noside_3x2x1_uint8.raw': new Uint8Array([1, 2, 3, 4, 5, 6]) });
  });
  afterAll(async () => {
    await server.close();
  });

  it('a sidecar URL loads its raw file, with monotonic fetch progress ending at the total', async () => {
    const events: LoadProgress[] = [];
    const v = await loadVolume(`${server.url}${ANAT}.json`, { onProgress: (p) => events.push(p) });
    expect(sha256(v.data)).toBe(sidecar(ANAT).sha256);
    const fetches = events.filter((e) => e.stage === 'fetch' && e.total === 67650);
    expect(fetches.length).toBeGreaterThan(1);
    expect(fetches.at(-1)!.loaded).toBe(67650);
    for (let i = 1; i < fetches.length; i++) expect(fetches[i].loaded).toBeGreaterThanOrEqual(fetches[i - 1].loaded);
    expect(events.some((e) => e.stage === 'convert')).toBe(true);
  });

  it('a .raw URL finds its sidecar next to it, or falls back to the name pattern', async () => {
    const v = await loadVolume(`${server.url}${ANAT}.raw`);
    expect(v.meta?.sha256).toBe(sidecar(ANAT).sha256);
    const w = await loadVolume(`${server.url}noside_3x2x1_uint8.raw`);
    expect(w.dims).toEqual([3, 2, 1]);
    expect(Array.from(w.data)).toEqual([1, 2, 3, 4, 5, 6]);
  });

  it('a URL that 404s is not-found, and aborting a slow download stops it', async () => {
    const e = await expectLoaderError(loadVolume(`${server.url}missing.nii`), 'not-found');
    expect(e.message).toContain('404');
    const ac = new AbortController();
    const p = loadVolume(`${server.url}slow/${ANAT}.raw`, {
      raw: { dims: [33, 41, 25], type: 'int16' },
      signal: ac.signal,
      onProgress: (ev) => {
        if (ev.loaded > 2000) ac.abort();
      },
    });
    await expectLoaderError(p, 'aborted');
  });

  it('an unreachable server is a network error', async () => {
    await expectLoaderError(loadVolume('http://127.0.0.1:1/x.nii'), 'network');
  });
});
