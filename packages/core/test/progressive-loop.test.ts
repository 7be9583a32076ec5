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

  /**
   * A fake GPU queue on a fake clock: `sync()` waits for all the queued work. The iterations cost
   * `it` ms each and the finish `finish` ms; `outside(ms)` queues work the way temporal reuse's
   * history resolve does on a camera change, and raises the loop's flag. `run(frames, onReport)`
   * runs a loop with a 12 ms budget for that many frames and returns each frame's
   * [ms per iteration, finish ms] and batch size.
   */
  function fakeGpu(it: number, finish: number) {
    let now = 0;
    vi.spyOn(performance, 'now').mockImplementation(() => now);
    let pending = 0;
    let flag = false;
    const gpu = {
      iterations: 0,
      duringNextSync: null as (() => void) | null,
      outside(ms: number) {
        pending += ms;
        flag = true;
      },
      async run(frames: number, onReport: (frame: number) => void) {
        const reports: [number, number][] = [];
        const batches: number[] = [];
        await new Promise<void>((resolve) => {
          const loop = new ProgressiveLoop({
            step: (n) => {
              pending += it * n;
              gpu.iterations += n;
              batches.push(n);
            },
            finishFrame: () => (pending += finish),
            sync: async () => {
              now += pending;
              pending = 0;
              // Something that runs while the loop awaits the GPU (a camera change: a reset and its resolve).
              const during = gpu.duringNextSync;
              gpu.duringNextSync = null;
              during?.();
            },
            takeOutsideWork: () => {
              const f = flag;
              flag = false;
              return f;
            },
            onStats: (ms, finishMs) => {
              reports.push([ms, finishMs]);
              onReport(reports.length);
              if (reports.length === frames) {
                loop.stop();
                resolve();
              }
            },
          });
          loop.start({ frameBudgetMs: 12, currentIterations: () => gpu.iterations });
        });
        return { reports, batches };
      },
    };
    return gpu;
  }

  it('waits for work queued between frames before timing the iterations, and takes its time off that frame', async () => {
    // Iterations 3 ms, finish 1 ms, budget 12 ms; before every other frame a camera change queues a 3 ms resolve.
    const gpu = fakeGpu(3, 1);
    const { reports, batches } = await gpu.run(7, (frame) => {
      if (frame % 2 === 1) gpu.outside(3);
    });
    // The rate stays the iterations' own: 3 ms, not (3n + 3) / n.
    for (const [ms, finish] of reports) {
      expect(ms).toBeCloseTo(3, 9);
      expect(finish).toBeCloseTo(1, 9);
    }
    // After the first frame: (12 − 1 − 3) / 3 = 2 iterations after a resolve, (12 − 1) / 3 = 3 otherwise.
    expect(batches).toEqual([1, 2, 3, 2, 3, 2, 3]);
  });

  it('learns nothing from a frame whose estimate was reset, or that outside work joined, while it awaited the GPU', async () => {
    // Iterations 2 ms, finish 1 ms. During the 3rd frame's batch a camera change resets the
    // estimate and queues a 5 ms resolve, which the frame's finish then waits for.
    const gpu = fakeGpu(2, 1);
    const { reports } = await gpu.run(5, (frame) => {
      if (frame === 2)
        gpu.duringNextSync = () => {
          gpu.iterations = 0;
          gpu.outside(5);
        };
    });
    for (const [ms, finish] of reports) {
      expect(ms).toBeCloseTo(2, 9);
      expect(finish).toBeCloseTo(1, 9);
    }
  });
});
