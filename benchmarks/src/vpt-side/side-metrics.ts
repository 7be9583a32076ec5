/**
 * Arithmetic of the side-by-side suite: PSNR against a finite reference, and ratios
 * between interleaved rounds.
 */
import { median, timeToPsnr, type CurvePoint } from '../metrics.js';
import type { SidePoint } from './side-page.js';

/**
 * PSNR (peak 1) of an n-iteration estimate against a reference of R iterations of the same
 * unbiased renderer made with independent random numbers. Per pixel, E[(x_n − x_R)²] =
 * v/n + v/R (v the variance of one iteration), so the error against the truth, v/n, is the
 * measured MSE times R/(R + n): the reference's own noise no longer flattens the curve.
 * R = Infinity takes the reference as exact (an estimate that is not a mean, as MIP's maximum).
 */
export function psnrAgainstTruth(mse: number, n: number, referenceIterations: number): number {
  const truth = Number.isFinite(referenceIterations) ? (mse * referenceIterations) / (referenceIterations + n) : mse;
  return 10 * Math.log10(1 / Math.max(truth, 1e-20));
}

/** A curve of the page's raw MSEs as CurvePoints (for timeToPsnr), PSNR corrected for the reference. */
export function sideCurve(points: readonly SidePoint[], referenceIterations: number): CurvePoint[] {
  return points.map((p) => {
    const psnr = psnrAgainstTruth(p.mse, p.iterations, referenceIterations);
    return {
      iterations: p.iterations,
      ms: p.ms,
      rmse: 10 ** (-psnr / 20),
      rmseRaw: Math.sqrt(p.mse),
      psnr,
      rmseLdr: NaN,
      psnrLdr: NaN,
      nonFinite: 0,
      estimatedRmse: null,
    };
  });
}

/** Time (ms) at which a side curve first reaches `db`, or null. */
export const sideTimeTo = (points: readonly SidePoint[], referenceIterations: number, db: number) =>
  timeToPsnr(sideCurve(points, referenceIterations), db);

/** Iterations at which a side curve first reaches `db` (interpolated like time), or null: the load-independent half of time to quality. */
export const sideIterationsTo = (points: readonly SidePoint[], referenceIterations: number, db: number) =>
  timeToPsnr(
    sideCurve(points, referenceIterations).map((p) => ({ ...p, ms: p.iterations })),
    db,
  );

/** Median and range of per-round ratios a_i / b_i (rounds where either is missing are left out); null when none. */
export function ratioSummary(
  a: readonly (number | null)[],
  b: readonly (number | null)[],
): { median: number; min: number; max: number; rounds: number } | null {
  const r: number[] = [];
  for (let i = 0; i < Math.min(a.length, b.length); i++) {
    const x = a[i],
      y = b[i];
    if (x !== null && y !== null && y > 0 && Number.isFinite(x / y)) r.push(x / y);
  }
  if (!r.length) return null;
  return { median: median(r), min: Math.min(...r), max: Math.max(...r), rounds: r.length };
}

/** "0.42 (0.38–0.47)", or "–" without a value. */
export function formatRatio(s: { median: number; min: number; max: number } | null): string {
  return s ? `${s.median.toFixed(2)} (${s.min.toFixed(2)}–${s.max.toFixed(2)})` : '–';
}
