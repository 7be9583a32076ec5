import { describe, expect, it } from 'vitest';
import { rgbRmse } from './helpers/mcrt-stats.js';
import { usePage } from './helpers/session.js';

/**
 * RenderContext.estimateError() reports |even − odd|/2 from the renderer's half
 * accumulations. Against the true RMSE (the image vs a long-run reference with another
 * seed) it must agree within a factor of 2 (with ~430 RGB values the estimate's own
 * relative spread is ~7 %), and fall as the iterations grow.
 */
const page = usePage();

describe('MCRT live error estimate (webgl2)', () => {
  it('tracks the true RMSE against a long-run reference', async () => {
    const { ref, runs } = await page.run(async ({ core, t }) => {
      const W = 12,
        H = 12;
      const scene = (seed: number) => ({
        volume: core.createProceduralVolume('blob', 16),
        transferFunction: t.tf1d([0.05, [0.9, 0.8, 0.7], 0], [1, [0.95, 0.95, 0.95], 1]),
        camera: { position: [0.2, 0.5, 1.9], target: [0, 0, 0], up: [0, 1, 0], fovy: 0.7 },
        lights: [{ type: 'directional', direction: [1, 1, 0], irradiance: [2, 2, 2] }],
        environment: { type: 'constant', radiance: [0.3, 0.4, 0.6] },
        densityScale: 20,
        seed,
      });
      const ctx = await t.context({
        backend: 'webgl2',
        renderer: 'mcrt',
        width: W,
        height: H,
        params: { anisotropy: 0.3 },
      });
      ctx.setScene(scene(100));
      await ctx.renderIterations(1024);
      const ref: Float32Array = await ctx.readHDR();
      const runs = [];
      for (const n of [16, 64]) {
        ctx.setScene(scene(5 + n));
        await ctx.renderIterations(n);
        const hdr: Float32Array = await ctx.readHDR();
        runs.push({ n, hdr: Array.from(hdr), estimate: (await ctx.estimateError()).rmse });
      }
      ctx.dispose();
      return { ref: Array.from(ref), runs };
    });
    const r = runs.map(({ n, hdr, estimate }) => ({ n, trueRmse: rgbRmse(hdr, ref), estimate }));
    for (const { n, trueRmse, estimate } of r) {
      const msg = `${n} iterations: true ${trueRmse}, estimate ${estimate}`;
      expect(trueRmse, msg).toBeGreaterThan(1e-3);
      expect(estimate / trueRmse, msg).toBeGreaterThan(0.5);
      expect(estimate / trueRmse, msg).toBeLessThan(2);
    }
    expect(r[1].estimate).toBeLessThan(r[0].estimate);
  });
});
