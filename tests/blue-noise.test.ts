import { describe, expect, it } from 'vitest';
import { zSummary } from './helpers/mcrt-stats.js';
import { usePage } from './helpers/session.js';

/**
 * `sampler: 'blue-noise'` (core's shaders/blue-noise.ts): the first dimensions of each sample
 * come from a rank-1 sequence rotated per pixel by a blue-noise mask. Checked here: both
 * backends render the same bits for every renderer that has it, the bound mask is the CPU's,
 * nothing non-finite reaches the accumulation, and the estimate is unbiased — over independent
 * seeds the per-pixel means of blue-noise runs agree with those of PCG runs (z-test; EAM, ISO's
 * shaded image and MCRT are means; MIP keeps a maximum, which the sampler may reach sooner).
 */
const page = usePage();

const RENDERERS = ['eam', 'mip', 'iso', 'mcrt'] as const;
const W = 16,
  H = 12;

describe('blue-noise sampling', () => {
  it.each(RENDERERS)(
    '%s: WebGL 2 and WebGPU images are bit-identical, finite, and differ from the PCG image',
    async (renderer) => {
      const r = await page.run(
        async ({ core, t }, renderer, W, H) => {
          const scene = {
            ...t.scene({
              volume: core.createProceduralVolume('blob', 20),
              densityScale: 20,
              seed: 5,
              camera: { position: [0.6, -0.3, 1.5], target: [0, 0, 0], up: [0, 1, 0], fovy: 0.8 },
              transferFunction: t.tf1d([0.1, [0.2, 0.4, 1], 0], [0.6, [1, 0.8, 0.3], 0.8], [1, [0.9, 0.9, 0.9], 1]),
              environment: {
                type: 'latlong',
                width: 8,
                height: 4,
                data: new Float32Array(8 * 4 * 3).map((_, i) => [0.05, 0.3, 1, 3][(i * 5 + (i >> 2)) % 4]),
              },
            }),
            lights: [{ type: 'directional', direction: [1, 1, 0.5], irradiance: [2, 1.5, 1] }],
          };
          const out: Record<string, Float32Array> = {};
          let mask: Float32Array | null = null;
          for (const [key, backend, sampler] of [
            ['gl', 'webgl2', 'blue-noise'],
            ['gpu', 'webgpu', 'blue-noise'],
            ['pcg', 'webgl2', 'pcg'],
          ] as const) {
            const ctx = await t.context({
              backend,
              renderer,
              width: W,
              height: H,
              sampling: 'exact',
              params: { sampler },
            });
            ctx.setScene(scene);
            await ctx.renderIterations(6);
            out[key] = await ctx.readHDR();
            if (key === 'gl') mask = await ctx.readAuxiliaryTexture('blueNoise');
            ctx.dispose();
          }
          // The sampler is core's subpath (the renderers import it; the page's import map lists it).
          // (eval: a literal import() here would be rewritten by the test runner's transform.)
          const cpu = (await (0, eval)("import('@vpt/core/blue-noise')")).blueNoiseMask() as Float32Array;
          let maskDiff = 0;
          for (let i = 0; i < cpu.length; i++) if (mask![i * (mask!.length / cpu.length)] !== cpu[i]) maskDiff++;
          return {
            diff: t.sameBits(out.gl, out.gpu),
            vsPcg: t.sameBits(out.gl, out.pcg),
            nonFinite: t.hasNonFinite(out.gl) || t.hasNonFinite(out.gpu),
            maskDiff,
            maskLength: mask!.length,
          };
        },
        renderer,
        W,
        H,
      );
      expect(r.nonFinite).toBe(false);
      expect(r.diff).toBe(0);
      expect(r.maskDiff).toBe(0);
      // The sampler changes the samples: many pixel values differ from the PCG image's.
      expect(r.vsPcg).toBeGreaterThan((W * H) / 2);
    },
  );

  // Per seed s: the image after N iterations, for K seeds with each sampler. The per-pixel mean
  // over seeds and its standard error (seeds are independent in both samplers) give
  // z = Δmean / √(se₁² + se₂²). Pass: per channel |Σz|/√n < 4 and max |z| < 5.5.
  it.each([
    ['eam', {}],
    ['iso', {}],
    ['mcrt', {}],
    ['mcrt', { scattering: 'single' }],
  ] as const)('%s %j: blue noise is unbiased (z-test of means over seeds against PCG)', async (renderer, params) => {
    const K = 16,
      N = 4;
    const runs = await page.run(
      async ({ core, t }, renderer, params, K, N) => {
        const base = {
          ...t.scene({
            volume: core.createProceduralVolume('blob', 16),
            densityScale: 25,
            camera: { position: [0.3, 0.9, 1.8], target: [0, 0, 0], up: [0, 1, 0], fovy: 0.6 },
            transferFunction: t.tf1d(
              [0.05, [0.9, 0.9, 0.9], 0],
              [0.4, [0.95, 0.7, 0.4], 0.7],
              [1, [0.99, 0.99, 0.99], 1],
            ),
            environment: {
              type: 'latlong',
              width: 8,
              height: 4,
              data: new Float32Array(8 * 4 * 3).map((_, i) => [0.05, 0.3, 1, 5][(i * 5 + (i >> 2)) % 4]),
            },
          }),
          lights: [{ type: 'directional', direction: [-0.4, 1, 0.3], irradiance: [2, 1.8, 1.5] }],
        };
        const out: Record<string, { mean: number[]; se: number[]; nonFinite: boolean }> = {};
        for (const sampler of ['pcg', 'blue-noise']) {
          const ctx = await t.context({
            backend: 'webgl2',
            renderer,
            width: 16,
            height: 16,
            params: { ...params, sampler },
          });
          const sum = new Float64Array(16 * 16 * 4);
          const sq = new Float64Array(16 * 16 * 4);
          let nonFinite = false;
          for (let s = 0; s < K; s++) {
            ctx.setScene({ ...base, seed: 1000 + s * 7919 });
            await ctx.renderIterations(N);
            const hdr = await ctx.readHDR();
            nonFinite ||= t.hasNonFinite(hdr);
            for (let i = 0; i < hdr.length; i++) {
              sum[i] += hdr[i];
              sq[i] += hdr[i] * hdr[i];
            }
          }
          ctx.dispose();
          const mean = Array.from(sum, (x) => x / K);
          const se = Array.from(sq, (x, i) => Math.sqrt(Math.max(x / K - mean[i] ** 2, 0) / (K - 1)));
          out[sampler] = { mean, se, nonFinite };
        }
        return out;
      },
      renderer,
      params,
      K,
      N,
    );
    const a = runs['pcg'],
      b = runs['blue-noise'];
    expect(a.nonFinite || b.nonFinite).toBe(false);
    const z: number[] = [];
    for (let i = 0; i < a.mean.length; i += 4) {
      for (let c = 0; c < 3; c++) {
        const se = Math.hypot(a.se[i + c], b.se[i + c]);
        if (se === 0) {
          expect(a.mean[i + c]).toBe(b.mean[i + c]);
          continue;
        }
        z.push((a.mean[i + c] - b.mean[i + c]) / se);
      }
    }
    const s = zSummary(z, 3);
    expect(z.length).toBeGreaterThan(100);
    expect(s.meanScaled, JSON.stringify(s)).toBeLessThan(4);
    expect(s.maxAbs, JSON.stringify(s)).toBeLessThan(5.5);
  });
});
