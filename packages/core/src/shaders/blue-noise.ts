/**
 * Blue-noise sampling of a path's first dimensions (the `sampler: 'blue-noise'` renderer
 * parameter; shader chunk SAMPLE_DIMS of blue-noise.glsl.ts / .wgsl.ts). This is the subpath
 * `@vpt/core/blue-noise`, not reached from core's index: the renderers import it, so in the
 * viewer's bundle it rides in their lazy chunks and the entry carries only sampler-param.ts.
 *
 * The mask is a 64 × 64 tiling blue-noise dither array made by void-and-cluster (Ulichney 1993,
 * "The void-and-cluster method for dither array generation", Proc. SPIE 1913), built here at
 * run time, deterministically (no data shipped): a toroidal Gaussian energy (σ = 1.5), an
 * initial pattern of PCG-hashed points relaxed by swapping its tightest cluster into its
 * largest void, then ranks by removing clusters (phase 1) and filling voids (phases 2 and 3:
 * the zeros' energy is the constant kernel sum minus the ones', so the largest void of the
 * ones is the tightest cluster of the zeros). Its texels hold the ranks 0…4095, each once.
 *
 * A kernel's dimension d at pixel p of sample i (u.iteration + u.sampleBase) is x = frac(m(p + o_d) + i·α_d + U_d), in
 * 32-bit fixed point: the rank-1 sequence i·α (Roberts 2018, "The unreasonable effectiveness
 * of quasirandom sequences": R2 for the jitter, the golden ratio, Richtmyer's √2, √3 for the light sample) Cranley–Patterson
 * rotated per pixel by the blue-noise mask (Georgiev & Fajardo 2016, "Blue-noise dithered
 * sampling"; the golden-ratio animated mask Wolfe et al. 2022 compare against), with a
 * uniform shift U_d and a toroidal mask offset o_d hashed from (seed, d). Over the seed's U_d
 * each x is exactly uniform and the dimensions are independent, so every estimator stays
 * unbiased; per seed the mean over iterations converges as a low-discrepancy sequence.
 */
import type { AuxiliaryTexture } from '../renderer.js';
import { pcgHash } from '../reference/cpu-reference.js';

export { SAMPLER_PARAM, samplerParam, type Sampler } from './sampler-param.js';
export { SAMPLE_DIMS as GLSL_SAMPLE_DIMS } from './blue-noise.glsl.js';
export { SAMPLE_DIMS as WGSL_SAMPLE_DIMS } from './blue-noise.wgsl.js';

/** The mask's side in pixels (a power of two: kernels wrap with `& (size − 1)`). */
export const BLUE_NOISE_SIZE = 64;

/**
 * The dimensions that blue noise serves (the kernels' `rngDim(rng, d)`); every other draw is
 * the PCG stream. 0, 1: the pixel jitter (R2 pair); 2: the march's offset (EAM, MIP, ISO) or
 * the camera ray's first free flight (MCRT); 3, 4: the first light sample (R2 pair).
 */
export const SAMPLE_DIM = { jitterX: 0, jitterY: 1, offset: 2, lightU: 3, lightV: 4 } as const;

/**
 * α_d of each dimension as 0.32 fixed point: R2's (1/φ₂, 1/φ₂²) for the jitter, 1/φ for dimension
 * 2, frac(√2), frac(√3) (Richtmyer's square roots of primes) for the light sample. The five and 1
 * are linearly independent over the rationals, so at each pixel the 5D Kronecker sequence is
 * equidistributed; reusing R2 for the second pair made dimension 3 a constant shift of dimension
 * 0 at every pixel, a per-seed error that did not average out over iterations (ISO lost 3.6 dB
 * at 512 iterations on the anchor scene).
 */
export const SAMPLE_DIM_ALPHA: readonly number[] = [3242174889, 2447445413, 2654435769, 1779033704, 3144134278];

let memo: Float32Array | undefined;

/** The 64 × 64 void-and-cluster rank mask, row-major (x fastest); memoised. */
export function blueNoiseMask(): Float32Array {
  memo ??= voidAndCluster(BLUE_NOISE_SIZE, 1.5);
  return memo;
}

/** Void-and-cluster ranks of an n × n torus (Ulichney 1993), deterministic. */
export function voidAndCluster(n: number, sigma: number): Float32Array {
  const count = n * n;
  // Toroidal Gaussian kernel by offset (dx, dy), each in [0, n).
  const kernel = new Float64Array(count);
  for (let dy = 0; dy < n; dy++) {
    for (let dx = 0; dx < n; dx++) {
      const x = Math.min(dx, n - dx);
      const y = Math.min(dy, n - dy);
      kernel[dy * n + dx] = Math.exp(-(x * x + y * y) / (2 * sigma * sigma));
    }
  }
  const energy = new Float64Array(count);
  const on = new Uint8Array(count);
  const splat = (p: number, sign: number): void => {
    const px = p % n;
    const py = (p - px) / n;
    for (let y = 0; y < n; y++) {
      const ky = ((y - py + n) % n) * n;
      const row = y * n;
      for (let x = 0; x < n; x++) energy[row + x] += sign * kernel[ky + ((x - px + n) % n)];
    }
  };
  // The tightest cluster (max energy among ones) or the largest void (min energy among zeros).
  const extreme = (ones: boolean): number => {
    let best = -1;
    let value = ones ? -Infinity : Infinity;
    for (let p = 0; p < count; p++) {
      if ((on[p] === 1) !== ones) continue;
      const e = energy[p];
      if (ones ? e > value : e < value) {
        value = e;
        best = p;
      }
    }
    return best;
  };
  // Initial pattern: ~10% of the pixels, PCG-hashed, then relaxed.
  const initial = Math.max(1, Math.floor(count / 10));
  let placed = 0;
  for (let k = 0; placed < initial; k++) {
    const p = pcgHash(k ^ 0x5bd1e995) % count;
    if (on[p]) continue;
    on[p] = 1;
    splat(p, 1);
    placed++;
  }
  for (let guard = 0; guard < count; guard++) {
    const c = extreme(true);
    on[c] = 0;
    splat(c, -1);
    const v = extreme(false);
    on[v] = 1;
    splat(v, 1);
    if (v === c) break;
  }
  const rank = new Float32Array(count);
  const startOn = on.slice();
  const startEnergy = energy.slice();
  // Phase 1: ranks initial−1 … 0 by removing the tightest cluster.
  for (let r = initial - 1; r >= 0; r--) {
    const c = extreme(true);
    on[c] = 0;
    splat(c, -1);
    rank[c] = r;
  }
  on.set(startOn);
  energy.set(startEnergy);
  // Phases 2 and 3: ranks initial … count−1 by filling the largest void.
  for (let r = initial; r < count; r++) {
    const v = extreme(false);
    on[v] = 1;
    splat(v, 1);
    rank[v] = r;
  }
  return rank;
}

/** The mask as the auxiliary texture `blueNoise` (r32float ranks) that SAMPLE_DIMS reads under BLUE_NOISE. */
export function blueNoiseTexture(): AuxiliaryTexture {
  return {
    name: 'blueNoise',
    dimension: '2d',
    key: `void-and-cluster-${BLUE_NOISE_SIZE}`,
    create: () => ({
      dimension: '2d',
      width: BLUE_NOISE_SIZE,
      height: BLUE_NOISE_SIZE,
      format: 'r32float',
      data: blueNoiseMask(),
      label: 'blue-noise mask',
    }),
  };
}

/**
 * CPU twin of the kernels' blueNoiseDim (same u32 arithmetic): dimension `dim` at `pixel` of
 * iteration `iteration` with seed `seed`, in [0, 1).
 */
export function blueNoiseDim(px: number, py: number, iteration: number, seed: number, dim: number): number {
  const h = pcgHash((seed + pcgHash((dim + 0x9e3779b9) >>> 0)) >>> 0);
  const mask = blueNoiseMask();
  const qx = (px + (h & 63)) & (BLUE_NOISE_SIZE - 1);
  const qy = (py + ((h >>> 6) & 63)) & (BLUE_NOISE_SIZE - 1);
  const r = mask[qy * BLUE_NOISE_SIZE + qx];
  const x = ((r << 20) + (1 << 19) + Math.imul(iteration, SAMPLE_DIM_ALPHA[dim]) + pcgHash(h)) >>> 0;
  return (x >>> 8) * (1 / 16777216);
}
