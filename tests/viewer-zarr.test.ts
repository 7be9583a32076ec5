import fs from 'node:fs';
import path from 'node:path';
import { afterAll, beforeAll, describe, expect, it } from 'vitest';
import { startFaultServer, tempDir, writeHeadZarr, type FaultServer } from '../packages/loaders/test/zarr-fixtures.js';
import { openViewerPage, type ViewerPage } from './helpers/viewer-page.js';

// <vpt-viewer src="….ome.zarr">: the coarsest level first, then the finest that fits,
// each a `vpt-load` with the level; the stats line names the level; a finer level that
// fails leaves the coarse one on screen with a typed error.
let vp: ViewerPage;
let server: FaultServer;
let root: string;
beforeAll(async () => {
  root = tempDir('vpt-viewer-zarr-');
  await writeHeadZarr(path.join(root, 'head.ome.zarr'), {
    version: '0.5',
    codec: 'gzip',
    levels: 3,
    chunk: [32, 32, 32],
  });
  server = await startFaultServer(root);
  vp = await openViewerPage();
});
afterAll(async () => {
  await vp?.close();
  await server?.close();
  fs.rmSync(root, { recursive: true, force: true });
});

interface LevelRun {
  loads: { dims: number[]; level?: { index: number; count: number; dims: number[]; final: boolean } }[];
  errors: { code: string; source: string; message: string }[];
  stats: string | null;
  ldr: number[];
  lit: number;
}

/** Create a viewer on `src`, wait until it settles and has its samples, and report. */
async function run(src: string): Promise<LevelRun> {
  return vp.page.evaluate(async (s: string) => {
    const vt = window.vt;
    const el = vt.create(
      { src: s, renderer: 'mip', backend: 'webgl2', panels: 'none', 'max-samples': '2' },
      'width:32px;height:32px',
    );
    const loads: LevelRun['loads'] = [];
    const errors: LevelRun['errors'] = [];
    el.addEventListener('vpt-load', (e: CustomEvent) => loads.push({ dims: e.detail.dims, level: e.detail.level }));
    el.addEventListener('vpt-error', (e: CustomEvent) =>
      errors.push({ code: e.detail.code, source: e.detail.source, message: e.detail.message }),
    );
    await el.whenSettled();
    await vt.converged(el);
    await el.updateComplete;
    const ldr = await vt.ldr(el);
    let lit = 0;
    for (let i = 0; i < ldr.length; i += 4) if (ldr[i] > 0) lit++;
    const out = { loads, errors, stats: vt.shadowText(el, '[part=stats]'), ldr, lit };
    el.remove();
    return out;
  }, src);
}

describe('<vpt-viewer> refines an OME-Zarr volume level by level', () => {
  it('shows the coarsest level first and ends at level 0, which renders exactly like loading level 0 directly', async () => {
    server.faults.clear();
    const url = `${server.url}head.ome.zarr`;
    const progressive = await run(url);
    expect(progressive.errors).toEqual([]);
    const levels = progressive.loads.map((l) => l.level);
    expect(levels[0]).toEqual({ index: 2, count: 3, dims: [32, 32, 21], final: false });
    expect(levels.at(-1)).toEqual({ index: 0, count: 3, dims: [128, 128, 84], final: true });
    // Finer each time: accumulation restarts only when the level changes.
    const indices = levels.map((l) => l!.index);
    expect(indices).toEqual([...indices].sort((a, b) => b - a));
    expect(new Set(indices).size).toBe(indices.length);
    expect(progressive.stats).toMatch(/level 0 of 3/);
    expect(progressive.lit).toBeGreaterThan(50);

    const direct = await run(`${url}#level=0`);
    expect(direct.loads).toHaveLength(1);
    expect(direct.loads[0].level).toBeUndefined();
    expect(direct.loads[0].dims).toEqual([128, 128, 84]);
    // Same box, same fitted camera and transfer function, same samples: the same pixels.
    expect(progressive.ldr).toEqual(direct.ldr);
  });

  it('a finer level that fails keeps the coarse one on screen with a typed error; another src then loads', async () => {
    server.faults.clear();
    // A chunk cut short (a missing one would be the fill value, the Zarr spec's default).
    server.faults.set('/0/c/1/1/1', 'truncate');
    const failed = await run(`${server.url}head.ome.zarr`);
    expect(failed.loads[0].level?.index).toBe(2);
    expect(failed.loads.every((l) => l.level!.index > 0)).toBe(true);
    expect(failed.errors).toHaveLength(1);
    expect(failed.errors[0]).toMatchObject({ code: 'load-failed', source: 'src' });
    expect(failed.errors[0].message).toMatch(/0\/c\/1\/1\/1/); // the chunk is named
    expect(failed.lit).toBeGreaterThan(50); // the coarse head still renders
    expect(failed.stats).toMatch(/level [12] of 3/);
    server.faults.clear();
    const after = await run(`${server.url}head.ome.zarr#level=1`);
    expect(after.errors).toEqual([]);
    expect(after.loads[0].dims).toEqual([64, 64, 42]);
    expect(vp.errors.filter((e) => !/404|Failed to load resource/.test(e))).toEqual([]);
  });
});
