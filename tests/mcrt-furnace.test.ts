import { describe, expect, it } from 'vitest';
import { zSummary } from './helpers/mcrt-stats.js';
import { BACKENDS, usePage } from './helpers/session.js';

/**
 * White furnace: a non-absorbing medium (albedo 1) under a constant environment of radiance 1,
 * multiple scattering with unlimited depth, must look exactly like the environment: every
 * pixel 1, whatever the density and the phase function. The camera sees only the cube's face.
 */
const page = usePage({ mcrt: true });

const DENSITIES = [0.01, 10, 100, 1000];
const GS = [-0.99, 0, 0.99];
const W = 8,
  H = 8;

describe.each(BACKENDS)('MCRT white furnace on %s', (backend) => {
  // Phase sampling only: every path carries throughput 1 until it escapes to radiance 1, so
  // each sample is exactly 1 and the only admissible error is float rounding (none, in fact).
  it('phase sampling: every pixel is 1 (to 1e-6) for density 0.01–1000 and g = −0.99, 0, 0.99', async () => {
    const results = await page.run(
      async ({ t, mt }, backend, W, H, densities, gs) => {
        const ctx = await t.context({
          backend,
          renderer: 'mcrt',
          width: W,
          height: H,
          params: { environmentSampling: 'phase', maxDepth: -1 },
        });
        const out = [];
        try {
          for (const density of densities)
            for (const g of gs) {
              const r = await mt.measure(ctx, {
                iterations: 6,
                frames: false,
                params: { anisotropy: g },
                scene: mt.cubeScene({ albedo: [1, 1, 1], density }),
              });
              out.push({ density, g, hdr: r.hdr, nonFinite: r.nonFinite });
            }
        } finally {
          ctx.dispose();
        }
        return out;
      },
      backend,
      W,
      H,
      DENSITIES,
      GS,
    );
    expect(results.length).toBe(12);
    for (const r of results) {
      let worst = 0;
      for (let i = 0; i < r.hdr.length; i += 4)
        for (let c = 0; c < 3; c++) worst = Math.max(worst, Math.abs(r.hdr[i + c] - 1));
      const msg = `density ${r.density} g ${r.g}: max |pixel - 1| = ${worst}`;
      expect(r.nonFinite, msg).toBe(false);
      expect(worst, msg).toBeLessThanOrEqual(1e-6);
    }
  });
});

describe('MCRT white furnace with next-event estimation and MIS (webgl2)', () => {
  // With light sampling combined by MIS the samples scatter around 1; each pixel's mean over
  // N frames must be within 5 standard errors (measured from the same frames, floored by the
  // image's median) of 1, and the image-wide mean within 4 of its standard error. 64 pixels × 12 cases: a 5σ excursion by
  // chance has probability < 1e-3 over the whole set (t-distribution with N − 1 = 47 dof).
  it.each(DENSITIES)(
    'every pixel is 1 within its Monte Carlo error at density %s, g = −0.99, 0, 0.99',
    async (density) => {
      const N = 48;
      const runs = await page.run(
        async ({ t, mt }, W, H, density, gs, N) => {
          const ctx = await t.context({
            backend: 'webgl2',
            renderer: 'mcrt',
            width: W,
            height: H,
            // The fixed estimator (MIS, residual tracking), whose noise gives the z-test power;
            // 'auto' samples this constant sky by the phase function alone (exactly 1, tested above).
            params: { maxDepth: -1, estimator: 'fixed' },
          });
          const out = [];
          try {
            for (const g of gs)
              out.push({
                g,
                ...(await mt.measure(ctx, {
                  iterations: N,
                  params: { anisotropy: g },
                  scene: mt.cubeScene({ albedo: [1, 1, 1], density, seed: 3 }),
                })),
              });
          } finally {
            ctx.dispose();
          }
          return out;
        },
        W,
        H,
        density,
        GS,
        N,
      );
      for (const r of runs) {
        const g = r.g;
        expect(r.nonFinite).toBe(false);
        // Rare large samples (|g| near 1) make a pixel's own variance estimate from 48 frames
        // unreliable when they happen not to occur; every pixel sees the same face of the same
        // medium, so the median standard error over the image floors each pixel's.
        const ses = (r.se as number[]).filter((_, i) => i % 4 !== 3).sort((a, b) => a - b);
        const pooled = ses[ses.length >> 1];
        const z: number[] = [];
        let sum = 0,
          var_ = 0,
          spread = 0;
        for (let i = 0; i < r.mean.length; i += 4) {
          for (let c = 0; c < 3; c++) {
            const se = Math.max(r.se[i + c], pooled);
            z.push(se > 0 ? (r.mean[i + c] - 1) / se : r.mean[i + c] === 1 ? 0 : Infinity);
            spread = Math.max(spread, se);
          }
          sum += r.mean[i];
          var_ += r.se[i] ** 2;
        }
        const s = zSummary(z, 3);
        const imageMean = sum / (W * H),
          imageSe = Math.sqrt(var_) / (W * H);
        const msg = `density ${density} g ${g}: max |z| ${s.maxAbs.toFixed(2)}, image mean ${imageMean.toFixed(5)} ± ${imageSe.toExponential(2)}`;
        expect(s.maxAbs, msg).toBeLessThan(5);
        expect(Math.abs(imageMean - 1), msg).toBeLessThan(4 * imageSe + 1e-6);
        // The estimator really is noisy here (so the z-test has power), unlike phase sampling alone.
        expect(spread, msg).toBeGreaterThan(0);
      }
    },
  );
});
