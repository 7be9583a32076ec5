/** Curve arithmetic: time (or iterations) at which a PSNR curve first reaches a target. */

export interface CurvePoint {
  iterations: number;
  ms: number;
  /** HDR RMSE against the truth: the measured one with the reference's own noise variance subtracted (when the renderer estimates it). */
  rmse: number;
  /** HDR RMSE against the reference as measured. */
  rmseRaw?: number;
  psnr: number;
  rmseLdr: number;
  psnrLdr: number;
  nonFinite: number;
  estimatedRmse: number | null;
}

/**
 * First crossing of `targetDb`, interpolated linearly in log(time) between the two
 * checkpoints around it (PSNR grows ~ linearly in log time for Monte Carlo: 10 dB per
 * decade of samples). Null when the curve never reaches the target.
 */
export function timeToPsnr(
  points: readonly CurvePoint[],
  targetDb: number,
  key: 'psnr' | 'psnrLdr' = 'psnr',
): number | null {
  for (let i = 0; i < points.length; i++) {
    if (points[i][key] >= targetDb) {
      if (i === 0) return points[0].ms;
      const a = points[i - 1],
        b = points[i];
      const f = (targetDb - a[key]) / (b[key] - a[key]);
      return Math.exp(Math.log(a.ms) + f * (Math.log(b.ms) - Math.log(a.ms)));
    }
  }
  return null;
}

export function median(xs: readonly number[]): number {
  const s = [...xs].sort((a, b) => a - b);
  const m = s.length >> 1;
  return s.length % 2 ? s[m] : (s[m - 1] + s[m]) / 2;
}

export function spread(xs: readonly number[]): { min: number; max: number } {
  return { min: Math.min(...xs), max: Math.max(...xs) };
}

/** Root-mean-square difference over the RGB channels of two RGBA images (alpha ignored). */
export function rgbRmse(a: ArrayLike<number>, b: ArrayLike<number>): number {
  let s = 0,
    n = 0;
  for (let i = 0; i < a.length; i += 4)
    for (let c = 0; c < 3; c++) {
      s += (a[i + c] - b[i + c]) ** 2;
      n++;
    }
  return Math.sqrt(s / n);
}
