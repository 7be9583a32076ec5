import { afterEach, describe, expect, it, vi } from 'vitest';
import { ProgressiveLoop } from '../src/context/progressive-loop.js';

describe('ProgressiveLoop rate', () => {
  afterEach(() => vi.restoreAllMocks());

  it('drops a first-frame spike (compilation) at once instead of smoothing it over many frames', async () => {
    // A fake clock: the first frame's iteration takes 500 ms (compiling), every later one 10 ms.
    let now = 0;
    vi.spyOn(performance, 'now').mockImplementation(() => now);
    let frames = 0;
    const reports: number[] = [];
    let loop!: ProgressiveLoop;
    const done = new Promise<void>((resolve) => {
      loop = new ProgressiveLoop({
        step: (n) => {
          now += (frames === 0 ? 500 : 10) * n;
          frames++;
        },
        finishFrame: () => {},
        sync: async () => {},
        onStats: (ms) => {
          reports.push(ms);
          if (reports.length === 6) {
            loop.stop();
            resolve();
          }
        },
      });
    });
    loop.start({ frameBudgetMs: 12 });
    await done;
    expect(reports[0]).toBe(500);
    // The second frame (10 ms) is under half the learned 500: it replaces it (smoothing alone gives 353).
    expect(reports[1]).toBe(10);
    // Steady frames keep it there; a later rise would still be smoothed.
    for (const r of reports.slice(2)) expect(r).toBeCloseTo(10, 6);
  });

  it("learns the frame's finish (render, post chain) apart from the iterations, and fits the iterations to what it leaves", async () => {
    // Iterations cost 1 ms each, the finish (a denoiser) 8 ms per frame, the budget is 12 ms.
    let now = 0;
    vi.spyOn(performance, 'now').mockImplementation(() => now);
    const batches: number[] = [];
    const reports: [number, number][] = [];
    let loop!: ProgressiveLoop;
    const done = new Promise<void>((resolve) => {
      loop = new ProgressiveLoop({
        step: (n) => {
          now += n;
          batches.push(n);
        },
        finishFrame: () => {
          now += 8;
        },
        sync: async () => {},
        onStats: (ms, finish) => {
          reports.push([ms, finish]);
          if (reports.length === 4) {
            loop.stop();
            resolve();
          }
        },
      });
    });
    loop.start({ frameBudgetMs: 12 });
    await done;
    // Per iteration 1 ms (not (n + 8) / n), the finish 8 ms per frame.
    for (const [ms, finish] of reports) {
      expect(ms).toBeCloseTo(1, 9);
      expect(finish).toBeCloseTo(8, 9);
    }
    // After the first frame: (12 − 8) / 1 = 4 iterations, not 12.
    expect(batches).toEqual([1, 4, 4, 4]);
  });
});
