import { describe, expect, it } from 'vitest';
import { estimatorTable, iterationsFromHalves, iterationsFromLast, iterationsTo } from '../src/estimator-table.js';
import { processCpuMs, processTreeCpuMs } from '../src/process-cpu-time.js';
import type { ErrorCurveResult } from '../src/suites/error-vs-time.js';

/** A curve of an unbiased estimator whose MSE is `variance / n` (PSNR = p1 + 10·log10 n), peak 1. */
function curve(
  label: string,
  p1: number,
  lastIterations: number,
  extra: Partial<ErrorCurveResult> = {},
): ErrorCurveResult {
  const points = [1, 2, 4, 8, 16, 32, 64, 128, 192]
    .filter((n) => n <= lastIterations)
    .map((n) => {
      const psnr = p1 + 10 * Math.log10(n);
      const rmse = 10 ** (-psnr / 20);
      // The halves' estimate reads twice the true error: its iteration figures are 4× the truth.
      return { iterations: n, ms: 10 * n, rmse, psnr, rmseLdr: 0, psnrLdr: 0, nonFinite: 0, estimatedRmse: 2 * rmse };
    });
  return {
    scene: 'cloud',
    label,
    backend: 'webgl2',
    size: 64,
    referenceIterations: 384,
    referenceRmse: null,
    points,
    timeToDb: {},
    timeToDbLdr: {},
    ...extra,
  };
}

describe('estimator table (the estimator study)', () => {
  it('iterations to a target: the crossing, and the 1/n extrapolation from the last point and from the halves', () => {
    const c = curve('mcrt fixed: delta, phase, grid', 15, 192);
    // 10^((30 − 15)/10) = 31.6 iterations to 30 dB, 100 to 35 dB.
    expect(iterationsTo(c, 30)).toBeCloseTo(31.62, 0);
    expect(iterationsFromLast(c, 30)).toBeCloseTo(31.62, 2);
    expect(iterationsFromLast(c, 35)).toBeCloseTo(100, 2);
    expect(iterationsFromHalves(c, 35)).toBeCloseTo(400, 1);
    // Too short a curve for an extrapolation.
    expect(iterationsFromLast(curve('x', 15, 4), 30)).toBeNull();
  });

  it('averages iteration figures over runs, pools costs, and times auto against the best fixed estimator', () => {
    const run = (p1: number, ms: number[]) => [
      curve('mcrt multiple', 15, 192, {
        interleavedMsPerIteration: [...ms],
        interleavedGpuProcessCpuMsPerIteration: [20],
      }),
      curve('mcrt fixed: delta, phase, grid', 15, 192, {
        interleavedMsPerIteration: [...ms],
        interleavedGpuProcessCpuMsPerIteration: [20],
      }),
      curve('mcrt fixed: ratio, phase, grid', p1, 192, {
        interleavedMsPerIteration: [12, 12],
        interleavedGpuProcessCpuMsPerIteration: [24],
      }),
    ];
    // Ratio: 10^(-0.5) and 10^(-0.3) of delta's iterations in the two runs (mean 0.4087), at 1.2× the cost.
    const table = estimatorTable([run(20, [10, 10]), run(18, [10, 10])]);
    expect(table).toContain('**cloud** — 2 run(s)');
    // Auto's twin is delta (identical curves): their samples pooled, 4 per run.
    expect(table).toMatch(/\| auto \| 10\.0 \(10\.0–10\.0; 8\) \| 20\.0 \|/);
    const line = table.split('\n').find((l) => l.startsWith('- 35 dB, wall median cost, iterations by last point'))!;
    expect(line).toContain('best fixed ratio, phase, grid');
    expect(line).toContain(`auto / best = ${(1 / (1.2 * ((10 ** -0.5 + 10 ** -0.3) / 2))).toFixed(2)}`);
  });

  it("reads a process's CPU time, which grows with work done", () => {
    const before = processCpuMs(process.pid);
    let x = 0;
    for (let i = 0; i < 3e8; i++) x += i & 1;
    expect(x).toBeGreaterThan(0);
    expect(processCpuMs(process.pid)).toBeGreaterThan(before);
  });

  it("counts a process tree's CPU time, its root's included", () => {
    const own = processCpuMs(process.pid);
    // The root's own CPU time only grows between the two reads, so the tree's must reach it.
    expect(processTreeCpuMs(process.pid)).toBeGreaterThanOrEqual(own);
    // The machine's first process heads the tree of every other, this one too.
    expect(processTreeCpuMs(1)).toBeGreaterThanOrEqual(own);
  });
});
