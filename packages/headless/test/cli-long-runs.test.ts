// Issue 28 item 5, the CLI's side: --time-limit reaches the render, progress lines go to
// stderr (rate-limited), a time-limited run says so, and the JSON line carries the
// renderer's reported choice. The browser side is replaced by a stub (long-runs.test.ts
// runs the real one).
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { afterAll, describe, expect, it, vi } from 'vitest';
import type { RenderResult, RenderSceneOptions } from '../src/render.js';
import { parseRenderArgs } from '../src/cli/args.js';

const calls: RenderSceneOptions[] = [];
/** Progress the stub reports: [done, total, ms]. */
let progress: [number, number, number][] = [];
let timeLimited = false;
vi.mock('../src/render.js', () => ({
  renderScene: async (_desc: unknown, options: RenderSceneOptions): Promise<RenderResult> => {
    calls.push(options);
    for (const p of progress) options.onProgress?.(...p);
    return {
      width: 1,
      height: 1,
      hdr: new Float32Array([1, 1, 1, 1]),
      hdrPostSteps: [],
      ldr: new Uint8Array([255, 255, 255, 255]),
      timings: {
        totalMs: 10,
        iterations: timeLimited ? 7 : 100,
        msPerIteration: 0.1,
        setupMs: 1,
        ...(timeLimited ? { timeLimited: true } : {}),
      },
      backend: { kind: 'webgl2', renderer: 'SwiftShader' },
      gpuBytes: { volume: 0, gradient: 0, auxiliary: 0, targets: 0, total: 0 },
      volumeDims: [8, 8, 8],
      warnings: [],
      rendererStats: { estimator: 'residual ratio tracking', why: 'dense medium' },
    };
  },
}));
const { runRender } = await import('../src/cli/render-main.js');

const dir = fs.mkdtempSync(path.join(os.tmpdir(), 'vpt-cli-long-'));
const scene = path.join(dir, 'scene.json');
fs.writeFileSync(scene, JSON.stringify({ renderer: 'mcrt', iterations: 1000 }));
afterAll(() => fs.rmSync(dir, { recursive: true, force: true }));

async function run(argv: string[]) {
  const stdout: string[] = [],
    stderr: string[] = [];
  const code = await runRender([scene, '-o', path.join(dir, 'a.png'), ...argv], {
    out: (l) => stdout.push(l),
    err: (l) => stderr.push(l),
  });
  return { code, json: JSON.parse(stdout.at(-1) ?? '{}'), stderr };
}

describe('vpt-render long runs', () => {
  it('--time-limit reaches the render in ms, and a stopped run says so on stderr and in the JSON line', async () => {
    timeLimited = true;
    progress = [];
    const r = await run(['--time-limit', '2.5']);
    expect(r.code).toBe(0);
    expect(calls.at(-1)!.timeLimitMs).toBe(2500);
    expect(r.json).toMatchObject({ iterations: 7, timeLimited: true });
    expect(r.stderr.join('\n')).toMatch(/time limit of 2\.5 s stopped the render after 7 iterations/);
    timeLimited = false;
  });

  it('progress lines: none in the first 3 s, then at most one per 5 s, each with the count and the time left', async () => {
    progress = [
      [10, 1000, 1000],
      [40, 1000, 4000],
      [60, 1000, 6000],
      [200, 1000, 10_000],
      [1000, 1000, 50_000],
    ];
    const r = await run([]);
    const lines = r.stderr.filter((l) => /iterations \(/.test(l));
    expect(lines).toEqual([
      expect.stringMatching(/^vpt-render: 40\/1000 iterations \(4\.0 %\), 4 s, about 96 s left$/),
      expect.stringMatching(/^vpt-render: 200\/1000 iterations \(20\.0 %\), 10 s, about 40 s left$/),
    ]);
    // (1000 - 40) × 4 s / 40 = 96 s and (1000 - 200) × 10 s / 200 = 40 s: the remaining work at the mean rate.
  });

  it("the JSON line carries the renderer's reported choice", async () => {
    progress = [];
    const r = await run([]);
    expect(r.json.rendererStats).toEqual({ estimator: 'residual ratio tracking', why: 'dense medium' });
  });

  it('--time-limit must be a positive number of seconds', () => {
    for (const bad of ['0', '-1', 'soon', 'Infinity', '1e9'])
      expect(() => parseRenderArgs(['s.json', '-o', 'a.png', `--time-limit=${bad}`])).toThrow(
        /--time-limit must be a number from 0.001 to 86400/,
      );
    expect(parseRenderArgs(['s.json', '-o', 'a.png', '--time-limit', '0.5']).timeLimit).toBe(0.5);
  });
});
