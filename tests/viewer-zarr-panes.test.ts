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

// The slice panes of a <vpt-viewer layout="slices"> on an OME-Zarr whose level 0 streams as
// bricks (as in tests/viewer-zarr-bricks.test.ts): once the bricks are resident the axial pane
// shows level 0's voxels, not the coarser stand-in the element's volume is.
const N = 128;
const RADIUS = 24;
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
const BALL = ball();
// Level 0 (2 MiB) beyond the 3D view's volume budget, level 1 within it (tests/viewer-zarr-bricks.test.ts).
const MAX_GPU_BYTES = (1 << 20) + 1.5 * (1 << 20);
const WINDOW: [number, number] = [128, 256];

let vp: ViewerPage;
let server: FaultServer;
let root: string;
beforeAll(async () => {
  root = tempDir('vpt-viewer-zarr-panes-');
  await writeZarrFolder(
    path.join(root, 'ball.ome.zarr'),
    { dims: [N, N, N], type: 'uint8', spacing: [1, 1, 1], images: [[BALL]] },
    { version: '0.5', codec: 'gzip', levels: 3, chunk: [32, 32, 32] },
  );
  server = await startFaultServer(root);
  vp = await openViewerPage();
});
afterAll(async () => {
  await vp?.close();
  await server?.close();
  fs.rmSync(root, { recursive: true, force: true });
});

describe('slice panes of a streamed OME-Zarr', () => {
  it('read the finest resident level: the axial pane equals level 0 once its bricks are resident', async () => {
    const r = await vp.page.evaluate(
      async (src: string, budget: number, win: [number, number]) => {
        const vt = window.vt as any;
        document.body.style.margin = '0';
        const el = vt.create(
          { src, backend: 'webgl2', panels: 'none', 'max-samples': '1', layout: 'slices' },
          'width:900px;height:400px',
        );
        el.maxGpuBytes = budget;
        const loads: any[] = [];
        el.addEventListener('vpt-load', (e: CustomEvent) => loads.push(e.detail.level));
        await el.whenSettled();
        for (let i = 0; i < 500 && !loads.some((l) => l?.bricked); i++) await vt.frames(1);
        el.sliceWindow = win;
        await el.updateComplete;
        // The pane draws again as its own bricks arrive.
        let complete = false;
        for (let i = 0; i < 600 && !complete; i++) {
          await vt.frames(2);
          const b = el.paneContext('axial')?.stats.bricking;
          complete = !!b && b.complete;
        }
        await new Promise((res) => setTimeout(res, 300));
        await vt.frames(4);
        const ctx = el.paneContext('axial');
        const standIn = el.loadedVolume;
        const out = {
          loads,
          complete,
          size: ctx.size,
          params: ctx.renderer.getParams(),
          hdr: Array.from((await ctx.readHDR()) as Float32Array),
          standIn: { dims: Array.from(standIn.dims as number[]), data: Array.from(standIn.data as Uint8Array) },
          errors: el.__events.filter((e: { type: string }) => e.type === 'error'),
        };
        el.remove();
        return out;
      },
      `${server.url}ball.ome.zarr`,
      MAX_GPU_BYTES,
      WINDOW,
    );
    expect(r.errors).toEqual([]);
    expect(r.loads.at(-1)).toMatchObject({ index: 0, bricked: true });
    expect(r.complete).toBe(true);
    const [sx, sy] = r.standIn.dims;
    expect(sx).toBe(64);
    // Axial cuts z (no orientation) at the stand-in's layer k: world z through its centre, which
    // is the border of level 0's layers 2k and 2k + 1 (float rounding picks either).
    const k = r.params.index as number;
    const w = (d: number) => Math.min(1, Math.max(0, (d - (WINDOW[0] - WINDOW[1] / 2)) / WINDOW[1]));
    const cands = (p: number, n: number, size: number) => {
      const s = ((p + 0.5) / size) * n;
      return [...new Set([Math.floor(s - 1e-4), Math.floor(s + 1e-4)])].filter((c) => c >= 0 && c < n);
    };
    const { width: W, height: H } = r.size;
    let worst0 = 0,
      worstStandIn = 0;
    for (let j = 0; j < H; j++)
      for (let i = 0; i < W; i++) {
        const got = r.hdr[4 * (i + W * j)];
        let best = Infinity;
        for (const z of [2 * k, 2 * k + 1])
          for (const x of cands(i, N, W))
            for (const y of cands(j, N, H)) best = Math.min(best, Math.abs(got - w(BALL[x + N * (y + N * z)])));
        worst0 = Math.max(worst0, best);
        let bestS = Infinity;
        for (const x of cands(i, sx, W))
          for (const y of cands(j, sy, H))
            bestS = Math.min(bestS, Math.abs(got - w(r.standIn.data[x + sx * (y + sy * k)])));
        worstStandIn = Math.max(worstStandIn, bestS);
      }
    expect(worst0).toBeLessThan(1e-6);
    // The stand-in's own slice is not what is shown.
    expect(worstStandIn).toBeGreaterThan(0.01);
  });
});
