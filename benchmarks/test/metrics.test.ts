import { describe, expect, it } from 'vitest';
import { median, timeToPsnr, type CurvePoint } from '../src/metrics.js';

const point = (ms: number, psnr: number): CurvePoint => ({
  iterations: 0,
  ms,
  rmse: 0,
  psnr,
  rmseLdr: 0,
  psnrLdr: psnr - 3,
  nonFinite: 0,
  estimatedRmse: null,
});

describe('timeToPsnr', () => {
  // Monte Carlo: PSNR = 10·log10(t) + c, so the crossing of target T is t = 10^((T − c)/10) exactly,
  // and log-time interpolation between checkpoints must recover it.
  const c = 12;
  const curve = [1, 3, 10, 40, 100, 700].map((t) => point(t, 10 * Math.log10(t) + c));
  it('recovers the analytic crossing time between checkpoints', () => {
    for (const target of [15, 25, 30, 35]) expect(timeToPsnr(curve, target)).toBeCloseTo(10 ** ((target - c) / 10), 6);
  });
  it('uses the first checkpoint when it already beats the target, and null when never reached', () => {
    expect(timeToPsnr(curve, 5)).toBe(1);
    expect(timeToPsnr(curve, 60)).toBeNull();
  });
  it('can read the LDR curve', () => {
    expect(timeToPsnr(curve, 20, 'psnrLdr')).toBeCloseTo(10 ** ((23 - c) / 10), 6);
  });
  it('median of even and odd counts', () => {
    expect(median([3, 1, 2])).toBe(2);
    expect(median([4, 1, 3, 2])).toBe(2.5);
  });
});
