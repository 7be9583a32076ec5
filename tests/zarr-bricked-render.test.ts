import fs from 'node:fs';
import path from 'node:path';
import { afterAll, beforeAll, describe, expect, it } from 'vitest';
import type { SceneDescription } from '../packages/headless/src/index.js';
import { tempDir, writeZarrFolder } from '../packages/loaders/test/zarr-fixtures.js';
import { BACKENDS, usePage } from './helpers/session.js';

// vpt-render: a scene's OME-Zarr volume (no `level`) whose level 0 exceeds maxGpuBytes
// streams through the brick cache from the finest level that fits; once every brick is
// resident, exact sampling gives the unbricked level-0 image bit for bit.
const page = usePage();
const TMP = tempDir('vpt-zarr-bricked-render-');
afterAll(() => fs.rmSync(TMP, { recursive: true, force: true }));

const N = 128;
/** A ball of smoothly falling values in an exactly empty cube: most bricks are constant and take no atlas slot. */
function ball(): Uint8Array {
  const v = new Uint8Array(N * N * N);
  const c = (N - 1) / 2;
  for (let z = 0; z < N; z++)
    for (let y = 0; y < N; y++)
      for (let x = 0; x < N; x++) {
        const r = Math.hypot(x - c, y - c, z - c) / 24;
        if (r < 1) v[x + N * (y + N * z)] = Math.round(40 + 215 * (1 - r * r));
      }
  return v;
}

// Exact sampling stores 4 bytes a voxel: level 0 takes 8 MiB, level 1 1 MiB. The budget left
// after the 1 MiB transfer-function allowance and the small targets is just under 4 MiB:
// level 1 fits, level 0 does not, and the ball's 8 + 8 + 1 non-constant bricks (34³ texels
// × 4 bytes each; the brick size is 32) do.
const MAX_GPU_BYTES = (1 << 20) + 4 * (1 << 20);

const scene = (volume: SceneDescription['volume'], backend: 'webgl2' | 'webgpu', maxGpuBytes?: number) =>
  ({
    width: 24,
    height: 24,
    renderer: 'mip',
    // The default step follows the stand-in level's dims: fixed, so both renders march alike.
    rendererParams: { stepSize: 0.01 },
    iterations: 2,
    backend,
    sampling: 'exact',
    camera: { position: [1.1, 0.7, 1.6], target: [0, 0, 0], up: [0, 1, 0], fovy: 0.6 },
    volume,
    ...(maxGpuBytes ? { maxGpuBytes } : {}),
  }) as SceneDescription;

describe('vpt-render streams an OME-Zarr level 0 beyond maxGpuBytes as bricks', () => {
  beforeAll(async () => {
    await writeZarrFolder(
      path.join(TMP, 'ball.ome.zarr'),
      { dims: [N, N, N], type: 'uint8', spacing: [1, 1, 1], images: [[ball()]] },
      { version: '0.5', codec: 'gzip', levels: 3, chunk: [32, 32, 32] },
    );
  });

  for (const backend of BACKENDS)
    it(`${backend}: bricked from the chunks, equal bit for bit to the unbricked level 0`, async () => {
      const opts = { baseDir: TMP, warmup: false };
      const bricked = await page().render(scene({ zarr: 'ball.ome.zarr' }, backend, MAX_GPU_BYTES), opts);
      expect(bricked.warnings).toEqual([]);
      // Every level-0 brick served by its own data (the 56 outside the ball are constant).
      expect(bricked.bricking).toMatchObject({ complete: true, failed: 0, finest: 64 });
      expect(bricked.volumeDims).toEqual([64, 64, 64]); // the stand-in: level 1, the finest that fits
      expect(bricked.gpuBytes.total).toBeLessThanOrEqual(MAX_GPU_BYTES);
      const direct = await page().render(scene({ zarr: 'ball.ome.zarr', level: 0 }, backend), opts);
      expect(direct.bricking).toBeNull();
      expect(direct.volumeDims).toEqual([N, N, N]);
      let lit = 0;
      for (let i = 0; i < direct.hdr.length; i += 4) if (direct.hdr[i] > 0.1) lit++;
      expect(lit).toBeGreaterThan(40);
      // The same voxels through the apron (docs/architecture.md, "Bricked volumes"): the same pixels.
      let worst = 0;
      for (let i = 0; i < direct.hdr.length; i++) worst = Math.max(worst, Math.abs(bricked.hdr[i] - direct.hdr[i]));
      expect(worst).toBe(0);
      const b = bricked.bricking!;
      console.log(
        `${backend} vpt-render bricked OME-Zarr (128³ ball, maxGpuBytes ${MAX_GPU_BYTES}): ${b.uploaded} bricks uploaded, ` +
          `${b.resident} resident, ${b.constant} constant, ${b.gpuBytes} B atlas+tables`,
      );
    });
});
