import { describe, expect, it } from 'vitest';
import { createProceduralVolume, type Scene, type Vec3 } from '../packages/core/src/index.js';
import { pixelExpectations, singleScatteringRadiance } from './helpers/mcrt-reference.js';
import { zSummary } from './helpers/mcrt-stats.js';
import { usePage } from './helpers/session.js';

/**
 * Single scattering of a homogeneous cube under one directional light, black environment:
 * L = ∫ e^{−σ(t−t0)} σ·albedo·p_HG(l·d)·E·e^{−σ d_l(x)} dt, computed on the CPU by quadrature
 * (tests/helpers/mcrt-reference.ts). The light sits behind the camera's right shoulder, so
 * the scattering angle is large: g = +0.6 and g = −0.6 give very different images, and a
 * flipped phase-function convention would fail. Each shadow-ray estimator is checked.
 * Tolerance: standard errors from the frames (aggregate |Σz|/√n < 3, max |z| < 5).
 */
const page = usePage({ mcrt: true });

const W = 16,
  H = 16,
  N = 64;
const sigma = 2.5;
const albedo: Vec3 = [0.9, 0.6, 0.3];
const light = { direction: [0.5, 0.6, 1.0] as Vec3, irradiance: [3, 3, 3] as Vec3 };
const camera = { position: [0.5, 0.3, 2.4] as Vec3, target: [0, 0, 0] as Vec3, up: [0, 1, 0] as Vec3, fovy: 0.6 };

describe('MCRT single scattering vs CPU quadrature (webgl2)', () => {
  const cases = [
    [0.6, 'residual', 1],
    [-0.6, 'residual', 1],
    [-0.6, 'ratio', 1],
    [-0.6, 'delta', 1],
    [-0.6, 'residual', 3],
  ] as const;
  it.each(cases)('g = %s, %s tracking, %s light samples', async (g, tracking, lightSamples) => {
    const gpu = await page.run(
      ({ mt }, W, H, N, sigma, albedo, light, camera, g, tracking, lightSamples) => {
        return mt.run({
          backend: 'webgl2',
          width: W,
          height: H,
          iterations: N,
          params: { scattering: 'single', anisotropy: g, tracking, lightSamples },
          scene: mt.cubeScene({
            albedo,
            density: sigma,
            camera,
            environment: { type: 'constant', radiance: [0, 0, 0] },
            lights: [{ type: 'directional', ...light }],
          }),
        });
      },
      W,
      H,
      N,
      sigma,
      albedo,
      light,
      camera,
      g,
      tracking,
      lightSamples,
    );
    expect(gpu.nonFinite).toBe(false);
    const scene = { volume: createProceduralVolume('cube', 8), camera } as Scene;
    const ref = pixelExpectations(scene, W, H, singleScatteringRadiance(scene, sigma, albedo, g, light));
    const z: number[] = [];
    let interior = 0,
      refSum = 0;
    ref.forEach((p, k) => {
      if (p.miss) for (let c = 0; c < 3; c++) expect(gpu.mean[4 * k + c]).toBe(0);
      if (!p.interior) return;
      interior++;
      refSum += p.value[0];
      // 1e-3 relative: float32 and the footprint/line quadratures.
      for (let c = 0; c < 3; c++)
        z.push((gpu.mean[4 * k + c] - p.value[c]) / Math.hypot(gpu.se[4 * k + c], 1e-3 * p.value[c]));
    });
    const s = zSummary(z, 3);
    const msg = `g ${g} ${tracking}: ${JSON.stringify(s)}`;
    expect(interior).toBeGreaterThan(80);
    expect(Math.abs(s.meanScaled), msg).toBeLessThan(3);
    expect(s.maxAbs, msg).toBeLessThan(5);
    expect(refSum).toBeGreaterThan(0);
  });
  it('the sign of g matters here (back-scattering toward the camera), so the cases above tell the conventions apart', () => {
    // Computed here from the CPU expectation, independent of the other tests' order or outcome.
    const scene = { volume: createProceduralVolume('cube', 8), camera } as Scene;
    const meanOf = (g: number) => {
      const ref = pixelExpectations(
        scene,
        W,
        H,
        singleScatteringRadiance(scene, sigma, albedo, g, light, 100),
        4,
      ).filter((p) => p.interior);
      return ref.reduce((a, p) => a + p.value[0], 0) / ref.length;
    };
    expect(meanOf(-0.6) / meanOf(0.6)).toBeGreaterThan(3);
  });
});
