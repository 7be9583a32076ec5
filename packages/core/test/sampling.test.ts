import { describe, expect, it } from 'vitest';
import {
  buildEnvironmentSampling,
  directionToLatLong,
  environmentLookupCpu,
  latLongToDirection,
  sampleEnvironmentCpu,
  type LatLongEnvironment,
  type Vec3,
} from '../src/index.js';

/**
 * The Henyey–Greenstein sampling of shaders/sampling.glsl.ts (sampleHG / hgPhaseAB), transcribed
 * with an optional rounding function so float32 arithmetic can be emulated (Math.fround per op).
 */
function hgSample(g: number, xi: number, r: (x: number) => number = (x) => x) {
  const den = r(r(1 - g) + r(r(2 * g) * xi));
  const q = r(2 / r(den * den));
  const a = r(r(r(r(r(r(1 - g) * r(1 - g)) * r(1 - xi)) * r(1 + r(g * xi)))) * q);
  const b = r(r(r(r(r(1 + g) * r(1 + g)) * xi) * r(r(1 - g) + r(g * xi))) * q);
  return { a, b, cos: a < 1 ? r(1 - a) : r(b - 1) };
}
function hgPhaseAB(g: number, a: number, b: number) {
  const d = g >= 0 ? (1 - g) * (1 - g) + 2 * g * a : (1 + g) * (1 + g) - 2 * g * b;
  return ((1 - g) * (1 + g)) / (4 * Math.PI) / (d * Math.sqrt(d));
}
/** docs/design.md's HG, written as given. */
const hgDesign = (g: number, cos: number) => (1 - g * g) / (4 * Math.PI * Math.pow(1 + g * g - 2 * g * cos, 1.5));
/** Analytic CDF of cosθ under HG (integral of the docs/design.md density over the sphere, in closed form). */
const hgCdf = (g: number, mu: number) =>
  Math.abs(g) < 1e-12 ? (mu + 1) / 2 : ((1 - g * g) / (2 * g)) * (1 / Math.sqrt(1 + g * g - 2 * g * mu) - 1 / (1 + g));

describe('Henyey–Greenstein sampling (the kernels’ closed form)', () => {
  const gs = [-0.999, -0.9, -0.3, -1e-6, 0, 1e-6, 0.3, 0.9, 0.999];
  it('inverts the analytic CDF for every g, including 0 and |g| → 1', () => {
    for (const g of gs) {
      for (let k = 0; k <= 1000; k++) {
        const xi = k === 1000 ? 1 - 2 ** -24 : k / 1000;
        const s = hgSample(g, xi);
        expect(Math.abs(s.a + s.b - 2)).toBeLessThan(1e-12);
        expect(Math.abs(hgCdf(g, s.cos) - xi)).toBeLessThan(1e-9 + 1e-6 * Math.abs(g) ** 40);
      }
    }
  });
  it('evaluates the docs/design.md density, normalized over the sphere', () => {
    for (const g of gs) {
      for (const cos of [-1, -0.5, 0, 0.3, 0.99, 1]) {
        const ref = hgDesign(g, cos);
        expect(Math.abs(hgPhaseAB(g, 1 - cos, 1 + cos) - ref) / ref).toBeLessThan(1e-9);
      }
      // ∫ p dω = 2π ∫ p dμ = F(1) − F(−1) with the closed-form CDF.
      expect(Math.abs(hgCdf(g, 1) - hgCdf(g, -1) - 1)).toBeLessThan(1e-9);
    }
  });
  it('keeps 1 − cosθ accurate in float32 for g = 0.999, where the classic formula cancels', () => {
    const f = Math.fround;
    const g = f(0.999);
    let worstStable = 0,
      worstClassic = 0;
    for (let k = 1; k < 200; k++) {
      const xi = f(k / 200);
      const exact = hgSample(g, xi).a; // float64, same g and ξ
      const stable = hgSample(g, xi, f).a;
      const s = f(f(f(1 - f(g * g))) / f(f(1 - g) + f(f(2 * g) * xi)));
      const classicCos = f(f(f(1 + f(g * g)) - f(s * s)) / f(2 * g));
      worstStable = Math.max(worstStable, Math.abs(stable - exact) / exact);
      worstClassic = Math.max(worstClassic, Math.abs(f(1 - classicCos) - exact) / exact);
    }
    expect(worstStable).toBeLessThan(1e-5);
    expect(worstClassic).toBeGreaterThan(1e-3); // why the rearrangement exists
  });
});

describe('lat-long environment sampling (CPU twin of the kernels)', () => {
  const W = 16,
    H = 8;
  const data = new Float32Array(W * H * 3);
  for (let j = 0; j < H; j++)
    for (let i = 0; i < W; i++) {
      const k = 3 * (j * W + i);
      const v = 10 ** ((((i * 7 + j * 13) % 17) / 17) * 8 - 4); // 1e-4 … 1e4
      data[k] = v;
      data[k + 1] = 0.5 * v;
      data[k + 2] = i === 3 && j === 2 ? 0 : 0.25 * v;
    }
  data.fill(0, 3 * (5 * W), 3 * (6 * W)); // one black row: never sampled
  const env: LatLongEnvironment = { type: 'latlong', width: W, height: H, data, scale: 2 };
  const t = buildEnvironmentSampling(env);

  it('maps directions with Mitsuba 3’s convention: row 0 = +y, u = 0 along −z, u = ¼ along +x', () => {
    expect(directionToLatLong([0, 1, 0])[1]).toBe(0);
    expect(directionToLatLong([0, -1, 0])[1]).toBeCloseTo(1, 12);
    expect(directionToLatLong([0, 0, -1])).toEqual([0, 0.5]);
    expect(directionToLatLong([1, 0, 0])[0]).toBeCloseTo(0.25, 12);
    expect(directionToLatLong([0, 0, 1])[0]).toBeCloseTo(0.5, 12);
    expect(directionToLatLong([-1, 0, 0])[0]).toBeCloseTo(0.75, 12);
    for (const [u, v] of [
      [0.1, 0.2],
      [0.6, 0.9],
      [0.95, 0.5],
    ]) {
      const [u2, v2] = directionToLatLong(latLongToDirection(u, v));
      expect(u2).toBeCloseTo(u, 12);
      expect(v2).toBeCloseTo(v, 12);
    }
    // Radiance is the texel's, times the scale.
    const d = latLongToDirection((3 + 0.5) / W, (1 + 0.5) / H);
    expect(environmentLookupCpu(t, d).radiance[0]).toBeCloseTo(2 * data[3 * (1 * W + 3)], 5);
  });

  it('has a pdf that integrates to 1 over the sphere and matches the sampler at its samples', () => {
    // ∫ p(ω) dω over texels: p is constant in (u, v) per texel and dω = 2π² sinθ du dv.
    let integral = 0;
    const n = 64;
    for (let j = 0; j < H * n; j++)
      for (let i = 0; i < W * 4; i++) {
        const u = (i + 0.5) / (W * 4),
          v = (j + 0.5) / (H * n);
        integral +=
          (environmentLookupCpu(t, latLongToDirection(u, v)).pdf * 2 * Math.PI * Math.PI * Math.sin(Math.PI * v)) /
          (W * 4 * H * n);
      }
    expect(integral).toBeCloseTo(1, 3);
    for (let k = 1; k < 500; k++) {
      const s = sampleEnvironmentCpu(t, (k * 0.618034) % 1, (k * 0.7548777) % 1);
      const l = environmentLookupCpu(t, s.direction);
      expect(Math.abs(l.pdf - s.pdf) / s.pdf).toBeLessThan(1e-6);
      expect(l.radiance).toEqual(s.radiance);
    }
  });

  it('draws texels in proportion to luminance × sinθ (chi-square over 200k samples)', () => {
    const counts = new Float64Array(W * H);
    const N = 200000;
    let a = 12345;
    const rand = () => {
      a = (Math.imul(a, 1664525) + 1013904223) >>> 0;
      return (a >>> 8) / 16777216;
    };
    for (let k = 0; k < N; k++) {
      const s = sampleEnvironmentCpu(t, rand(), rand());
      counts[s.texel[1] * W + s.texel[0]]++;
    }
    let chi2 = 0,
      dof = 0;
    for (let j = 0; j < H; j++)
      for (let i = 0; i < W; i++) {
        const k = j * W + i;
        const r = t.map[4 * k],
          g = t.map[4 * k + 1],
          b = t.map[4 * k + 2];
        const w = (0.2126 * r + 0.7152 * g + 0.0722 * b) * Math.sin((Math.PI * (j + 0.5)) / H);
        let total = 0;
        for (let q = 0; q < W * H; q++) {
          const qj = Math.floor(q / W);
          total +=
            (0.2126 * t.map[4 * q] + 0.7152 * t.map[4 * q + 1] + 0.0722 * t.map[4 * q + 2]) *
            Math.sin((Math.PI * (qj + 0.5)) / H);
        }
        const expected = (N * w) / total;
        if (j === 5) expect(counts[k]).toBe(0);
        if (expected >= 5) {
          chi2 += (counts[k] - expected) ** 2 / expected;
          dof++;
        }
      }
    // chi-square with ~dof degrees of freedom: mean dof, sd sqrt(2 dof); 6 sd is far beyond chance.
    expect(dof).toBeGreaterThan(20);
    expect(chi2).toBeLessThan(dof + 6 * Math.sqrt(2 * dof));
  });

  it('falls back to uniform tables for a black environment', () => {
    const dark = buildEnvironmentSampling({ type: 'latlong', width: 4, height: 2, data: new Float32Array(24) });
    expect(dark.marginal[2]).toBe(1);
    expect(Array.from(dark.map.filter((_, i) => i % 4 === 3))).toEqual(new Array(8).fill(1));
    const s = sampleEnvironmentCpu(dark, 0.3, 0.9);
    expect(Number.isFinite(s.pdf) && s.pdf > 0).toBe(true);
    const v: Vec3 = s.direction;
    expect(Math.hypot(...v)).toBeCloseTo(1, 12);
  });
});
