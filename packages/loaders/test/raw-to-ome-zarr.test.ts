/**
 * scripts/raw-to-ome-zarr.mjs with several sidecars (what `pnpm data:fetch` does for a
 * datasets.json `omeZarr.channels`): the store's `c` axis holds each raw file in order, and
 * each sidecar's value_range, channel_label and channel_color come back through the loader as
 * that channel's omero window, label and colour. The script imports the built loaders
 * (packages/loaders/dist), so this is skipped, saying so, where they are not built.
 */
import fs from 'node:fs';
import path from 'node:path';
import { afterAll, describe, expect, it } from 'vitest';
import { loadVolume } from '../src/index.js';
import { HERE } from './helpers.js';
import { pattern, tempDir } from './zarr-fixtures.js';

const root = path.resolve(HERE, '../../..');
const built = fs.existsSync(path.join(root, 'packages', 'loaders', 'dist', 'index.js'));
const TMP = tempDir();
afterAll(() => fs.rmSync(TMP, { recursive: true, force: true }));

const dims: [number, number, number] = [5, 4, 3];
const spacing: [number, number, number] = [0.5, 0.5, 2];

/** A raw uint16 channel and its sidecar in TMP; returns the sidecar's path. */
function channel(name: string, data: Uint16Array, extra: Record<string, unknown>): string {
  fs.writeFileSync(path.join(TMP, `${name}.raw`), new Uint8Array(data.buffer, data.byteOffset, data.byteLength));
  const sidecar = { file: `${name}.raw`, dims, voxel_type: 'uint16', endianness: 'little', spacing, ...extra };
  fs.writeFileSync(path.join(TMP, `${name}.json`), JSON.stringify(sidecar));
  return path.join(TMP, `${name}.json`);
}

describe.skipIf(!built)(
  `raw-to-ome-zarr: sidecars as channels${built ? '' : ' (skipped: build the packages first, pnpm run build)'}`,
  () => {
    it("writes each raw file as a channel, with its sidecar's window, label and colour", async () => {
      const a = pattern(dims, 'uint16', 1) as Uint16Array;
      const b = pattern(dims, 'uint16', 2) as Uint16Array;
      const sidecars = [
        channel('a', a, { value_range: [3, 300], channel_label: 'nuclei', channel_color: '0000FF' }),
        // No label: the channel keeps the viewer's default name; its colour is still written.
        channel('b', b, { value_range: [7, 700], channel_color: 'FF0000' }),
      ];
      const { convertRawToOmeZarr } = await import(path.join(root, 'scripts', 'raw-to-ome-zarr.mjs'));
      const out = path.join(TMP, 'two.ome.zarr');
      await convertRawToOmeZarr(sidecars, out, { levels: 1, chunk: 4, name: 'two channels' });
      const attrs = JSON.parse(fs.readFileSync(path.join(out, '.zattrs'), 'utf8'));
      expect(attrs.multiscales[0].name).toBe('two channels');
      const v = await loadVolume(out, { zarr: { channels: [0, 1] } });
      expect(v.dims).toEqual(dims);
      expect(v.meta?.channelLabels).toEqual(['nuclei', null]);
      expect(v.meta?.channelColors).toEqual(['0000FF', 'FF0000']);
      expect(v.meta?.channelRanges).toEqual([
        [3, 300],
        [7, 700],
      ]);
      // Interleaved, channel fastest: channel 0 is a's voxels, channel 1 b's.
      const data = v.data as Uint16Array;
      for (let i = 0; i < a.length; i++) {
        expect(data[2 * i]).toBe(a[i]);
        expect(data[2 * i + 1]).toBe(b[i]);
      }
    });
  },
);
