import { describe, expect, it } from 'vitest';
import { createProceduralVolume, type Scene, type Vec3 } from '../packages/core/src/index.js';
import { extinctionCap } from '../packages/renderer-mcrt/src/index.js';
import { pixelExpectations } from './helpers/mcrt-reference.js';
import { BACKENDS, usePage } from './helpers/session.js';

/**
 * A very dense medium is a surface in the limit (docs/architecture.md, "MCRT renderer": the
 * extinction cap). A sphere of albedo 0.8 at densityScale 1e8, the largest accepted, lit by a
 * headlight under a black sky, must show the diffuse reflectance of a semi-infinite isotropic
 * medium, Chandrasekhar's I(μ, μ0) = ϖE/(4π) · μ0/(μ + μ0) · H(μ)H(μ0) (Radiative Transfer,
 * 1960, ch. IV eq. 30, with πF = E): that holds for any depth profile of σ_t at a constant
 * albedo, since a plane-parallel medium depends only on optical depth. And the walk must cost
 * no more at 1e8 than at the cap itself: the tracking steps per path are counted by the
 * `fetches` debug output.
 */
const page = usePage({ mcrt: true });

const ALBEDO = 0.8;
const SIZE = 24;
const ITERATIONS = 32;

/** Chandrasekhar's H-function for isotropic scattering, by iterating its integral equation on Gauss–Legendre nodes. */
function chandrasekharH(albedo: number): (mu: number) => number {
  const N = 64;
  // Gauss–Legendre nodes on [0, 1] (Newton on P_N).
  const x: number[] = [],
    w: number[] = [];
  for (let i = 1; i <= N; i++) {
    let z = Math.cos((Math.PI * (i - 0.25)) / (N + 0.5));
    let dp = 0;
    for (let it = 0; it < 100; it++) {
      let p0 = 1,
        p1 = z;
      for (let k = 2; k <= N; k++) [p0, p1] = [p1, ((2 * k - 1) * z * p1 - (k - 1) * p0) / k];
      dp = (N * (z * p1 - p0)) / (z * z - 1);
      const dz = p1 / dp;
      z -= dz;
      if (Math.abs(dz) < 1e-15) break;
    }
    x.push((1 - z) / 2);
    w.push(1 / ((1 - z * z) * dp * dp));
  }
  let H = x.map(() => 1);
  const step = (mu: number, h: number[]) =>
    1 / (1 - (albedo / 2) * mu * h.reduce((s, hk, k) => s + (w[k] * hk) / (mu + x[k]), 0));
  for (let it = 0; it < 500; it++) H = x.map((mu) => step(mu, H));
  return (mu: number) => step(mu, H);
}

function denseSphere(density: number): Scene {
  return {
    volume: createProceduralVolume('sphere', 32),
    transferFunction: {
      dimensions: '1d',
      points: [
        { value: 0, color: [ALBEDO, ALBEDO, ALBEDO], opacity: 0 },
        { value: 1, color: [ALBEDO, ALBEDO, ALBEDO], opacity: 1 },
      ],
    },
    camera: { position: [0, 0, 2], target: [0, 0, 0], up: [0, 1, 0], fovy: 0.5 },
    lights: [{ type: 'directional', direction: [0, 0, 1], irradiance: [1, 1, 1] }],
    environment: { type: 'constant', radiance: [0, 0, 0] },
    densityScale: density,
    seed: 7,
  } as Scene;
}

describe('Chandrasekhar H-function (the reference)', () => {
  it('meets its moment identity ∫H dμ = 2(1 − √(1 − ϖ))/ϖ', () => {
    for (const a of [0.5, 0.8, 0.99]) {
      const H = chandrasekharH(a);
      let m = 0;
      const n = 4000;
      for (let i = 0; i < n; i++) m += H((i + 0.5) / n) / n;
      expect(m).toBeCloseTo((2 * (1 - Math.sqrt(1 - a))) / a, 3);
    }
  });
});

describe.each(BACKENDS)('MCRT dense media on %s', (backend) => {
  it('a sphere at densityScale 1e8 shows the diffuse reflectance of a semi-infinite medium', async () => {
    const r = await page.run(
      async ({ mt, core }, backend, scene, n, size) =>
        mt.run({
          backend,
          width: size,
          height: size,
          scene: { ...scene, volume: core.createProceduralVolume('sphere', 32) },
          iterations: n,
          params: { anisotropy: 0 },
        }),
      backend,
      { ...denseSphere(1e8), volume: null },
      ITERATIONS,
      SIZE,
    );
    expect(r.nonFinite).toBe(false);
    // The surface: the sphere's trilinear edge ends within a voxel beyond 0.35 + 0.5/32 (createProceduralVolume).
    const R = 0.37;
    const H = chandrasekharH(ALBEDO);
    const scene = denseSphere(1e8);
    // Channel 0: the expected radiance; channel 1: 1 where the ray sees the sphere within 53° of its normal.
    const expected = pixelExpectations(scene, SIZE, SIZE, (o, d) => {
      const b = o[0] * d[0] + o[1] * d[1] + o[2] * d[2];
      const c = o[0] * o[0] + o[1] * o[1] + o[2] * o[2] - R * R;
      const disc = b * b - c;
      if (disc < 0) return [0, 0, 0];
      const t = -b - Math.sqrt(disc);
      const n: Vec3 = [(o[0] + t * d[0]) / R, (o[1] + t * d[1]) / R, (o[2] + t * d[2]) / R];
      const mu = -(n[0] * d[0] + n[1] * d[1] + n[2] * d[2]);
      const mu0 = n[2]; // the light's direction is +z
      const I = ((ALBEDO / (4 * Math.PI)) * mu0 * H(mu) * H(mu0)) / (mu + mu0);
      return [I, mu >= 0.6 ? 1 : 0, 0];
    });
    // The lit side away from the voxelised limb: pixels whose whole footprint qualifies.
    let sumR = 0,
      sumE = 0,
      var_ = 0,
      count = 0;
    for (let p = 0; p < SIZE * SIZE; p++) {
      if (expected[p].value[1] < 1) continue;
      sumR += r.mean![4 * p];
      sumE += expected[p].value[0];
      var_ += r.se![4 * p] ** 2;
      count++;
    }
    expect(count).toBeGreaterThan(80);
    const meanR = sumR / count,
      meanE = sumE / count,
      se = Math.sqrt(var_) / count;
    console.log(
      `dense sphere ${backend}: ${count} px, render ${meanR.toFixed(4)} ± ${se.toFixed(4)}, Chandrasekhar ${meanE.toFixed(4)}`,
    );
    expect(meanE).toBeGreaterThan(0.05);
    expect(Math.abs(meanR - meanE)).toBeLessThan(0.04 * meanE + 4 * se);
  }, 240_000);

  it('costs no more tracking steps per path at densityScale 1e8 than at the extinction cap', async () => {
    const cap = extinctionCap(denseSphere(1));
    const r = await page.run(
      async ({ t, core }, backend, scenes, size) => {
        const ctx = await t.context({
          backend,
          renderer: 'mcrt',
          width: size,
          height: size,
          params: { debugOutput: 'fetches', anisotropy: 0 },
        });
        const out = [];
        try {
          for (const scene of scenes) {
            ctx.setScene({ ...scene, volume: core.createProceduralVolume('sphere', 32) });
            ctx.reset();
            ctx.iterate(1);
            const f = await ctx.readFrame();
            let max = 0,
              sum = 0;
            for (let i = 0; i < f.length; i += 4) {
              max = Math.max(max, f[i]);
              sum += f[i];
            }
            out.push({ max, mean: sum / (f.length / 4) });
          }
        } finally {
          ctx.dispose();
        }
        return out;
      },
      backend,
      [denseSphere(cap), denseSphere(1e8)].map((s) => ({ ...s, volume: null })),
      SIZE,
    );
    const [atCap, dense] = r;
    console.log(`lookups per path ${backend}: at the cap ${JSON.stringify(atCap)}, at 1e8 ${JSON.stringify(dense)}`);
    expect(atCap.mean).toBeGreaterThan(0);
    // Beyond the cap the medium is the same surface: the walk does not grow with density.
    expect(dense.mean).toBeLessThan(1.25 * atCap.mean);
    // Far below the 2^20 tracking steps at which a path is ended as absorbed.
    expect(dense.max).toBeLessThan(1 << 16);
  }, 240_000);
});
