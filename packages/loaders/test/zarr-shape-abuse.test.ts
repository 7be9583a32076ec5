// OME-Zarr stores whose shapes and chunks abuse the reader (issue 28): each one must end in
// a typed LoaderError within seconds, or read the level that fits, never hang or throw raw.
import fs from 'node:fs';
import path from 'node:path';
import { afterAll, describe, expect, it } from 'vitest';
import { loadVolume } from '../src/index.js';
import { MAX_ZARR_CHUNKS_PER_READ } from '../src/zarr/multiscale-source.js';
import { expectLoaderError } from './helpers.js';
import {
  HUGE_SHAPE,
  plantGzipBomb,
  TINY_CHUNKS,
  writeAbusedStore,
  ZERO_CHUNK,
  type AbuseStoreOptions,
  type ZarrayEdit,
} from './zarr-abuse-stores.js';
import { tempDir } from './zarr-fixtures.js';

const TMP = tempDir('vpt-zarr-abuse-');
afterAll(() => fs.rmSync(TMP, { recursive: true, force: true }));

/** An abused store in the temp folder (see zarr-abuse-stores.ts). */
function store(name: string, edit: ZarrayEdit, options?: AbuseStoreOptions): Promise<string> {
  return writeAbusedStore(path.join(TMP, `${name}.ome.zarr`), edit, options);
}

/** The load's outcome and how long it took. */
async function timed<T>(p: Promise<T>): Promise<{ ms: number; value?: T; error?: unknown }> {
  const t0 = Date.now();
  try {
    return { ms: Date.now() - t0, value: await p };
  } catch (error) {
    return { ms: Date.now() - t0, error };
  }
}

describe('OME-Zarr shape abuse ends in a typed error or the level that fits', () => {
  it('1³ chunks on a 64³ shape: limit-exceeded naming the chunk requests, before any of them', async () => {
    const dir = await store('tiny-chunks', TINY_CHUNKS);
    const t0 = Date.now();
    const e = await expectLoaderError(loadVolume(dir), 'limit');
    expect(Date.now() - t0).toBeLessThan(5000);
    expect(e.code).toBe('limit-exceeded');
    expect(e.message).toMatch(new RegExp(`262144 chunk.*more than ${MAX_ZARR_CHUNKS_PER_READ}`));
    // Asked for by name, the same level is refused the same way.
    expect((await expectLoaderError(loadVolume(dir, { zarr: { level: 0 } }), 'limit')).message).toMatch(/chunks/);
  });

  it('a 100000³ shape: limit-exceeded, not "Invalid typed array length"', async () => {
    const dir = await store('huge-shape', HUGE_SHAPE);
    const e = await expectLoaderError(loadVolume(dir), 'limit');
    expect(e.code).toBe('limit-exceeded');
    expect(e.message).not.toMatch(/Invalid typed array length/);
    expect(e.message).toMatch(/no level can be read whole/);
  });

  it('100000³ with a 16³ level: the level that fits is read, with a warning saying why', async () => {
    const dir = await store('huge-with-level', HUGE_SHAPE, { levels: 2 });
    const r = await timed(loadVolume(dir));
    expect(r.error).toBeUndefined();
    expect(r.value!.dims).toEqual([8, 8, 8]);
    expect(((r.value!.meta?.warnings as string[]) ?? []).join(' ')).toMatch(/level 1 \[8, 8, 8\] is read: level 0 has/);
  });

  it('a chunk side of 0: a typed bad-header naming the chunk shape', async () => {
    const dir = await store('zero-chunk', ZERO_CHUNK);
    const e = await expectLoaderError(loadVolume(dir), 'bad-header');
    expect(e.message).toMatch(/chunk shape \[0, 8, 8\] must be 3 positive integers/);
    expect(e.message).not.toMatch(/empty iterator/);
  });

  it('a gzip bomb in a chunk is refused as soon as it inflates past the chunk size', async () => {
    const dir = await store('gzip-bomb', () => {}, { codec: 'gzip' });
    plantGzipBomb(dir);
    const t0 = Date.now();
    const e = await expectLoaderError(loadVolume(dir), 'limit');
    expect(e.message).toMatch(/inflates past \d+ bytes/);
    expect(Date.now() - t0).toBeLessThan(3000);
  }, 30_000);
});
