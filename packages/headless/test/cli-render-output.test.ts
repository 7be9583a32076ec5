import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { afterAll, describe, expect, it, vi } from 'vitest';
import { decodePFM, decodePNG } from '../src/image-io.js';
import type { RenderResult, RenderSceneOptions } from '../src/render.js';

// The browser side is replaced by a fixed 2 x 1 image: this file checks what the CLI
// does with a render (options passed through, files written, the JSON line).
const calls: { desc: unknown; options: RenderSceneOptions }[] = [];
let ldr: Uint8Array | null = new Uint8Array([255, 0, 0, 255, 0, 0, 255, 128]);
vi.mock('../src/render.js', () => ({
  renderScene: async (desc: unknown, options: RenderSceneOptions): Promise<RenderResult> => {
    calls.push({ desc, options });
    return {
      width: 2,
      height: 1,
      hdr: new Float32Array([1.5, 0, 0, 1, 0, 0, 2.5, 0.5]),
      hdrPostSteps: ['denoise'],
      ldr,
      timings: { totalMs: 12.5, iterations: options.iterations ?? 64, msPerIteration: 0.19, setupMs: 40 },
      backend: { kind: 'webgl2', renderer: 'SwiftShader' },
      gpuBytes: { volume: 1000, gradient: 0, auxiliary: 16, targets: 64, total: 1080 },
      volumeDims: [10, 10, 10],
      warnings: [],
      rendererStats: {},
    };
  },
}));
const { runRender } = await import('../src/cli/render-main.js');

const dir = fs.mkdtempSync(path.join(os.tmpdir(), 'vpt-cli-out-'));
afterAll(() => fs.rmSync(dir, { recursive: true, force: true }));

describe('vpt-render output', () => {
  it('writes PNG and PFM and prints the timings as one JSON line', async () => {
    const scene = path.join(dir, 'scene.json');
    fs.writeFileSync(scene, JSON.stringify({ renderer: 'mip', width: 64 }));
    const stdout: string[] = [],
      stderr: string[] = [];
    const code = await runRender(
      [
        scene,
        '-o',
        path.join(dir, 'out', 'a.png'),
        '--pfm',
        path.join(dir, 'a.pfm'),
        '--iterations',
        '5',
        '--backend',
        'webgl2',
        '--width',
        '2',
        '--height',
        '1',
        '--seed',
        '3',
        '--root',
        dir,
      ],
      { out: (l) => stdout.push(l), err: (l) => stderr.push(l) },
    );
    expect(stderr).toEqual([]);
    expect(code).toBe(0);
    expect(calls[0].desc).toEqual({ renderer: 'mip', width: 64 });
    expect(calls[0].options).toMatchObject({
      baseDir: dir,
      iterations: 5,
      backend: 'webgl2',
      width: 2,
      height: 1,
      seed: 3,
      sceneRoot: dir,
    });
    expect(stdout).toHaveLength(1);
    expect(JSON.parse(stdout[0])).toEqual({
      totalMs: 12.5,
      iterations: 5,
      msPerIteration: 0.19,
      setupMs: 40,
      width: 2,
      height: 1,
      backend: 'webgl2',
      device: 'SwiftShader',
      gpuBytes: { volume: 1000, gradient: 0, auxiliary: 16, targets: 64, total: 1080 },
      volumeDims: [10, 10, 10],
      hdrPostSteps: ['denoise'],
    });
    const png = decodePNG(fs.readFileSync(path.join(dir, 'out', 'a.png')));
    expect(Array.from(png.rgba)).toEqual([255, 0, 0, 255, 0, 0, 255, 255]); // opaque by default
    const pfm = decodePFM(fs.readFileSync(path.join(dir, 'a.pfm')));
    expect(Array.from(pfm.rgba)).toEqual([1.5, 0, 0, 1, 0, 0, 2.5, 1]);
  });

  it('keeps the coverage alpha with --keep-alpha', async () => {
    const scene = path.join(dir, 'scene.json');
    expect(
      await runRender([scene, '-o', path.join(dir, 'alpha.png'), '--keep-alpha'], { out: () => {}, err: () => {} }),
    ).toBe(0);
    expect(Array.from(decodePNG(fs.readFileSync(path.join(dir, 'alpha.png'))).rgba)).toEqual([
      255, 0, 0, 255, 0, 0, 255, 128,
    ]);
  });

  it('fails when a PNG is asked for but the post chain is empty', async () => {
    ldr = null;
    const scene = path.join(dir, 'nopost.json');
    fs.writeFileSync(scene, JSON.stringify({ post: [] }));
    const stderr: string[] = [];
    expect(await runRender([scene, '-o', path.join(dir, 'b.png')], { out: () => {}, err: (l) => stderr.push(l) })).toBe(
      1,
    );
    expect(stderr).toEqual([expect.stringMatching(/^vpt-render: .*post chain is empty/)]);
    expect(fs.existsSync(path.join(dir, 'b.png'))).toBe(false);
  });
});
