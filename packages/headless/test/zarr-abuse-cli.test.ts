// Issue 28: OME-Zarr shape abuse through vpt-render (the page, its loaders worker and the
// brick cache): each store ends in a typed error within a bound, or renders the level that
// fits, instead of hanging (1³ chunks), a raw "Invalid typed array length" (100000³), a
// self-contradictory brick-budget error (100000³ with a small level) or a slow bomb.
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { afterAll, beforeAll, describe, expect, it } from 'vitest';
import {
  HUGE_SHAPE,
  plantGzipBomb,
  TINY_CHUNKS,
  writeAbusedStore,
  ZERO_CHUNK,
  type AbuseStoreOptions,
  type ZarrayEdit,
} from '../../loaders/test/zarr-abuse-stores.js';
import { runRender } from '../src/cli/render-main.js';
import type { CliIO } from '../src/cli/io.js';

let dir: string;
beforeAll(() => {
  dir = fs.mkdtempSync(path.join(os.tmpdir(), 'vpt-zarr-abuse-cli-'));
});
afterAll(() => fs.rmSync(dir, { recursive: true, force: true }));

/** An abused 16³ store (see the loaders' zarr-abuse-stores.ts) and a 16² scene file beside it. */
async function sceneWith(name: string, edit: ZarrayEdit, options: AbuseStoreOptions = {}): Promise<string> {
  await writeAbusedStore(path.join(dir, `${name}.ome.zarr`), edit, { fill: 200, ...options });
  const scene = path.join(dir, `${name}.json`);
  fs.writeFileSync(
    scene,
    JSON.stringify({ volume: { zarr: `${name}.ome.zarr` }, width: 16, height: 16, iterations: 1, backend: 'webgl2' }),
  );
  return scene;
}

async function render(scene: string): Promise<{ code: number; stderr: string; stdout: string; ms: number }> {
  const stderr: string[] = [];
  const stdout: string[] = [];
  const io: CliIO = { out: (l) => stdout.push(l), err: (l) => stderr.push(l) };
  const t0 = Date.now();
  const code = await runRender([scene, '-o', scene.replace(/\.json$/, '.png')], io);
  return { code, stderr: stderr.join('\n'), stdout: stdout.join('\n'), ms: Date.now() - t0 };
}

/** Browser start and a 16² render on 2 loaded cores take a few seconds; a hang took > 150 s. */
const BOUND_MS = 60_000;

describe('vpt-render on abusive OME-Zarr stores', () => {
  it('1³ chunks on a 64³ shape: limit-exceeded naming the chunk requests, in bounded time', async () => {
    const scene = await sceneWith('tiny-chunks', TINY_CHUNKS);
    const r = await render(scene);
    expect(r.code).toBe(1);
    expect(r.stderr).toMatch(/262144 chunks, more than 32768 requests/);
    expect(r.ms).toBeLessThan(BOUND_MS);
  }, 120_000);

  it('100000³ with a 16³ level renders that level, saying so', async () => {
    const scene = await sceneWith('huge-with-level', HUGE_SHAPE, { levels: 2 });
    const r = await render(scene);
    expect(r.stderr).not.toMatch(/Invalid typed array length/);
    expect(r.code).toBe(0);
    expect(fs.existsSync(scene.replace(/\.json$/, '.png'))).toBe(true);
    expect(r.stdout + r.stderr).toMatch(/level 1 is rendered whole/);
    expect(r.ms).toBeLessThan(BOUND_MS);
  }, 120_000);

  it('a chunk side of 0 and a gzip bomb in a chunk: typed errors, fast', async () => {
    const zero = await render(await sceneWith('zero-chunk', ZERO_CHUNK));
    expect(zero.code).toBe(1);
    expect(zero.stderr).toMatch(/chunk shape \[0, 8, 8\] must be 3 positive integers/);
    expect(zero.stderr).not.toMatch(/empty iterator/);
    const bombScene = await sceneWith('gzip-bomb', () => {}, { codec: 'gzip' });
    plantGzipBomb(path.join(dir, 'gzip-bomb.ome.zarr'));
    const bomb = await render(bombScene);
    expect(bomb.code).toBe(1);
    expect(bomb.stderr).toMatch(/inflates past \d+ bytes/);
    // 26 s before; a browser start and a refused chunk now.
    expect(bomb.ms).toBeLessThan(20_000);
  }, 180_000);
});
