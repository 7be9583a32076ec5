/**
 * OME-Zarr channels read together (`zarr.channels`): one read over the chunks gives the
 * interleaved multichannel volume, each channel equal to that channel read alone.
 */
import fs from 'node:fs';
import path from 'node:path';
import { afterAll, describe, expect, it } from 'vitest';
import { loadVolume, openOmeZarr } from '../src/index.js';
import { expectLoaderError, serve } from './helpers.js';
import { pattern, tempDir, writeZarrFolder } from './zarr-fixtures.js';

const TMP = tempDir();
afterAll(() => fs.rmSync(TMP, { recursive: true, force: true }));

const dims: [number, number, number] = [6, 5, 4];
const images = [0, 1].map((t) => [0, 1, 2].map((c) => pattern(dims, 'uint16', 10 * t + c)));
const windows: [number, number][] = [
  [0, 100],
  [5, 500],
  [7, 900],
];

/** Channels `picked` of time `t`, interleaved channel fastest, from the images written. */
function interleaved(t: number, picked: number[]): number[] {
  const n = dims[0] * dims[1] * dims[2];
  const out: number[] = [];
  for (let i = 0; i < n; i++) for (const c of picked) out.push(images[t][c][i]);
  return out;
}

describe('OME-Zarr: several channels in one read', () => {
  it('carries the omero labels and colours of the channels read, in their order (bad ones left out)', async () => {
    for (const version of ['0.4', '0.5'] as const) {
      const dir = await writeZarrFolder(
        path.join(TMP, `info-${version}.ome.zarr`),
        { dims, type: 'uint16', spacing: [1, 1, 1], images },
        {
          version,
          windows,
          channelInfo: [{ label: 'DAPI', color: '0000FF' }, { color: 'red' }, { label: 'GFP', color: '00ff00' }],
        },
      );
      const v = await loadVolume(dir, { zarr: { channels: [2, 0, 1] } });
      expect(v.meta?.channelLabels, version).toEqual(['GFP', 'DAPI', null]);
      // 'red' is no RRGGBB hex: no colour for that channel.
      expect(v.meta?.channelColors, version).toEqual(['00ff00', '0000FF', null]);
    }
  });

  it('any channels in any order, at any time point, equal the channels read one by one', async () => {
    for (const version of ['0.4', '0.5'] as const) {
      const dir = await writeZarrFolder(
        path.join(TMP, `ch-${version}.ome.zarr`),
        { dims, type: 'uint16', spacing: [1, 2, 3], images },
        { version, codec: 'zstd', chunk: [4, 4, 4], windows },
      );
      for (const picked of [[0, 1, 2], [2, 0], [1], [0, 2]])
        for (const time of [0, 1]) {
          const v = await loadVolume(dir, { zarr: { channels: picked, time } });
          expect(v.dims).toEqual(dims);
          expect(v.spacing).toEqual([1, 2, 3]);
          expect(v.channels ?? 1).toBe(picked.length);
          expect(Array.from(v.data), `${version} [${picked}] t${time}`).toEqual(interleaved(time, picked));
          expect(v.meta?.channelRanges).toEqual(picked.map((c) => windows[c]));
          // Each channel alone, as the per-channel path reads it.
          for (const [k, c] of picked.entries()) {
            const one = await loadVolume(dir, { zarr: { channel: c, time } });
            expect(
              Array.from(v.data).filter((_, i) => i % picked.length === k),
              `channel ${c}`,
            ).toEqual(Array.from(one.data));
          }
        }
      // A region of a level, through the source.
      const s = await openOmeZarr(dir);
      const box = await s.readChannelsRegion!(0, [1, 2], [1, 1, 1], [4, 3, 2]);
      const want: number[] = [];
      for (let z = 1; z < 2; z++)
        for (let y = 1; y < 3; y++)
          for (let x = 1; x < 4; x++) for (const c of [1, 2]) want.push(images[0][c][x + dims[0] * (y + dims[1] * z)]);
      expect(Array.from(box)).toEqual(want);
    }
  });

  it('fetches each chunk once for all channels (one pass), over HTTP', async () => {
    await writeZarrFolder(
      path.join(TMP, 'http.ome.zarr'),
      { dims, type: 'uint16', spacing: [1, 1, 1], images },
      { version: '0.4', codec: 'raw', chunk: [4, 4, 4] },
    );
    const server = await serve(TMP);
    try {
      const v = await loadVolume(`${server.url}http.ome.zarr`, { zarr: { channels: [0, 1, 2], time: 1 } });
      expect(Array.from(v.data)).toEqual(interleaved(1, [0, 1, 2]));
      const chunks = server.requests.filter((r) => /\/0\/\d/.test(r));
      // 2 × 2 × 1 space chunks of 4³ over 6 × 5 × 4, per channel (the writer chunks c by 1): 12, none twice.
      expect(new Set(chunks).size).toBe(chunks.length);
      expect(chunks.length).toBe(12);
    } finally {
      await server.close();
    }
  });

  it('bad channel lists are typed errors naming the field', async () => {
    const dir = await writeZarrFolder(
      path.join(TMP, 'bad.ome.zarr'),
      { dims, type: 'uint16', spacing: [1, 1, 1], images },
      { version: '0.5', codec: 'raw', chunk: [4, 4, 4] },
    );
    let e = await expectLoaderError(loadVolume(dir, { zarr: { channels: [0, 3] } }), 'bad-header');
    expect(e.message).toMatch(/channels \[0, 3\]/);
    e = await expectLoaderError(loadVolume(dir, { zarr: { channels: [] } }), 'bad-header');
    expect(e.message).toMatch(/zarr\.channels/);
  });
});
