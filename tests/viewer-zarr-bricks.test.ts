import fs from 'node:fs';
import path from 'node:path';
import { afterAll, beforeAll, describe, expect, it } from 'vitest';
import {
  startFaultServer,
  tempDir,
  writeZarrFolder,
  type FaultServer,
} from '../packages/loaders/test/zarr-fixtures.js';
import { openViewerPage, type ViewerPage } from './helpers/viewer-page.js';

// <vpt-viewer src="….ome.zarr"> whose level 0 does not fit the GPU memory budget: after the
// levels that fit, level 0 streams from the store's chunks through the brick cache, and
// once its bricks are resident the image equals an unbricked render of level 0. A chunk
// that fails while streaming leaves its region at the coarser level, with one warning.
const N = 128;
const RADIUS = 24;
/** A ball of smoothly falling values in an empty (exactly zero) cube: most bricks are constant and take no atlas slot. */
function ball(): Uint8Array {
  const v = new Uint8Array(N * N * N);
  const c = (N - 1) / 2;
  for (let z = 0; z < N; z++)
    for (let y = 0; y < N; y++)
      for (let x = 0; x < N; x++) {
        const r = Math.hypot(x - c, y - c, z - c) / RADIUS;
        if (r < 1) v[x + N * (y + N * z)] = Math.round(40 + 215 * (1 - r * r));
      }
  return v;
}

// Level 0 takes 2 MiB (uint8); the volume budget is maxGpuBytes less the render targets and
// 1 MiB for the transfer function: 1.5 MiB leaves level 1 (256 KiB) fitting, level 0 not,
// and room for the ball's 8 + 8 + 1 non-constant bricks (34³ bytes each).
const MAX_GPU_BYTES = (1 << 20) + 1.5 * (1 << 20);

let vp: ViewerPage;
let server: FaultServer;
let root: string;
const warnings: string[] = [];
beforeAll(async () => {
  root = tempDir('vpt-viewer-zarr-bricks-');
  await writeZarrFolder(
    path.join(root, 'ball.ome.zarr'),
    { dims: [N, N, N], type: 'uint8', spacing: [1, 1, 1], images: [[ball()]] },
    { version: '0.5', codec: 'gzip', levels: 3, chunk: [32, 32, 32] },
  );
  server = await startFaultServer(root);
  vp = await openViewerPage();
  vp.page.on('console', (m) => {
    if (m.type() === 'warn') warnings.push(m.text());
  });
});
afterAll(async () => {
  await vp?.close();
  await server?.close();
  fs.rmSync(root, { recursive: true, force: true });
});

interface BrickRun {
  loads: {
    dims: number[];
    level?: { index: number; count: number; dims: number[]; final: boolean; bricked?: boolean };
  }[];
  errors: { code: string; message: string }[];
  bricking: {
    uploaded: number;
    resident: number;
    constant: number;
    failed: number;
    finest: number;
    complete: boolean;
    gpuBytes: number;
  } | null;
  stats: string | null;
  ldr: number[];
  lit: number;
}

const TF = {
  dimensions: '1d',
  points: [
    { value: 0, color: [0, 0, 0], opacity: 0 },
    { value: 1, color: [1, 1, 1], opacity: 1 },
  ],
};

/** A MIP viewer on `src` (budget: `maxGpuBytes`, or the default), until its bricks (if any) are resident and it has converged. */
async function run(src: string, maxGpuBytes: number | undefined): Promise<BrickRun> {
  return vp.page.evaluate(
    async (s: string, budget: number | null, tf: string) => {
      const vt = window.vt;
      const el = vt.create(
        {
          src: s,
          renderer: 'mip',
          backend: 'webgl2',
          panels: 'none',
          'max-samples': '2',
          'transfer-function': tf,
          // The renderers' default steps follow the stand-in's dims: fixed, so both renders march alike.
          'renderer-params': '{"stepSize":0.004}',
        },
        'width:32px;height:32px',
      );
      if (budget !== null) el.maxGpuBytes = budget;
      const loads: BrickRun['loads'] = [];
      const errors: BrickRun['errors'] = [];
      el.addEventListener('vpt-load', (e: CustomEvent) => loads.push({ dims: e.detail.dims, level: e.detail.level }));
      el.addEventListener('vpt-error', (e: CustomEvent) =>
        errors.push({ code: e.detail.code, message: e.detail.message }),
      );
      await el.whenSettled();
      const wantsBricks = budget !== null;
      if (wantsBricks) {
        // The last vpt-load (level 0, bricked) comes after the levels that fit.
        for (let i = 0; i < 500 && !loads.some((l) => l.level?.bricked); i++) await vt.frames(1);
        await el.context.whenBricksSettled();
      }
      await vt.frames(10); // the uploads' reset reaches the session's stats
      await vt.converged(el);
      await el.updateComplete;
      const ldr = await vt.ldr(el);
      let lit = 0;
      for (let i = 0; i < ldr.length; i += 4) if (ldr[i] > 0) lit++;
      const b = el.context.stats.bricking;
      const out: BrickRun = {
        loads,
        errors,
        bricking: b && {
          uploaded: b.uploaded,
          resident: b.resident,
          constant: b.constant,
          failed: b.failed,
          finest: b.finest,
          complete: b.complete,
          gpuBytes: b.gpuBytes,
        },
        stats: vt.shadowText(el, '[part=stats]'),
        ldr,
        lit,
      };
      el.remove();
      return out;
    },
    src,
    maxGpuBytes ?? null,
    JSON.stringify(TF),
  );
}

describe('<vpt-viewer> streams an OME-Zarr level 0 beyond the budget as bricks', () => {
  it('shows the levels that fit, then level 0 bricked, equal to the unbricked level 0 once resident', async () => {
    server.faults.clear();
    const url = `${server.url}ball.ome.zarr`;
    const sent0 = server.bytesSent;
    const requests0 = server.log.length;
    const bricked = await run(url, MAX_GPU_BYTES);
    const sent = server.bytesSent - sent0;
    const level0Requests = server.log.slice(requests0).filter((p) => p.includes('/ball.ome.zarr/0/c/')).length;
    const storeBytes = (level: number) =>
      (fs.readdirSync(path.join(root, 'ball.ome.zarr', String(level)), { recursive: true }) as string[])
        .map((f) => path.join(root, 'ball.ome.zarr', String(level), f))
        .filter((f) => fs.statSync(f).isFile())
        .reduce((n, f) => n + fs.statSync(f).size, 0);
    expect(bricked.errors).toEqual([]);
    expect(bricked.loads.map((l) => [l.level?.index, l.level?.final, l.level?.bricked ?? false])).toEqual([
      [2, false, false],
      [1, false, false],
      [0, true, true],
    ]);
    expect(bricked.loads.at(-1)!.level!.dims).toEqual([N, N, N]);
    const b = bricked.bricking!;
    expect(b).not.toBeNull();
    expect(b.complete).toBe(true);
    expect(b.failed).toBe(0);
    // Every level-0 brick the ball touches is its own (8 of 64); the other 56 are constant.
    expect(b.finest).toBeGreaterThanOrEqual(8);
    expect(b.resident).toBeGreaterThanOrEqual(8);
    expect(b.gpuBytes).toBeLessThan(MAX_GPU_BYTES);
    expect(bricked.stats).toMatch(/level bricked 0 \(\d+\/64 bricks\) of 3/);
    expect(bricked.lit).toBeGreaterThan(20);
    // A brick's read with its apron spans up to 27 chunks; the store's chunk cache fetches each of the 4³ once.
    expect(level0Requests).toBe(64);
    console.log(
      `bricked OME-Zarr (128³ uint8 ball, budget ${MAX_GPU_BYTES} B): ${b.uploaded} bricks uploaded until complete, ` +
        `${b.resident} resident, ${b.constant} constant, atlas+tables ${b.gpuBytes} B, ${sent} bytes served in all, ` +
        `${level0Requests} level-0 chunk requests; stored: level 0 ${storeBytes(0)} B, 1 ${storeBytes(1)} B, 2 ${storeBytes(2)} B`,
    );

    const direct = await run(`${url}#level=0`, undefined);
    expect(direct.errors).toEqual([]);
    expect(direct.bricking).toBeNull();
    expect(direct.loads[0].dims).toEqual([N, N, N]);
    // The bricked filter reads the same voxels (the apron holds the neighbours): the same pixels,
    // up to the hardware filter's weights (one LDR step).
    expect(bricked.ldr.length).toBe(direct.ldr.length);
    let worst = 0;
    for (let i = 0; i < direct.ldr.length; i++) worst = Math.max(worst, Math.abs(bricked.ldr[i] - direct.ldr[i]));
    expect(worst).toBeLessThanOrEqual(1);
  });

  it('a level-0 chunk that fails while streaming keeps the coarser level there, with one warning', async () => {
    server.faults.clear();
    // Chunk (z, y, x) = (1, 1, 1): voxels 32–63 on every axis, inside the ball.
    // Cut short (a missing chunk would be the fill value, the Zarr spec's default).
    server.faults.set('/ball.ome.zarr/0/c/1/1/1', 'truncate');
    warnings.length = 0;
    const failed = await run(`${server.url}ball.ome.zarr`, MAX_GPU_BYTES);
    expect(failed.errors).toEqual([]);
    expect(failed.loads.at(-1)!.level).toMatchObject({ index: 0, bricked: true });
    // A brick is read with its one-voxel apron, so every level-0 brick next to the chunk
    // (3 × 3 × 3 of them) needs it and fails; those regions keep level 1.
    expect(failed.bricking).toMatchObject({ failed: 27, complete: true });
    expect(failed.stats).toMatch(/27 failed/);
    expect(failed.lit).toBeGreaterThan(20);
    const brickWarnings = warnings.filter((w) => /brick/i.test(w));
    expect(brickWarnings).toHaveLength(1);
    expect(brickWarnings[0]).toMatch(/0\/c\/1\/1\/1/);
    server.faults.clear();
  });
});
