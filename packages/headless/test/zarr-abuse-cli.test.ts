// Issue 28: OME-Zarr shape abuse through vpt-render (the page, its loaders worker and the
// brick cache): each store ends in a typed error within a bound, or renders the level that
// fits, instead of hanging (1³ chunks), a raw "Invalid typed array length" (100000³), a
// self-contradictory brick-budget error (100000³ with a small level) or a slow bomb.
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import zlib from 'node:zlib';
import { afterAll, beforeAll, describe, expect, it } from 'vitest';
import { writeOmeZarr } from '@vpt/loaders';
import { runRender } from '../src/cli/render-main.js';
import type { CliIO } from '../src/cli/io.js';

let dir: string;
beforeAll(() => {
  dir = fs.mkdtempSync(path.join(os.tmpdir(), 'vpt-zarr-abuse-cli-'));
});
afterAll(() => fs.rmSync(dir, { recursive: true, force: true }));

/** A 16³ uint8 v0.4 store (8³ chunks) with `levels` levels, each level's .zarray edited; the scene beside it. */
async function sceneWith(
  name: string,
  edit: (zarray: Record<string, any>, level: number) => void,
  options: { levels?: number; codec?: 'raw' | 'gzip' } = {},
): Promise<string> {
  const store = path.join(dir, `${name}.ome.zarr`);
  await writeOmeZarr(
    (key, bytes) => {
      const file = path.join(store, ...key.split('/'));
      fs.mkdirSync(path.dirname(file), { recursive: true });
      fs.writeFileSync(file, bytes);
    },
    { dims: [16, 16, 16], type: 'uint8', spacing: [1, 1, 1], images: [[new Uint8Array(16 ** 3).fill(200)]] },
    { version: '0.4', codec: options.codec ?? 'raw', chunk: [8, 8, 8], levels: options.levels ?? 1 },
  );
  for (let k = 0; k < (options.levels ?? 1); k++) {
    const file = path.join(store, String(k), '.zarray');
    const j = JSON.parse(fs.readFileSync(file, 'utf8'));
    edit(j, k);
    fs.writeFileSync(file, JSON.stringify(j));
  }
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
    const scene = await sceneWith('tiny-chunks', (j) => {
      j.shape = [64, 64, 64];
      j.chunks = [1, 1, 1];
    });
    const r = await render(scene);
    expect(r.code).toBe(1);
    expect(r.stderr).toMatch(/262144 chunks, more than 32768 requests/);
    expect(r.ms).toBeLessThan(BOUND_MS);
  }, 120_000);

  it('100000³ with a 16³ level renders that level, saying so', async () => {
    const scene = await sceneWith(
      'huge-with-level',
      (j, k) => {
        if (k === 0) {
          j.shape = [100000, 100000, 100000];
          j.chunks = [64, 64, 64];
        }
      },
      { levels: 2 },
    );
    const r = await render(scene);
    expect(r.stderr).not.toMatch(/Invalid typed array length/);
    expect(r.code).toBe(0);
    expect(fs.existsSync(scene.replace(/\.json$/, '.png'))).toBe(true);
    expect(r.stdout + r.stderr).toMatch(/level 1 is rendered whole/);
    expect(r.ms).toBeLessThan(BOUND_MS);
  }, 120_000);

  it('a chunk side of 0 and a gzip bomb in a chunk: typed errors, fast', async () => {
    const zero = await render(await sceneWith('zero-chunk', (j) => (j.chunks = [0, 8, 8])));
    expect(zero.code).toBe(1);
    expect(zero.stderr).toMatch(/chunk shape \[0, 8, 8\] must be 3 positive integers/);
    expect(zero.stderr).not.toMatch(/empty iterator/);
    const bombScene = await sceneWith('gzip-bomb', () => {}, { codec: 'gzip' });
    fs.writeFileSync(
      path.join(dir, 'gzip-bomb.ome.zarr', '0', '0', '0', '0'),
      zlib.gzipSync(Buffer.alloc(256 << 20), { level: 1 }),
    );
    const bomb = await render(bombScene);
    expect(bomb.code).toBe(1);
    expect(bomb.stderr).toMatch(/inflates past \d+ bytes/);
    // 26 s before; a browser start and a refused chunk now.
    expect(bomb.ms).toBeLessThan(20_000);
  }, 180_000);
});
