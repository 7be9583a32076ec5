import fs from 'node:fs';
import path from 'node:path';
import { afterAll, beforeAll, describe, expect, it } from 'vitest';
import type { SceneDescription } from '../packages/headless/src/index.js';
import {
  HEAD_SIDECAR,
  startFaultServer,
  tempDir,
  writeHeadZarr,
  writeZarrFolder,
  type FaultServer,
} from '../packages/loaders/test/zarr-fixtures.js';
import { openOmeZarr } from '../packages/loaders/src/index.js';
import { BACKENDS, usePage } from './helpers/session.js';

// OME-Zarr end to end: the headless page reads a store through @vpt/loaders' worker
// (zarrita + codecs), so a level-0 copy of the bundled head must render bit for bit like
// the raw file, anisotropic scales must give the analytic box, and failing chunk requests
// must end in typed errors that leave the page usable.
const page = usePage();
const TMP = tempDir('vpt-zarr-browser-');
afterAll(() => fs.rmSync(TMP, { recursive: true, force: true }));

const camera = {
  position: [-1.6, -0.35, 0.55],
  target: [0, 0, 0],
  up: [0, -1, 0],
  fovy: 0.75,
} as SceneDescription['camera'];
const headScene = (volume: SceneDescription['volume'], backend: 'webgl2' | 'webgpu'): SceneDescription => ({
  width: 40,
  height: 40,
  renderer: 'eam',
  iterations: 3,
  backend,
  camera,
  densityScale: 30,
  environment: { type: 'constant', radiance: [0.02, 0.02, 0.03] },
  volume,
});

describe('OME-Zarr renders like the raw data', () => {
  beforeAll(async () => {
    await writeHeadZarr(path.join(TMP, 'head-v04-blosc.ome.zarr'), { version: '0.4', codec: 'blosc', levels: 2 });
    await writeHeadZarr(path.join(TMP, 'head-v05-zstd.ome.zarr'), { version: '0.5', codec: 'zstd', levels: 2 });
  });

  for (const backend of BACKENDS)
    it(`${backend}: level 0 of v0.4 (blosc) and v0.5 (zstd) copies of the head equals the raw render bit for bit`, async () => {
      const raw = await page().render(headScene({ sidecar: HEAD_SIDECAR }, backend), { warmup: false });
      // Not a blank image: the head covers a good part of the frame.
      let covered = 0;
      for (let i = 3; i < raw.hdr.length; i += 4) if (raw.hdr[i] > 0.05) covered++;
      expect(covered).toBeGreaterThan(200);
      for (const name of ['head-v04-blosc.ome.zarr', 'head-v05-zstd.ome.zarr']) {
        const z = await page().render(headScene({ zarr: name }, backend), { baseDir: TMP, warmup: false });
        expect(z.volumeDims).toEqual([128, 128, 84]);
        expect(
          Buffer.from(z.hdr.buffer).equals(Buffer.from(raw.hdr.buffer)),
          `${name} differs from the raw render`,
        ).toBe(true);
      }
      // Level 1 is a different (coarser) volume: the comparison above can fail.
      const coarse = await page().render(headScene({ zarr: 'head-v05-zstd.ome.zarr', level: 1 }, backend), {
        baseDir: TMP,
        warmup: false,
      });
      expect(coarse.volumeDims).toEqual([64, 64, 42]);
      expect(Buffer.from(coarse.hdr.buffer).equals(Buffer.from(raw.hdr.buffer))).toBe(false);
    });

  it('anisotropic scales give the analytic box (silhouette widths along x, y and z)', async () => {
    // A constant volume, 16³ voxels of spacing x 1, y 2, z 4: the box is 0.25 × 0.5 × 1 (longest side 1).
    const dims: [number, number, number] = [16, 16, 16];
    await writeZarrFolder(
      path.join(TMP, 'aniso.ome.zarr'),
      { dims, type: 'uint8', spacing: [1, 2, 4], images: [[new Uint8Array(16 ** 3).fill(200)]] },
      { version: '0.5', codec: 'gzip', chunk: [8, 8, 8] },
    );
    const size = 64,
      fovy = 0.5,
      d = 3;
    const silhouette = async (position: [number, number, number]) => {
      const r = await page().render(
        {
          width: size,
          height: size,
          renderer: 'eam',
          iterations: 4,
          backend: 'webgl2',
          camera: { position, target: [0, 0, 0], up: [0, 1, 0], fovy },
          densityScale: 2000,
          transferFunction: {
            points: [
              { value: 0, color: [1, 1, 1], opacity: 1 },
              { value: 1, color: [1, 1, 1], opacity: 1 },
            ],
          },
          environment: { type: 'constant', radiance: [0, 0, 0] },
          volume: { zarr: 'aniso.ome.zarr' },
        },
        { baseDir: TMP, warmup: false },
      );
      // Covered pixels along the centre row and column (coverage = HDR alpha).
      const a = (x: number, y: number) => r.hdr[4 * (y * size + x) + 3];
      let w = 0,
        h = 0;
      for (let i = 0; i < size; i++) {
        if (a(i, size / 2) > 0.5) w++;
        if (a(size / 2, i) > 0.5) h++;
      }
      return { w, h };
    };
    // Pixels a half-extent e spans at depth z in front of the camera.
    const px = (e: number, z: number) => (2 * (e / z / Math.tan(fovy / 2)) * size) / 2;
    // From +z: the near face (z = 0.5) sets the outline; x half-extent 0.125, y 0.25.
    const front = await silhouette([0, 0, d]);
    expect(Math.abs(front.w - px(0.125, d - 0.5))).toBeLessThanOrEqual(1.5);
    expect(Math.abs(front.h - px(0.25, d - 0.5))).toBeLessThanOrEqual(1.5);
    // From +x: the near face is x = 0.125; the image's horizontal axis is z (half-extent 0.5).
    const side = await silhouette([d, 0, 0]);
    expect(Math.abs(side.w - px(0.5, d - 0.125))).toBeLessThanOrEqual(1.5);
    expect(Math.abs(side.h - px(0.25, d - 0.125))).toBeLessThanOrEqual(1.5);
  });
});

describe('openOmeZarr in the page thread (the import map serves zarrita and the codecs)', () => {
  it('reads the levels and a region of a v0.5 zstd store like Node does', async () => {
    const dir = path.join(TMP, 'head-v05-zstd.ome.zarr');
    const base = page().mount(dir);
    const inPage = await page().page.evaluate(async (url: string) => {
      const { openOmeZarr } = await (0, eval)("import('/packages/loaders/dist/index.js')");
      const source = await openOmeZarr(url);
      const box = await source.readRegion(1, [10, 20, 5], [40, 50, 30]);
      return { levels: source.levels, type: source.type, box: Array.from(box as Uint8Array) };
    }, new URL(base, page().url).href);
    const node = await openOmeZarr(dir);
    expect(inPage.levels).toEqual(node.levels);
    expect(inPage.type).toBe('uint8');
    expect(inPage.box).toEqual(Array.from(await node.readRegion(1, [10, 20, 5], [40, 50, 30])));
  });
});

describe('OME-Zarr over a failing HTTP server', () => {
  let server: FaultServer;
  let root: string;
  beforeAll(async () => {
    root = tempDir('vpt-zarr-served-');
    await writeHeadZarr(path.join(root, 'head.ome.zarr'), { version: '0.5', codec: 'gzip', levels: 2 });
    server = await startFaultServer(root);
  });
  afterAll(async () => {
    await server.close();
    fs.rmSync(root, { recursive: true, force: true });
  });

  it('404, truncated and stalled chunks end in typed errors in the worker, never a hang; a one-off 500 is retried', async () => {
    const url = `${server.url}head.ome.zarr`;
    const outcome = async (options: Record<string, unknown>) =>
      page().page.evaluate(
        async (u: string, o: Record<string, unknown>) => {
          const { loadVolume } = await (0, eval)("import('/packages/loaders/dist/index.js')");
          const t0 = performance.now();
          try {
            const v = await loadVolume(u, o);
            return { dims: v.dims, loadedIn: v.meta.loadedIn, ms: performance.now() - t0 };
          } catch (e) {
            const err = e as { name: string; reason: string; code: string; message: string };
            return { name: err.name, reason: err.reason, code: err.code, message: err.message };
          }
        },
        url,
        options,
      );
    server.faults.clear();
    expect(await outcome({})).toMatchObject({ dims: [128, 128, 84], loadedIn: 'worker' });
    server.faults.set('/0/c/1/1/0', '404');
    // A chunk the store lacks is the fill value (the Zarr spec's default), not-found when strict.
    expect(await outcome({})).toMatchObject({ dims: [128, 128, 84], loadedIn: 'worker' });
    expect(await outcome({ zarr: { missingChunks: 'error' } })).toMatchObject({
      name: 'LoaderError',
      reason: 'not-found',
      code: 'load-failed',
    });
    server.faults.clear();
    server.faults.set('/0/c/1/1/0', 'truncate');
    expect(await outcome({ zarr: { retries: 1 } })).toMatchObject({ name: 'LoaderError', reason: 'truncated' });
    server.faults.clear();
    server.faults.set('/0/c/0/0/1', 'stall');
    const stalled = await outcome({ zarr: { requestTimeoutMs: 400, retries: 0 } });
    expect(stalled).toMatchObject({ name: 'LoaderError', reason: 'network' });
    expect(String(stalled.message)).toMatch(/timed out/);
    server.faults.clear();
    server.faults.set('/0/c/0/0/1', '500-once');
    expect(await outcome({})).toMatchObject({ dims: [128, 128, 84] });
    // The level the fragment names, over HTTP.
    server.faults.clear();
    expect(
      await page().page.evaluate(async (u: string) => {
        const { loadVolume } = await (0, eval)("import('/packages/loaders/dist/index.js')");
        return (await loadVolume(u)).dims;
      }, `${url}#level=1`),
    ).toEqual([64, 64, 42]);
  });

  it('a scene whose store fails renders nothing and says why; the next scene renders', async () => {
    server.faults.clear();
    server.faults.set('/0/c/0/1/1', '404');
    // Strict: a missing chunk fails the load (by default it would be the fill value).
    const scene = headScene({ zarr: `${server.url}head.ome.zarr`, missingChunks: 'error' }, 'webgl2');
    const e = await page()
      .render(scene)
      .then(
        () => null,
        (err: Error & { code?: string }) => err,
      );
    expect(e?.code).toBe('load-failed');
    expect(e?.message).toMatch(/0\/c\/0\/1\/1 is missing/);
    server.faults.clear();
    const ok = await page().render(scene, { warmup: false });
    expect(ok.volumeDims).toEqual([128, 128, 84]);
  });
});
