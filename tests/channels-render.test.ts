import fs from 'node:fs';
import path from 'node:path';
import { afterAll, beforeAll, describe, expect, it } from 'vitest';
import { validateSceneDescription, type SceneDescription } from '../packages/headless/src/index.js';
import { tempDir, writeZarrFolder } from '../packages/loaders/test/zarr-fixtures.js';
import { usePage } from './helpers/session.js';

// vpt-render's scene-file interface for multichannel volumes: `"volume": { "zarr": …, "channels":
// [0, 1] }` or `"volume": { "channels": [<volume>, <volume>] }` (files of one grid), and top-level
// `"channels": [{ "transferFunction", "enabled", "color", "range" }]`. Done-when check: a channel
// whose TF has opacity 0 renders what the other channels render alone.
const page = usePage();
const TMP = tempDir('vpt-channels-render-');
afterAll(() => fs.rmSync(TMP, { recursive: true, force: true }));

const N = 16;
function blob(cx: number, cy: number, cz: number, r: number): Uint8Array {
  const d = new Uint8Array(N * N * N);
  for (let z = 0; z < N; z++)
    for (let y = 0; y < N; y++)
      for (let x = 0; x < N; x++) {
        const q = ((x + 0.5) / N - cx) ** 2 + ((y + 0.5) / N - cy) ** 2 + ((z + 0.5) / N - cz) ** 2;
        d[x + N * (y + N * z)] = Math.round(255 * Math.exp(-q / (r * r)));
      }
  return d;
}
const C0 = blob(0.4, 0.5, 0.5, 0.22),
  C1 = blob(0.62, 0.42, 0.55, 0.18);

const tf = (color: [number, number, number], opacity: number) => ({
  points: [
    { value: 0.1, color, opacity: 0 },
    { value: 1, color, opacity },
  ],
});

const scene = (renderer: string, volume: SceneDescription['volume'], channels: SceneDescription['channels']) =>
  ({
    width: 20,
    height: 16,
    renderer,
    iterations: 3,
    backend: 'webgl2',
    sampling: 'exact',
    densityScale: 10,
    camera: { position: [0.9, 0.5, 1.6], target: [0, 0, 0], up: [0, 1, 0], fovy: 0.5 },
    lights: [{ type: 'directional', direction: [-0.5, 1, 0.4], irradiance: [2, 1.8, 1.5] }],
    volume,
    channels,
  }) as SceneDescription;

function bitsDiffer(a: ArrayLike<number>, b: ArrayLike<number>): number {
  const u = new Uint32Array(Float32Array.from(a).buffer),
    v = new Uint32Array(Float32Array.from(b).buffer);
  let n = 0;
  for (let i = 0; i < u.length; i++) if (u[i] !== v[i]) n++;
  return u.length === v.length ? n : -1;
}

describe('vpt-render: multichannel scene files', () => {
  beforeAll(async () => {
    await writeZarrFolder(
      path.join(TMP, 'two.ome.zarr'),
      { dims: [N, N, N], type: 'uint8', spacing: [1, 1, 1], images: [[C0, C1]] },
      {
        version: '0.4',
        codec: 'gzip',
        windows: [
          [0, 255],
          [0, 255],
        ],
      },
    );
    fs.writeFileSync(path.join(TMP, 'c0.raw'), C0);
    fs.writeFileSync(path.join(TMP, 'c1.raw'), C1);
  });
  const opts = { baseDir: TMP, warmup: false };
  const zarr = { zarr: 'two.ome.zarr', channels: [0, 1] };
  const files = {
    channels: [
      { raw: 'c0.raw', dims: [N, N, N], type: 'uint8' },
      { raw: 'c1.raw', dims: [N, N, N], type: 'uint8' },
    ],
  } as SceneDescription['volume'];
  const red = tf([1, 0.3, 0.2], 0.8),
    green = tf([0.2, 1, 0.3], 0.9),
    none = tf([1, 0, 1], 0);

  for (const renderer of ['eam', 'mcrt', 'mip'])
    it(`${renderer}: a channel of opacity 0 renders channel 0 alone; OME-Zarr channels and a list of files agree`, async () => {
      const zeroed = await page().render(
        scene(renderer, zarr, [{ transferFunction: red }, { transferFunction: none }]),
        opts,
      );
      const alone = await page().render(
        scene(renderer, zarr, [{ transferFunction: red }, { transferFunction: none, enabled: false }]),
        opts,
      );
      const both = await page().render(
        scene(renderer, zarr, [{ transferFunction: red }, { transferFunction: green }]),
        opts,
      );
      const fromFiles = await page().render(
        scene(renderer, files, [{ transferFunction: red }, { transferFunction: green }]),
        opts,
      );
      expect(Array.from(both.hdr).every(Number.isFinite)).toBe(true);
      expect(bitsDiffer(zeroed.hdr, alone.hdr)).toBe(0);
      // The second channel is visible when its TF is not zero: the check can fail.
      let changed = 0;
      for (let i = 0; i < both.hdr.length; i += 4) if (Math.abs(both.hdr[i + 1] - zeroed.hdr[i + 1]) > 0.01) changed++;
      expect(changed).toBeGreaterThan(10);
      expect(bitsDiffer(both.hdr, fromFiles.hdr)).toBe(0);
      // The GPU memory of the 2-channel texture: 2 × 4 bytes per voxel on the exact path (rg32float).
      expect(both.gpuBytes.volume).toBe(N * N * N * 8);
      expect(alone.gpuBytes.volume).toBe(N * N * N * 4);
    });

  it('bad channel settings fail before a browser starts, naming the field', () => {
    const bad = (d: unknown) => () => validateSceneDescription(d);
    expect(bad({ volume: zarr, channels: [{ transferFunction: red }] })).toThrow(/channels: 1 entries for the 2/);
    expect(bad({ volume: { ...zarr, channel: 0 } })).toThrow(/"channel" \(one\) or "channels"/);
    expect(bad({ volume: zarr, channels: [{ transferFunction: red }, { enabled: true }] })).toThrow(
      /channels\[1\]\.transferFunction: is required/,
    );
    expect(
      bad({ volume: zarr, channels: [{ transferFunction: red }, { transferFunction: red, colour: [1, 0, 0] }] }),
    ).toThrow(/channels\[1\]/);
    expect(
      bad({ volume: zarr, channels: [{ transferFunction: red }, { transferFunction: red, color: [2, 0, 0] }] }),
    ).toThrow(/channels\[1\]\.color/);
    expect(bad({ volume: { channels: [] } })).toThrow(/volume\.channels/);
  });

  it('a scene whose volume has two channels but no channel settings is refused (typed)', async () => {
    await expect(page().render(scene('eam', zarr, undefined), opts)).rejects.toThrow(/needs "channels"/);
  });
});
