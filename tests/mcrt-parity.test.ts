import { describe, expect, it } from 'vitest';
import { usePage } from './helpers/session.js';

const page = usePage();

// docs/design.md: with the same seed both backends produce the same image on SwiftShader, bit for
// bit. One scene with everything (HDR lat-long environment, two directional lights, a
// heterogeneous coloured medium), rendered by kernel variants that exercise every feature flag.
const VARIANTS: Record<string, unknown>[] = [
  {},
  { tracking: 'ratio', majorantGrid: false },
  { tracking: 'delta', scattering: 'single', anisotropy: 0.7, lightSamples: 3 }, // MIS, 1/3 weights
  { scattering: 'single', anisotropy: 0.1 }, // auto: 3 light samples of the map alone
  { scattering: 'single', environmentSampling: 'phase', lightSamples: 2 },
  { environmentSampling: 'light', misHeuristic: 'balance', anisotropy: -0.999, maxDepth: 3 },
  { environmentSampling: 'phase', anisotropy: 0.999, rouletteDepth: 1 },
  { debugOutput: 'transmittance' },
  { debugOutput: 'fetches' },
];

describe('MCRT WebGL 2 / WebGPU parity', () => {
  it.each(VARIANTS.map((v) => [JSON.stringify(v), v]))(
    '%s: HDR image and last frame are bit-identical, and so is the error estimate from the half accumulations',
    async (_name, params) => {
      const r = await page.run(async ({ core, t }, params) => {
        const W = 16,
          H = 12;
        const env = {
          type: 'latlong',
          width: 16,
          height: 8,
          data: new Float32Array(16 * 8 * 3).map((_, i) => Math.pow(10, (((i * 7919) % 97) / 97) * 4 - 2)),
        };
        const out: Record<string, { hdr: Float32Array; frame: Float32Array; err: unknown }> = {};
        for (const backend of ['webgl2', 'webgpu']) {
          const ctx = await t.context({ backend, renderer: 'mcrt', width: W, height: H, params });
          ctx.setScene({
            ...t.scene({
              volume: core.createProceduralVolume('blob', 20),
              densityScale: 30,
              seed: 7,
              camera: { position: [0.7, -0.4, 1.5], target: [0, 0.05, 0], up: [0, 1, 0], fovy: 0.8 },
              transferFunction: t.tf1d([0.1, [0.2, 0.4, 1], 0], [0.6, [1, 0.8, 0.3], 0.8], [1, [0.9, 0.9, 0.9], 1]),
              environment: env,
            }),
            lights: [
              { type: 'directional', direction: [1, 1, 0.5], irradiance: [3, 2, 1] },
              { type: 'directional', direction: [-1, 0.2, 0], irradiance: [0.5, 0.5, 2] },
            ],
          });
          await ctx.renderIterations(5);
          out[backend] = { hdr: await ctx.readHDR(), frame: await ctx.readFrame(), err: await ctx.estimateError() };
          ctx.dispose();
        }
        const a = out.webgl2,
          b = out.webgpu;
        let varied = 0;
        for (let i = 4; i < a.hdr.length; i += 4) if (a.hdr[i] !== a.hdr[0]) varied++;
        return {
          hdrDiff: t.sameBits(a.hdr, b.hdr),
          frameDiff: t.sameBits(a.frame, b.frame),
          errA: a.err,
          errB: b.err,
          varied,
          n: a.hdr.length / 4,
          nonFinite: t.hasNonFinite(a.hdr),
        };
      }, params);
      expect(r.nonFinite).toBe(false);
      expect(r.varied).toBeGreaterThan(r.n / 8); // a real image
      expect(r.hdrDiff).toBe(0);
      expect(r.frameDiff).toBe(0);
      // The half accumulations agree too (the error estimate is computed from them).
      expect(r.errA).toEqual(r.errB);
    },
  );
});
