import fs from 'node:fs';
import path from 'node:path';
import { afterAll, beforeAll, describe, expect, it } from 'vitest';
import type { SceneDescription } from '../packages/headless/src/index.js';
import { tempDir, writeZarrFolder } from '../packages/loaders/test/zarr-fixtures.js';
import { BACKENDS, usePage } from './helpers/session.js';
import { twoFieldBall } from './helpers/uint8-ball.js';

// vpt-render: a 2-channel OME-Zarr (`"channels": [0, 1]`, no `level`) whose level 0 exceeds
// maxGpuBytes with both channels counted streams through the brick cache (one source per
// channel, interleaved; an rg32float atlas on the exact path) from the finest level that
// fits; once every brick is resident it renders the unbricked level 0 bit for bit.
const page = usePage();
const TMP = tempDir('vpt-zarr-bricked-channels-');
afterAll(() => fs.rmSync(TMP, { recursive: true, force: true }));

const N = 128;

// Exact sampling stores 4 bytes a voxel per channel (rg32float): level 0 takes 16 MiB, level 1
// 2 MiB. The budget left after the 1 MiB transfer-function allowance and the small targets is
// just under 12 MiB: level 1 fits, level 0 does not (it would as one channel of 8 MiB), and the
// 8 + 8 + 1 non-constant bricks (34³ texels × 8 bytes; the brick size is 32) do.
const MAX_GPU_BYTES = (1 << 20) + 12 * (1 << 20);

const tf = (color: [number, number, number], opacity: number) => ({
  points: [
    { value: 0.1, color, opacity: 0 },
    { value: 1, color, opacity },
  ],
});

const scene = (renderer: string, level: number | undefined, backend: 'webgl2' | 'webgpu', maxGpuBytes?: number) =>
  ({
    width: 24,
    height: 24,
    renderer,
    // The default step follows the stand-in level's dims: fixed, so both renders march alike.
    rendererParams: { stepSize: 0.01 },
    iterations: 2,
    backend,
    sampling: 'exact',
    densityScale: 10,
    camera: { position: [1.1, 0.7, 1.6], target: [0, 0, 0], up: [0, 1, 0], fovy: 0.6 },
    volume: { zarr: 'two.ome.zarr', channels: [0, 1], ...(level !== undefined ? { level } : {}) },
    channels: [{ transferFunction: tf([1, 0.3, 0.2], 0.8) }, { transferFunction: tf([0.2, 1, 0.3], 0.9) }],
    ...(maxGpuBytes ? { maxGpuBytes } : {}),
  }) as SceneDescription;

describe('vpt-render streams a multichannel OME-Zarr level 0 beyond maxGpuBytes as bricks', () => {
  beforeAll(async () => {
    const [a, b] = twoFieldBall(N);
    await writeZarrFolder(
      path.join(TMP, 'two.ome.zarr'),
      { dims: [N, N, N], type: 'uint8', spacing: [1, 1, 1], images: [[a, b]] },
      {
        version: '0.5',
        codec: 'gzip',
        levels: 3,
        chunk: [32, 32, 32],
        windows: [
          [0, 255],
          [0, 255],
        ],
      },
    );
  });

  for (const backend of BACKENDS)
    for (const renderer of ['mip', 'eam'])
      it(`${backend}, ${renderer}: two channels bricked from the chunks, equal bit for bit to the unbricked level 0`, async () => {
        const opts = { baseDir: TMP, warmup: false };
        const bricked = await page().render(scene(renderer, undefined, backend, MAX_GPU_BYTES), opts);
        expect(bricked.warnings).toEqual([]);
        expect(bricked.bricking).toMatchObject({ complete: true, failed: 0, finest: 64 });
        expect(bricked.volumeDims).toEqual([64, 64, 64]); // the stand-in: level 1, the finest that fits
        expect(bricked.gpuBytes.total).toBeLessThanOrEqual(MAX_GPU_BYTES);
        const direct = await page().render(scene(renderer, 0, backend), opts);
        expect(direct.bricking).toBeNull();
        expect(direct.volumeDims).toEqual([N, N, N]);
        let lit = 0;
        for (let i = 0; i < direct.hdr.length; i += 4) if (direct.hdr[i] > 0.1) lit++;
        expect(lit).toBeGreaterThan(20); // something to compare
        let worst = 0;
        for (let i = 0; i < direct.hdr.length; i++) worst = Math.max(worst, Math.abs(bricked.hdr[i] - direct.hdr[i]));
        expect(worst).toBe(0);
      });
});
