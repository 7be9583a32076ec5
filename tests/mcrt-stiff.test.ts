import { describe, expect, it } from 'vitest';
import { tf1d } from './helpers/test-scene.js';
import {
  buildEnvironmentSampling,
  createProceduralVolume,
  environmentLookupCpu,
  reference,
  type Scene,
  type Vec3,
} from '../packages/core/src/index.js';
import { opticalDepth, pixelExpectations } from './helpers/mcrt-reference.js';
import { zSummary } from './helpers/mcrt-stats.js';
import { BACKENDS, usePage } from './helpers/session.js';

/**
 * Stiff and extreme cases (docs/design.md, "Numbers that matter"): very thin and very dense media,
 * |g| = 0.999, albedo 0 and 1, an HDR environment spanning 1e-4 … 1e4, and a long
 * accumulation. No NaN or Inf may reach a frame or an accumulation, and where an answer is
 * known the image must show it, by z-tests against it: the thin absorber's exp(−σ·chord),
 * the white furnace's 1, and the HDR environment seen through an absorbing blob.
 */
const page = usePage({ mcrt: true });

describe.each(BACKENDS)('MCRT stiff media on %s', (backend) => {
  it('densities 1e-3 and 1e4, albedo 0 and 1, g = ±0.999: finite, and the known answers', async () => {
    // 24 frames where a pixel is a Bernoulli draw (the thin absorber); 8 in the dense media, whose long walks are slow.
    const ITER_THIN = 24,
      ITER_DENSE = 8;
    const results = await page.run(
      async ({ t, mt }, backend, ITER_THIN, ITER_DENSE) => {
        const out = [];
        for (const environmentSampling of ['mis', 'phase']) {
          const ctx = await t.context({
            backend,
            renderer: 'mcrt',
            width: 4,
            height: 4,
            params: { environmentSampling },
          });
          try {
            for (const density of [1e-3, 1e4])
              for (const albedo of [0, 1])
                for (const g of [-0.999, 0.999]) {
                  const r = await mt.measure(ctx, {
                    iterations: density < 1 ? ITER_THIN : ITER_DENSE,
                    params: { anisotropy: g },
                    scene: mt.cubeScene({ albedo: [albedo, albedo, albedo], density }),
                  });
                  out.push({
                    density,
                    albedo,
                    g,
                    environmentSampling,
                    mean: r.mean,
                    se: r.se,
                    nonFinite: r.nonFinite,
                    rmse: r.err.rmse,
                  });
                }
          } finally {
            ctx.dispose();
          }
        }
        return out;
      },
      backend,
      ITER_THIN,
      ITER_DENSE,
    );
    expect(results.length).toBe(16);
    // The thin absorber: the environment (1) times exp(−1e-3·chord), box-filtered over each pixel.
    const cube = {
      volume: createProceduralVolume('cube', 8),
      camera: { position: [0, 0, 2], target: [0, 0, 0], up: [0, 1, 0], fovy: 0.4 },
    } as Scene;
    const thin = pixelExpectations(cube, 4, 4, (_o, _d, t0, t1) => {
      const T = Math.exp(-1e-3 * Math.max(0, t1 - t0));
      return [T, T, T];
    });
    expect(thin.every((p) => p.interior)).toBe(true); // every pixel looks through the cube
    const furnace: string[] = [];
    for (const { density, albedo, g, environmentSampling, mean, se, nonFinite, rmse } of results) {
      const red = (mean as number[]).filter((_, i) => i % 4 === 0);
      const lo = Math.min(...red),
        hi = Math.max(...red);
      const msg = `density ${density} albedo ${albedo} g ${g} ${environmentSampling}: pixels in [${lo}, ${hi}]`;
      expect(nonFinite, msg).toBe(false);
      expect(Number.isFinite(rmse), msg).toBe(true);
      if (albedo === 0 && density === 1e4) expect(hi, msg).toBe(0); // T = e^{-10⁴}
      if (albedo === 0 && density === 1e-3) {
        // Each sample is 0 or 1 (the camera ray's free flight): σ per pixel ≥ the Bernoulli spread √(E(1−E)/N).
        const z = thin.map(
          (p, k) =>
            (red[k] - p.value[0]) / Math.max(se[4 * k], Math.sqrt((p.value[0] * (1 - p.value[0])) / ITER_THIN), 1e-6),
        );
        expect(Math.max(...z.map(Math.abs)), `${msg}: z ${z.map((x) => x.toFixed(2))}`).toBeLessThan(4);
        expect(lo, msg).toBeGreaterThan(0.99); // 0.9985 expected; a black or half-bright image fails
      }
      if (albedo === 1 && environmentSampling === 'phase') {
        expect(Math.abs(lo - 1), msg).toBeLessThan(1e-6);
        expect(Math.abs(hi - 1), msg).toBeLessThan(1e-6);
      }
      if (albedo === 1 && environmentSampling === 'mis') {
        // The white furnace: 1 in expectation. The image mean against 1, in units of its standard
        // error pooled over the 16 pixels (steadier than any one pixel's few frames).
        const imageMean = red.reduce((a, b) => a + b, 0) / red.length;
        const pooledSe = Math.sqrt(red.reduce((a, _, k) => a + se[4 * k] ** 2, 0)) / red.length;
        if (pooledSe === 0) expect(imageMean, msg).toBeCloseTo(1, 6);
        else {
          const z = (imageMean - 1) / pooledSe;
          furnace.push(`${msg}: mean ${imageMean.toFixed(4)} ± ${pooledSe.toFixed(4)}, z ${z.toFixed(2)}`);
          expect(Math.abs(z), furnace.join('\n')).toBeLessThan(4);
        }
      }
    }
    expect(furnace.length).toBeGreaterThanOrEqual(2); // the dense furnace really is noisy (MIS), so the z-test bites
  });

  it('an HDR environment from 1e-4 to 1e4 seen through an absorbing blob: the CPU expectation, under every sampling strategy', async () => {
    // Albedo 0: a camera path ends at its first collision, so a pixel shows L_env(d)·T(ray).
    // Pixels whose footprint lies within one environment texel have the closed form
    // L_texel · mean T over the footprint (T by quadrature of the blob's σ_t).
    const EW = 32,
      EH = 16,
      W = 16,
      H = 16,
      ITER = 32;
    const data = new Float32Array(EW * EH * 3);
    for (let i = 0; i < data.length; i++) data[i] = Math.pow(10, (((i * 7919) % 101) / 100) * 8 - 4);
    const tf = tf1d([0, [0, 0, 0], 0], [0.5, [0, 0, 0], 0.5], [1, [0, 0, 0], 1]);
    const camera = { position: [0.3, 0.2, 1.6] as Vec3, target: [0, 0, 0] as Vec3, up: [0, 1, 0] as Vec3, fovy: 1.2 };
    const scene: Scene = {
      volume: createProceduralVolume('blob', 16),
      transferFunction: tf,
      camera,
      lights: [{ type: 'directional', direction: [0, 1, 0], irradiance: [1e4, 1e4, 1e4] }],
      environment: { type: 'latlong', width: EW, height: EH, data },
      densityScale: 4,
      seed: 4,
    };
    const tables = buildEnvironmentSampling({ type: 'latlong', width: EW, height: EH, data });
    const tau = opticalDepth(scene, 400);
    const transmittance = pixelExpectations(scene, W, H, (o, d, t0, t1) => {
      const T = Math.exp(-tau(o, d, t0, t1));
      return [T, T, T];
    });
    const inOneTexel: (Vec3 | null)[] = transmittance.map((_, k) => {
      const x = k % W,
        y = Math.floor(k / W);
      const texels = new Set<number>();
      for (const [fx, fy] of [
        [0, 0],
        [1, 0],
        [0, 1],
        [1, 1],
        [0.5, 0],
        [0, 0.5],
        [1, 0.5],
        [0.5, 1],
      ])
        texels.add(
          environmentLookupCpu(tables, reference.cameraRay(scene, W, H, (x + fx) / W, (y + fy) / H).dir).radiance[0],
        );
      return texels.size === 1
        ? environmentLookupCpu(tables, reference.cameraRay(scene, W, H, (x + 0.5) / W, (y + 0.5) / H).dir).radiance
        : null;
    });
    const attenuated = transmittance.filter((p, k) => inOneTexel[k] && p.value[0] < 0.9 && p.value[0] > 0.05).length;
    expect(attenuated).toBeGreaterThan(10); // pixels where the blob really changes the answer
    for (const environmentSampling of ['mis', 'light', 'phase']) {
      const r = await page.run(
        ({ core, mt }, backend, environmentSampling, W, H, ITER, scene, data) => {
          const s = {
            ...scene,
            volume: core.createProceduralVolume('blob', 16),
            environment: { ...scene.environment, data: Float32Array.from(data) },
          };
          return mt.run({
            backend,
            width: W,
            height: H,
            iterations: ITER,
            params: { environmentSampling, anisotropy: 0.9 },
            scene: s,
          });
        },
        backend,
        environmentSampling,
        W,
        H,
        ITER,
        { ...scene, volume: null },
        Array.from(data),
      );
      expect(r.nonFinite, environmentSampling).toBe(false);
      expect(Number.isFinite(r.err.rmse)).toBe(true);
      const z: number[] = [];
      transmittance.forEach((p, k) => {
        const L = inOneTexel[k];
        if (!L) return;
        for (let c = 0; c < 3; c++) {
          const E = L[c] * p.value[c],
            q = p.value[c];
          // A sample is 0 or L (collided or not): σ ≥ L·√(q(1−q)/N); 1e-4 relative for float32 and the quadrature.
          z.push(
            (r.mean[4 * k + c] - E) /
              Math.max(r.se[4 * k + c], L[c] * Math.sqrt((q * (1 - q)) / ITER), 1e-4 * E + 1e-9),
          );
        }
      });
      const s = zSummary(z, 3);
      const msg = `${environmentSampling}: ${JSON.stringify(s)}`;
      expect(s.n, msg).toBeGreaterThan(60);
      expect(Math.abs(s.meanScaled), msg).toBeLessThan(3.5);
      expect(s.maxAbs, msg).toBeLessThan(5);
    }
  });

  it('an HDR environment from 1e-4 to 1e4 with a 1e4 sun and light, scattering medium: finite under every sampling strategy', async () => {
    for (const environmentSampling of ['mis', 'light', 'phase']) {
      const r = await page.run(
        ({ core, mt, t }, backend, environmentSampling) => {
          const W = 32,
            H = 16;
          const data = new Float32Array(W * H * 3);
          for (let i = 0; i < data.length; i++) data[i] = Math.pow(10, (((i * 7919) % 101) / 100) * 8 - 4);
          data.set([1e4, 1e4, 1e4], 3 * (3 * W + 5)); // a tiny "sun"
          const scene = {
            volume: core.createProceduralVolume('blob', 16),
            transferFunction: t.tf1d([0, [1, 1, 1], 0], [0.5, [0.5, 0.8, 1], 0.5], [1, [1, 1, 1], 1]),
            camera: { position: [0, 0, 2], target: [0, 0, 0], up: [0, 1, 0], fovy: 0.9 },
            lights: [{ type: 'directional', direction: [0, 1, 0], irradiance: [1e4, 1e4, 1e4] }],
            environment: { type: 'latlong', width: W, height: H, data },
            densityScale: 200,
            seed: 4,
          };
          return mt.run({
            backend,
            width: 8,
            height: 8,
            iterations: 8,
            params: { environmentSampling, anisotropy: 0.9 },
            scene,
          });
        },
        backend,
        environmentSampling,
      );
      expect(r.nonFinite, environmentSampling).toBe(false);
      expect(Number.isFinite(r.err.rmse)).toBe(true);
      expect(Math.max(...r.hdr)).toBeGreaterThan(1e-3);
    }
  });
});

describe('MCRT environment map as seen by the camera (webgl2)', () => {
  it('shows the lat-long texel along each ray exactly where no medium is hit (mapping: row 0 = +y, u = 0 along −z)', async () => {
    const W = 24,
      H = 16,
      EW = 8,
      EH = 4;
    const data = new Float32Array(EW * EH * 3);
    for (let k = 0; k < EW * EH; k++) data.set([k + 1, 100 + k, 0.5 * (k + 1)], 3 * k);
    const camera = { position: [0, 0, 0.9] as Vec3, target: [0.3, 0.2, 0] as Vec3, up: [0, 1, 0] as Vec3, fovy: 2.2 };
    const gpu: number[] = await page.run(
      async ({ mt }, W, H, camera, data, EW, EH) => {
        const r = await mt.run({
          backend: 'webgl2',
          width: W,
          height: H,
          iterations: 2,
          frames: false,
          scene: mt.cubeScene({
            albedo: [1, 1, 1],
            density: 0,
            camera,
            environment: { type: 'latlong', width: EW, height: EH, data: Float32Array.from(data), scale: 2 },
          }),
        });
        return r.hdr;
      },
      W,
      H,
      camera,
      Array.from(data),
      EW,
      EH,
    );
    const scene = { camera } as Scene;
    const tables = buildEnvironmentSampling({ type: 'latlong', width: EW, height: EH, data, scale: 2 });
    let checked = 0;
    for (let y = 0; y < H; y++)
      for (let x = 0; x < W; x++) {
        // Pixels whose whole footprint lies in one texel: the jittered mean is that texel.
        const texels = new Set<number>();
        for (const [fx, fy] of [
          [0, 0],
          [1, 0],
          [0, 1],
          [1, 1],
          [0.5, 0.5],
        ]) {
          const { dir } = reference.cameraRay(scene, W, H, (x + fx) / W, (y + fy) / H);
          texels.add(environmentLookupCpu(tables, dir).radiance[1]);
        }
        if (texels.size !== 1) continue;
        const { dir } = reference.cameraRay(scene, W, H, (x + 0.5) / W, (y + 0.5) / H);
        const L = environmentLookupCpu(tables, dir).radiance;
        for (let c = 0; c < 3; c++) expect(gpu[4 * (x + W * y) + c]).toBeCloseTo(L[c], 4);
        checked++;
      }
    expect(checked).toBeGreaterThan((W * H) / 3);
  });
});

describe('MCRT long accumulation (webgl2, 1×1 image, 100 000 iterations)', () => {
  // The white furnace with MIS (each sample noisy around 1): after 1e5 iterations the running
  // mean must still be 1 within 4 standard errors, counted generously as if only 1e4 samples
  // had been averaged (float32 running means stop refining long before they drift), and the
  // even and odd half-means must agree with it.
  it('the accumulated mean does not drift', async () => {
    const r = await page.run(async ({ t, mt }) => {
      const ctx = await t.context({
        backend: 'webgl2',
        renderer: 'mcrt',
        width: 1,
        height: 1,
        // The fixed estimator (MIS): 'auto' samples this white furnace by the phase function
        // alone, which returns exactly 1 on every path, and a drift check needs noise.
        params: { anisotropy: 0.5, estimator: 'fixed' },
      });
      ctx.setScene(
        mt.cubeScene({
          albedo: [1, 1, 1],
          density: 2,
          seed: 21,
          camera: { position: [0, 0, 2], target: [0, 0, 0], up: [0, 1, 0], fovy: 0.3 },
        }),
      );
      let s = 0,
        s2 = 0;
      const first = 256;
      for (let k = 0; k < first; k++) {
        ctx.iterate(1);
        const f = await ctx.readFrame();
        s += f[0];
        s2 += f[0] * f[0];
      }
      const total = 100000;
      for (let done = first; done < total; done += 2000) {
        ctx.iterate(Math.min(2000, total - done));
        await ctx.backend.finish();
      }
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
