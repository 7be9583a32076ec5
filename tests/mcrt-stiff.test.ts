import { beforeAll, describe, expect, it } from 'vitest';
import { buildEnvironmentSampling, environmentLookupCpu, reference, type Scene, type Vec3 } from '../packages/core/src/index.js';
import { installMcrtHelpers } from './helpers/mcrt-in-page.js';
import { BACKENDS, usePage } from './helpers/session.js';

/**
 * Stiff and extreme cases (docs/design.md, "Numbers that matter"): very thin and very dense media,
 * |g| = 0.999, albedo 0 and 1, an HDR environment spanning 1e-4 … 1e4, and a long
 * accumulation. No NaN or Inf may reach a frame or an accumulation, and where an answer is
 * known the image must show it.
 */
const page = usePage();
beforeAll(async () => { await installMcrtHelpers(page().page); });

describe.each(BACKENDS)('MCRT stiff media on %s', (backend) => {
  it('densities 1e-3 and 1e4, albedo 0 and 1, g = ±0.999: finite, and the known answers', async () => {
    const results = await page().page.evaluate(async (backend) => {
      const mt = (window as any).mt;
      const out = [];
      for (const environmentSampling of ['mis', 'phase']) {
        const ctx = await (window as any).t.context({ backend, renderer: 'mcrt', width: 4, height: 4, params: { environmentSampling } });
        try {
          for (const density of [1e-3, 1e4]) for (const albedo of [0, 1]) for (const g of [-0.999, 0.999]) {
            const r = await mt.measure(ctx, { iterations: 6, params: { anisotropy: g }, scene: mt.cubeScene({ albedo: [albedo, albedo, albedo], density }) });
            out.push({ density, albedo, g, environmentSampling, mean: r.mean, nonFinite: r.nonFinite, rmse: r.err.rmse });
          }
        } finally { ctx.dispose(); }
      }
      return out;
    }, backend);
    expect(results.length).toBe(16);
    for (const { density, albedo, g, environmentSampling, mean, nonFinite, rmse } of results) {
      const red = (mean as number[]).filter((_, i) => i % 4 === 0);
      const lo = Math.min(...red), hi = Math.max(...red);
      const msg = `density ${density} albedo ${albedo} g ${g} ${environmentSampling}: pixels in [${lo}, ${hi}]`;
      expect(nonFinite, msg).toBe(false);
      expect(Number.isFinite(rmse), msg).toBe(true);
      if (albedo === 0 && density === 1e4) expect(hi, msg).toBe(0); // T = e^{-10⁴}
      if (albedo === 0 && density === 1e-3) { expect(lo, msg).toBeGreaterThanOrEqual(0); expect(hi, msg).toBeLessThanOrEqual(1); }
      if (albedo === 1 && environmentSampling === 'phase') { expect(Math.abs(lo - 1), msg).toBeLessThan(1e-6); expect(Math.abs(hi - 1), msg).toBeLessThan(1e-6); }
      if (albedo === 1 && environmentSampling === 'mis') { expect(lo, msg).toBeGreaterThan(0.3); expect(hi, msg).toBeLessThan(3); }
    }
  });

  it('an HDR environment from 1e-4 to 1e4: finite under every sampling strategy', async () => {
    for (const environmentSampling of ['mis', 'light', 'phase']) {
      const r = await page().page.evaluate((backend, environmentSampling) => {
        const mt = (window as any).mt;
        const { core } = (window as any).vpt;
        const W = 32, H = 16;
        const data = new Float32Array(W * H * 3);
        for (let i = 0; i < data.length; i++) data[i] = Math.pow(10, (((i * 7919) % 101) / 100) * 8 - 4);
        data.set([1e4, 1e4, 1e4], 3 * (3 * W + 5)); // a tiny "sun"
        const scene = {
          volume: core.createProceduralVolume('blob', 16),
          transferFunction: { dimensions: '1d', points: [{ value: 0, color: [1, 1, 1], opacity: 0 }, { value: 0.5, color: [0.5, 0.8, 1], opacity: 0.5 }, { value: 1, color: [1, 1, 1], opacity: 1 }] },
          camera: { position: [0, 0, 2], target: [0, 0, 0], up: [0, 1, 0], fovy: 0.9 },
          lights: [{ type: 'directional', direction: [0, 1, 0], irradiance: [1e4, 1e4, 1e4] }],
          environment: { type: 'latlong', width: W, height: H, data }, densityScale: 200, seed: 4,
        };
        return mt.run({ backend, width: 8, height: 8, iterations: 8, params: { environmentSampling, anisotropy: 0.9 }, scene });
      }, backend, environmentSampling);
      expect(r.nonFinite, environmentSampling).toBe(false);
      expect(Number.isFinite(r.err.rmse)).toBe(true);
      expect(Math.max(...r.hdr)).toBeGreaterThan(1e-3);
    }
  });
});

describe('MCRT environment map as seen by the camera (webgl2)', () => {
  it('shows the lat-long texel along each ray exactly where no medium is hit (mapping: row 0 = +y, u = 0 along −z)', async () => {
    const W = 24, H = 16, EW = 8, EH = 4;
    const data = new Float32Array(EW * EH * 3);
    for (let k = 0; k < EW * EH; k++) data.set([k + 1, 100 + k, 0.5 * (k + 1)], 3 * k);
    const camera = { position: [0, 0, 0.9] as Vec3, target: [0.3, 0.2, 0] as Vec3, up: [0, 1, 0] as Vec3, fovy: 2.2 };
    const gpu: number[] = await page().page.evaluate(async (W, H, camera, data, EW, EH) => {
      const mt = (window as any).mt;
      const r = await mt.run({ backend: 'webgl2', width: W, height: H, iterations: 2, frames: false, scene: mt.cubeScene({ albedo: [1, 1, 1], density: 0, camera, environment: { type: 'latlong', width: EW, height: EH, data: Float32Array.from(data), scale: 2 } }) });
      return r.hdr;
    }, W, H, camera, Array.from(data), EW, EH);
    const scene = { camera } as Scene;
    const tables = buildEnvironmentSampling({ type: 'latlong', width: EW, height: EH, data, scale: 2 });
    let checked = 0;
    for (let y = 0; y < H; y++) for (let x = 0; x < W; x++) {
      // Pixels whose whole footprint lies in one texel: the jittered mean is that texel.
      const texels = new Set<number>();
      for (const [fx, fy] of [[0, 0], [1, 0], [0, 1], [1, 1], [0.5, 0.5]]) {
        const { dir } = reference.cameraRay(scene, W, H, (x + fx) / W, (y + fy) / H);
        texels.add(environmentLookupCpu(tables, dir).radiance[1]);
      }
      if (texels.size !== 1) continue;
      const { dir } = reference.cameraRay(scene, W, H, (x + 0.5) / W, (y + 0.5) / H);
      const L = environmentLookupCpu(tables, dir).radiance;
      for (let c = 0; c < 3; c++) expect(gpu[4 * (x + W * y) + c]).toBeCloseTo(L[c], 4);
      checked++;
    }
    expect(checked).toBeGreaterThan(W * H / 3);
  });
});

describe('MCRT long accumulation (webgl2, 1×1 image, 100 000 iterations)', () => {
  // The white furnace with MIS (each sample noisy around 1): after 1e5 iterations the running
  // mean must still be 1 within 4 standard errors, counted generously as if only 1e4 samples
  // had been averaged (float32 running means stop refining long before they drift), and the
  // even and odd half-means must agree with it.
  it('the accumulated mean does not drift', async () => {
    const r = await page().page.evaluate(async () => {
      const t = (window as any).t;
      const mt = (window as any).mt;
      const ctx = await t.context({ backend: 'webgl2', renderer: 'mcrt', width: 1, height: 1, params: { anisotropy: 0.5 } });
      ctx.setScene(mt.cubeScene({ albedo: [1, 1, 1], density: 2, seed: 21, camera: { position: [0, 0, 2], target: [0, 0, 0], up: [0, 1, 0], fovy: 0.3 } }));
      let s = 0, s2 = 0;
      const first = 256;
      for (let k = 0; k < first; k++) { ctx.iterate(1); const f = await ctx.readFrame(); s += f[0]; s2 += f[0] * f[0]; }
      const total = 100000;
      for (let done = first; done < total; done += 2000) { ctx.iterate(Math.min(2000, total - done)); await ctx.backend.finish(); }
      const hdr = await ctx.readHDR();
      const err = await ctx.estimateError();
      const iterations = ctx.stats.iterations;
      ctx.dispose();
      const m = s / first;
      return { mean: hdr[0], std: Math.sqrt(s2 / first - m * m), err, iterations, nonFinite: t.hasNonFinite(hdr) };
    });
    expect(r.iterations).toBe(100000);
    expect(r.nonFinite).toBe(false);
    expect(r.std).toBeGreaterThan(0.01);
    const tol = (4 * r.std) / Math.sqrt(1e4);
    expect(Math.abs(r.mean - 1), JSON.stringify(r)).toBeLessThan(tol);
    // |even − odd|/2 is the error estimate: it must be of the size of the error, not of a drift.
    expect(r.err.rmse, JSON.stringify(r)).toBeLessThan(tol);
  });
});
