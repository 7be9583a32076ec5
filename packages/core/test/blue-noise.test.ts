import { describe, expect, it } from 'vitest';
import {
  BLUE_NOISE_SIZE,
  blueNoiseDim,
  blueNoiseMask,
  SAMPLE_DIM_ALPHA,
  voidAndCluster,
} from '../src/shaders/blue-noise.js';
import { pcgHash } from '../src/reference/cpu-reference.js';
import fs from 'node:fs';
import path from 'node:path';
import { fileURLToPath } from 'node:url';

const N = BLUE_NOISE_SIZE;

/** Mean power of the mask's 2D DFT (values centred, unit variance) at radial frequencies 0 < |f| <= fmax cycles per tile. */
function lowFrequencyPower(mask: ArrayLike<number>, n: number, fmax: number): number {
  let mean = 0;
  for (let i = 0; i < n * n; i++) mean += mask[i];
  mean /= n * n;
  let variance = 0;
  for (let i = 0; i < n * n; i++) variance += (mask[i] - mean) ** 2;
  variance /= n * n;
  let sum = 0;
  let count = 0;
  for (let fy = -fmax; fy <= fmax; fy++)
    for (let fx = -fmax; fx <= fmax; fx++) {
      const r2 = fx * fx + fy * fy;
      if (r2 === 0 || r2 > fmax * fmax) continue;
      let re = 0;
      let im = 0;
      for (let y = 0; y < n; y++)
        for (let x = 0; x < n; x++) {
          const a = (-2 * Math.PI * (fx * x + fy * y)) / n;
          const v = mask[y * n + x] - mean;
          re += v * Math.cos(a);
          im += v * Math.sin(a);
        }
      // For white noise E|F|² = n² · variance, so this ratio is ~1.
      sum += (re * re + im * im) / (n * n * variance);
      count++;
    }
  return sum / count;
}

describe('blue-noise mask (void-and-cluster)', () => {
  const mask = blueNoiseMask();

  it('holds every rank 0 … 4095 exactly once (a flat histogram of its values)', () => {
    expect(mask.length).toBe(N * N);
    const seen = new Uint8Array(N * N);
    for (const r of mask) {
      expect(Number.isInteger(r) && r >= 0 && r < N * N).toBe(true);
      seen[r]++;
    }
    expect(seen.every((c) => c === 1)).toBe(true);
    // 16 bins of the normalized value: 256 each.
    const bins = new Array(16).fill(0);
    for (const r of mask) bins[Math.floor((r / (N * N)) * 16)]++;
    expect(bins).toEqual(new Array(16).fill(256));
  });

  it('has little power at low frequencies, where a white-noise permutation has as much as anywhere', () => {
    const blue = lowFrequencyPower(mask, N, 6);
    // White noise: the same ranks in a PCG-hashed order (Fisher–Yates).
    const white = Float32Array.from({ length: N * N }, (_, i) => i);
    for (let i = white.length - 1; i > 0; i--) {
      const j = pcgHash(i * 2654435761) % (i + 1);
      [white[i], white[j]] = [white[j], white[i]];
    }
    const whitePower = lowFrequencyPower(white, N, 6);
    expect(whitePower).toBeGreaterThan(0.6);
    expect(blue).toBeLessThan(0.1);
  });

  it('is deterministic', () => {
    expect(voidAndCluster(16, 1.5)).toEqual(voidAndCluster(16, 1.5));
  });
});

describe('blueNoiseDim (CPU twin of the kernels)', () => {
  it('is uniform over pixels at one iteration', () => {
    for (let dim = 0; dim < SAMPLE_DIM_ALPHA.length; dim++) {
      const bins = new Array(16).fill(0);
      for (let y = 0; y < N; y++) for (let x = 0; x < N; x++) bins[Math.floor(blueNoiseDim(x, y, 5, 3, dim) * 16)]++;
      // A rotated permutation of the ranks: every bin holds 256 ± 1.
      for (const b of bins) expect(Math.abs(b - 256)).toBeLessThanOrEqual(1);
    }
  });

  it('is low-discrepancy over iterations at one pixel, per pair in 2D and per dimension in 1D', () => {
    // 64 iterations into 16 cells (4 × 4 for a pair, 16 bins for dimension 2): 4 per cell. Over
    // 40 (pixel, seed) cases the mean sum of |count − 4| is ~25 for independent uniform draws.
    for (const [a, b] of [
      [0, 1],
      [3, 4],
      [2, 2],
      [3, 3],
      [4, 4],
    ]) {
      let sum = 0;
      for (let px = 0; px < 64; px += 7)
        for (let seed = 0; seed < 4; seed++) {
          const t = new Array(16).fill(0);
          for (let i = 0; i < 64; i++) {
            const x = blueNoiseDim(px, 11, i, seed, a);
            const y = blueNoiseDim(px, 11, i, seed, b);
            t[a === b ? Math.floor(x * 16) : Math.floor(x * 4) * 4 + Math.floor(y * 4)]++;
          }
          // R2 (0, 1) keeps every cell within ±2; the square roots' pair (3, 4) within ±3.
          const bound = a === 3 && b === 4 ? 3 : 2;
          for (const c of t) expect(Math.abs(c - 4), `dims ${a}, ${b}: ${t.join(' ')}`).toBeLessThanOrEqual(bound);
          sum += t.reduce((acc, c) => acc + Math.abs(c - 4), 0);
        }
      expect(sum / 40, `dims ${a}, ${b}`).toBeLessThan(14);
    }
  });

  it('has no two dimensions locked together at a pixel (their difference spreads over iterations)', () => {
    // With a shared α two dimensions differ by a constant at every iteration: a per-seed error
    // that never averages out. Every pair's difference must fill at least 12 of 16 bins in 64 iterations.
    for (let a = 0; a < SAMPLE_DIM_ALPHA.length; a++)
      for (let b = a + 1; b < SAMPLE_DIM_ALPHA.length; b++) {
        const bins = new Set<number>();
        for (let i = 0; i < 64; i++) {
          const d = (blueNoiseDim(5, 9, i, 3, b) - blueNoiseDim(5, 9, i, 3, a) + 1) % 1;
          bins.add(Math.floor(d * 16));
        }
        expect(bins.size, `dims ${a}, ${b}`).toBeGreaterThanOrEqual(12);
      }
  });

  it('is uniform over seeds, independently per dimension (the estimator is unbiased over the seed)', () => {
    const K = 4096;
    const bins = new Array(16).fill(0);
    let corr = 0;
    for (let s = 0; s < K; s++) {
      const a = blueNoiseDim(3, 9, 17, s, 0);
      const b = blueNoiseDim(3, 9, 17, s, 2);
      bins[Math.floor(a * 16)]++;
      corr += (a - 0.5) * (b - 0.5);
    }
    // Chi-squared with 15 degrees of freedom: 37.7 is its 0.1% tail.
    const chi2 = bins.reduce((acc, b) => acc + (b - K / 16) ** 2 / (K / 16), 0);
    expect(chi2).toBeLessThan(37.7);
    // Correlation of two dimensions: sd 1/√K of the normalized product; 4σ.
    expect(Math.abs((corr / K) * 12)).toBeLessThan(4 / Math.sqrt(K));
  });
});

describe('the renderer-only subpaths (@vpt/core/blue-noise, @vpt/core/sampling)', () => {
  const SRC = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '../src');
  /** Source files reached from `file` by static imports (dynamic import() not followed). */
  function staticGraph(file: string, seen = new Set<string>()): Set<string> {
    if (seen.has(file)) return seen;
    seen.add(file);
    const text = fs.readFileSync(file, 'utf8');
    for (const m of text.matchAll(
      /(?:^|[;\s}])(?:import|export)\s+(?!type\b)(?:[\w*{}\s,$]+\s*from\s*)?['"](\.[^'"]+)['"]/g,
    )) {
      const target = path.resolve(path.dirname(file), m[1]!.replace(/\.js$/, '.ts'));
      if (fs.existsSync(target)) staticGraph(target, seen);
    }
    return seen;
  }

  it("is not reached from core's index by static imports (so the viewer's entry does not carry it)", () => {
    const graph = [...staticGraph(path.join(SRC, 'index.ts'))].map((f) => path.relative(SRC, f));
    // The walk does reach the parameter's choices and the shared shader chunks.
    expect(graph).toContain(path.join('shaders', 'sampler-param.ts'));
    expect(graph).toContain(path.join('shaders', 'common.glsl.ts'));
    // Neither are the sampling chunks (@vpt/core/sampling), which only ISO's and MCRT's kernels include.
    for (const lazy of [
      'blue-noise.ts',
      'blue-noise.glsl.ts',
      'blue-noise.wgsl.ts',
      'sampling.glsl.ts',
      'sampling.wgsl.ts',
    ])
      expect(graph).not.toContain(path.join('shaders', lazy));
  });
});
