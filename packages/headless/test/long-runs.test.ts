// Issue 28 item 5 in the real page: a render run in batches (for progress and a time limit)
// gives the same bits as one renderIterations call, a time limit stops it with fewer
// iterations and a finite image, and MCRT auto's reported choice comes back.
import { afterAll, beforeAll, describe, expect, it } from 'vitest';
import { openVptPage, type VptPageSession } from '../src/render.js';
import type { SceneDescription } from '../src/scene-description.js';

let session: VptPageSession;
beforeAll(async () => {
  session = await openVptPage({ root: null });
}, 120_000);
afterAll(() => session?.close());

const SCENE: SceneDescription = {
  renderer: 'mcrt',
  volume: { procedural: 'blob', size: 16 },
  width: 16,
  height: 16,
  iterations: 24,
  backend: 'webgl2',
};

describe('batched renders', () => {
  it('with progress the image is bit-identical to the one-call render, and progress counts up to the total', async () => {
    const plain = await session.render(SCENE);
    const seen: [number, number][] = [];
    const batched = await session.render(SCENE, { onProgress: (done, total) => seen.push([done, total]) });
    expect(Buffer.from(batched.hdr.buffer).equals(Buffer.from(plain.hdr.buffer))).toBe(true);
    expect(batched.timings.iterations).toBe(24);
    expect(seen.at(-1)).toEqual([24, 24]);
    expect(seen.every(([d], i) => i === 0 || d > seen[i - 1][0])).toBe(true);
    // MCRT auto says what it chose.
    expect(Object.keys(plain.rendererStats).length).toBeGreaterThan(0);
  });

  it('a time limit stops a long render early with a finite image', async () => {
    const t0 = Date.now();
    const r = await session.render({ ...SCENE, iterations: 1_000_000 }, { timeLimitMs: 300 });
    expect(r.timings.timeLimited).toBe(true);
    expect(r.timings.iterations).toBeGreaterThan(0);
    expect(r.timings.iterations).toBeLessThan(1_000_000);
    expect(r.hdr.every(Number.isFinite)).toBe(true);
    expect(Date.now() - t0).toBeLessThan(30_000);
  });
});
