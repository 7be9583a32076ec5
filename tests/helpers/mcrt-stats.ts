/**
 * Small statistics helpers for the MCRT tests: z-score summaries, and the exact binomial
 * test for estimators whose samples are 0 or 1 (delta tracking), where the normal
 * approximation fails near p = 0 or 1; the RMSE of two images.
 */

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

/**
 * z-score summary: max |z|, n, how many exceed 3, and the aggregate Σz/√n (≈ N(0, 1) without
 * bias). z is pixel-major with `channels` values per pixel; the channels of one pixel come
 * from the same path and are correlated, so the aggregate is formed per channel and the
 * largest in magnitude is reported.
 */
export function zSummary(z: number[], channels = 1): { maxAbs: number; meanScaled: number; n: number; over3: number } {
  const n = z.length;
  let maxAbs = 0,
    over3 = 0;
  const sums = new Array(channels).fill(0),
    counts = new Array(channels).fill(0);
  z.forEach((v, i) => {
    maxAbs = Math.max(maxAbs, Math.abs(v));
    if (Math.abs(v) > 3) over3++;
    sums[i % channels] += v;
    counts[i % channels]++;
  });
  let meanScaled = 0;
  for (let c = 0; c < channels; c++) {
    const m = counts[c] ? sums[c] / Math.sqrt(counts[c]) : 0;
    if (Math.abs(m) > Math.abs(meanScaled)) meanScaled = m;
  }
  return { maxAbs, meanScaled, n, over3 };
}

/** erfc(x) for x ≥ 0, Chebyshev fit with relative error < 1.2e-7 (Press et al., Numerical Recipes, erfcc). */
function erfc(x: number): number {
  const t = 1 / (1 + 0.5 * x);
  return (
    t *
    Math.exp(
      -x * x -
        1.26551223 +
        t *
          (1.00002368 +
            t *
              (0.37409196 +
                t *
                  (0.09678418 +
                    t *
                      (-0.18628806 +
                        t *
                          (0.27886807 + t * (-1.13520398 + t * (1.48851587 + t * (-0.82215223 + t * 0.17087277)))))))),
    )
  );
}

/** |z| whose two-sided normal tail probability is p (bisection on erfc). */
export function zOfTwoSidedP(p: number): number {
  if (p >= 1) return 0;
  if (p <= 0) return Infinity;
  let lo = 0,
    hi = 40;
  for (let k = 0; k < 100; k++) {
    const mid = (lo + hi) / 2;
    if (erfc(mid / Math.SQRT2) > p) lo = mid;
    else hi = mid;
  }
  return (lo + hi) / 2;
}

function logChoose(n: number, k: number): number {
  let s = 0;
  for (let i = 1; i <= k; i++) s += Math.log((n - k + i) / i);
  return s;
}

/** Two-sided exact binomial p-value of k successes in n trials with success probability q. */
export function binomialTwoSidedP(k: number, n: number, q: number): number {
  if (q <= 0) return k === 0 ? 1 : 0;
  if (q >= 1) return k === n ? 1 : 0;
  const pmf = (i: number) => Math.exp(logChoose(n, i) + i * Math.log(q) + (n - i) * Math.log(1 - q));
  let lower = 0,
    upper = 0;
  for (let i = 0; i <= k; i++) lower += pmf(i);
  for (let i = k; i <= n; i++) upper += pmf(i);
  return Math.min(1, 2 * Math.min(lower, upper));
}

/** Signed z equivalent of an exact binomial test of a 0/1 estimator's mean (k = mean·n successes). */
export function binomialZ(mean: number, n: number, q: number): number {
  const k = Math.round(mean * n);
  const z = zOfTwoSidedP(binomialTwoSidedP(k, n, q));
  return k / n >= q ? z : -z;
}
