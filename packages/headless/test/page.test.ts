import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import { afterAll, beforeAll, describe, expect, it } from 'vitest';
import { chromiumExecutable } from '../src/chromium.js';
import { VptError } from '@vpt/core';
import { openVptPage, PageError, type VptPageSession } from '../src/render.js';

// The page module is built output (dist/page/vpt-page.js): this runs after `pnpm run build`
// (as CI does), with test doubles of core, the renderers and post, so it tests the page's
// own work (defaults, volume loading, errors, image transfer) without GPU rendering.
const here = path.dirname(fileURLToPath(import.meta.url));
const pageBuilt = fs.existsSync(path.join(here, '..', 'dist', 'page', 'vpt-page.js'));

describe.skipIf(!pageBuilt || !fs.existsSync(chromiumExecutable()))('the headless page (with stub packages)', () => {
  let session: VptPageSession, tmp: string;

  beforeAll(async () => {
    tmp = fs.mkdtempSync(path.join(os.tmpdir(), 'vpt-page-'));
    const packageDirs: Record<string, string> = {};
    for (const name of ['core', 'renderer-mip', 'renderer-eam', 'renderer-iso', 'renderer-mcrt', 'post']) {
      fs.mkdirSync(path.join(tmp, 'packages', name, 'dist'), { recursive: true });
      fs.copyFileSync(
        path.join(here, 'fixtures', 'stub-packages', name, 'index.js'),
        path.join(tmp, 'packages', name, 'dist', 'index.js'),
      );
      packageDirs[name] = path.join(tmp, 'packages', name);
    }
    // The stub core re-exports core's real errors, raw reader and request policy (built).
    const coreDist = path.join(here, '..', '..', 'core', 'dist');
    for (const file of ['errors.js', 'scene/raw-sidecar.js', 'io/request.js']) {
      fs.mkdirSync(path.dirname(path.join(tmp, 'packages', 'core', 'dist', file)), { recursive: true });
      fs.copyFileSync(path.join(coreDist, file), path.join(tmp, 'packages', 'core', 'dist', file));
    }
    // A big-endian uint16 volume with its sidecar, and a little-endian int16 raw.
    fs.mkdirSync(path.join(tmp, 'data'));
    const be = Buffer.alloc(2 * 2 * 2 * 2);
    for (let i = 0; i < 8; i++) be.writeUInt16BE(1000 + i, i * 2);
    fs.writeFileSync(path.join(tmp, 'data', 'vol_be.raw'), be);
    fs.writeFileSync(
      path.join(tmp, 'data', 'vol_be.json'),
      JSON.stringify({
        dims: [2, 2, 2],
        voxel_type: 'uint16',
        spacing: [1, 2, 3],
        endianness: 'big',
        value_range: [1000, 1007],
      }),
    );
    const le = Buffer.alloc(3 * 1 * 1 * 2);
    [-5, 0, 7].forEach((v, i) => le.writeInt16LE(v, i * 2));
    fs.writeFileSync(path.join(tmp, 'data', 'small.raw'), le);
    session = await openVptPage({ packageDirs, root: null });
  }, 60_000);

  afterAll(async () => {
    await session?.close();
    fs.rmSync(tmp, { recursive: true, force: true });
  });

  const lastScene = () =>
    session.page.evaluate(() => {
      const s = (
        window as unknown as {
          lastScene: {
            volume: { dims: number[]; type: string; spacing: number[]; valueRange?: number[]; data: ArrayLike<number> };
          } & Record<string, unknown>;
        }
      ).lastScene;
      return { ...s, volume: { ...s.volume, data: Array.from(s.volume.data) } };
    });

  it('exposes window.vpt', async () => {
    const keys = await session.page.evaluate(() => Object.keys(window.vpt).sort());
    expect(keys).toEqual([
      'buildScene',
      'core',
      'createRenderer',
      'eam',
      'iso',
      'loadVolume',
      'mcrt',
      'mip',
      'post',
      'renderDescription',
      'renderers',
    ]);
    // Renderers come from core's catalog, by name.
    const made = await session.page.evaluate(() => {
      const r = window.vpt.createRenderer('mcrt', { a: 1 }) as unknown as { kind: string; params: unknown };
      let unknown = '';
      try {
        window.vpt.createRenderer('nope');
      } catch (e) {
        unknown = (e as Error).message;
      }
      return { kind: r.kind, params: r.params, unknown };
    });
    expect(made).toEqual({ kind: 'mcrt', params: { a: 1 }, unknown: 'Unknown renderer "nope" (mip, iso, eam, mcrt)' });
  });

  it('fills in defaults and returns the images and timings', async () => {
    const r = await session.render({ width: 4, height: 2 });
    expect([r.width, r.height]).toEqual([4, 2]);
    expect(r.hdr).toBeInstanceOf(Float32Array);
    expect(Array.from(r.hdr.subarray(0, 8))).toEqual([0, 0, 0.5, 64, 0.25, 0, 0.5, 64]);
    expect(Array.from(r.hdr.subarray(16, 20))).toEqual([0, 0.5, 0.5, 64]); // row 1, top row first
    expect(r.ldr).toBeInstanceOf(Uint8Array);
    expect(r.ldr!.length).toBe(4 * 2 * 4);
    expect(r.timings).toMatchObject({ iterations: 64, msPerIteration: 0.5 });
    expect(r.timings.totalMs).toBeGreaterThanOrEqual(0);
    expect(r.backend).toEqual({ kind: 'webgl2', renderer: 'stub eam' });
    // The context's GPU memory and the uploaded dims pass through (the stub counts the volume's bytes).
    expect(r.gpuBytes).toEqual({ volume: 32 ** 3 * 4, gradient: 0, auxiliary: 0, targets: 0, total: 32 ** 3 * 4 });
    expect(r.volumeDims).toEqual([32, 32, 32]);
    expect(r.warnings).toEqual([]);
    const s = await lastScene();
    expect(s.volume.dims).toEqual([32, 32, 32]);
    expect(s).toMatchObject({
      environment: { type: 'constant', radiance: [1, 1, 1] },
      densityScale: 10,
      seed: 1,
      lights: [],
      camera: { position: [0, 0, 2], fovy: 0.7 },
    });
    const opts = await session.page.evaluate(
      () => (window as unknown as { lastOptions: Record<string, unknown> }).lastOptions,
    );
    expect(opts).toMatchObject({
      backend: 'auto',
      width: 4,
      height: 2,
      post: [{ name: 'exposure' }, { name: 'tonemap' }, { name: 'srgb' }],
    });
  });

  it('loads a sidecar volume (big-endian) relative to baseDir, merges the camera, passes renderer params', async () => {
    const r = await session.render(
      {
        renderer: 'mip',
        rendererParams: { stepSize: 0.01 },
        volume: { sidecar: 'data/vol_be.json' },
        camera: { fovy: 1.2 },
        seed: 9,
        iterations: 3,
        width: 1,
        height: 1,
      },
      { baseDir: tmp },
    );
    expect(r.backend.renderer).toBe('stub mip');
    expect(r.timings.iterations).toBe(3);
    const s = await lastScene();
    expect(s.volume).toMatchObject({
      dims: [2, 2, 2],
      type: 'uint16',
      spacing: [1, 2, 3],
      valueRange: [1000, 1007],
      data: [1000, 1001, 1002, 1003, 1004, 1005, 1006, 1007],
    });
    expect(s).toMatchObject({ seed: 9, camera: { position: [0, 0, 2], fovy: 1.2 } });
    const params = await session.page.evaluate(
      () => (window as unknown as { lastOptions: { renderer: { params: unknown } } }).lastOptions.renderer.params,
    );
    expect(params).toEqual({ stepSize: 0.01 });
  });

  it('loads a raw volume by absolute path, and releases every context', async () => {
    await session.render({
      volume: { raw: path.join(tmp, 'data', 'small.raw'), dims: [3, 1, 1], type: 'int16', valueRange: [-5, 7] },
      width: 1,
      height: 1,
    });
    const s = await lastScene();
    expect(s.volume).toMatchObject({ dims: [3, 1, 1], type: 'int16', valueRange: [-5, 7], data: [-5, 0, 7] });
    expect(await session.page.evaluate(() => (window as unknown as { stubContexts: number }).stubContexts)).toBe(0);
  });

  it('reports page-side failures as PageError with the VptError code', async () => {
    const fail = (d: object, baseDir?: string) =>
      session.render(d, { baseDir }).then(
        () => null,
        (e: PageError) => e,
      );
    const sizeMismatch = await fail({ volume: { raw: 'data/small.raw', dims: [2, 2, 2], type: 'int16' } }, tmp);
    // Checked in Node from the file's size before the page reads anything (issue 15).
    expect(sizeMismatch).toBeInstanceOf(VptError);
    expect(sizeMismatch).toMatchObject({
      code: 'load-failed',
      message: expect.stringMatching(/need 16 bytes, the file has 6/),
    });
    const notServed = await fail({ volume: { raw: '/not/served.raw', dims: [1, 1, 1], type: 'uint8' } });
    expect(notServed).toBeInstanceOf(PageError);
    expect(notServed).toMatchObject({ code: 'load-failed', message: expect.stringMatching(/HTTP 404/) });
    expect(await fail({ backend: 'webgpu' })).toMatchObject({ code: 'no-backend' });
    await expect(
      session.render({ volume: { raw: 'data/missing.raw', dims: [1, 1, 1], type: 'uint8' } }, { baseDir: tmp }),
    ).rejects.toThrow(/Volume file not found/);
    expect(await session.page.evaluate(() => (window as unknown as { stubContexts: number }).stubContexts)).toBe(0);
  });
});

describe.skipIf(!fs.existsSync(chromiumExecutable()))('openVptPage', () => {
  it('says how to fix a page whose packages are not built', async () => {
    const empty = fs.mkdtempSync(path.join(os.tmpdir(), 'vpt-empty-'));
    try {
      const dirs = Object.fromEntries(['core', 'renderer-mip', 'renderer-eam', 'post'].map((n) => [n, empty]));
      // The page imports the packages concurrently, so whichever 404 lands first is named.
      await expect(openVptPage({ packageDirs: dirs, root: null, loadTimeoutMs: 20_000 })).rejects.toThrow(
        /could not load @vpt\/(core|renderer-mip|renderer-eam|post) .*pnpm run build/,
      );
    } finally {
      fs.rmSync(empty, { recursive: true, force: true });
    }
  }, 60_000);
});
