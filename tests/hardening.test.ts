import { describe, expect, it } from 'vitest';
import { BACKENDS, usePage } from './helpers/session.js';

/**
 * Issue 15 in the browser: the brightest accepted sky keeps its energy under MIS, a step
 * too small for the volume is refused before a kernel can spin, a constant volume renders.
 */
const page = usePage({ mcrt: true });

describe.each(BACKENDS)('limits on %s', (backend) => {
  it('MCRT with MIS under a sky of MAX_RADIANCE (constant and lat-long) gives exactly MAX_RADIANCE × the image under radiance 1; 3e38 is refused', async () => {
    const r = (await page.run(async ({ core, t, mt }, backend) => {
      const L = core.MAX_RADIANCE;
      const ctx = await t.context({
        backend,
        renderer: 'mcrt',
        width: 8,
        height: 8,
        params: { maxDepth: -1, environmentSampling: 'mis' },
      });
      const latlong = (s: number) => ({
        type: 'latlong',
        width: 8,
        height: 4,
        data: new Float32Array(8 * 4 * 3).fill(1),
        scale: s,
      });
      try {
        const out: Record<string, unknown> = {};
        for (const [name, env] of [
          ['constant', (s: number) => ({ type: 'constant', radiance: [s, s, s] })],
          ['latlong', latlong],
        ] as const) {
          const unit = await mt.measure(ctx, {
            iterations: 8,
            frames: false,
            scene: mt.cubeScene({ albedo: [1, 1, 1], density: 10, environment: env(1) }),
          });
          const bright = await mt.measure(ctx, {
            iterations: 8,
            frames: false,
            scene: mt.cubeScene({ albedo: [1, 1, 1], density: 10, environment: env(L) }),
          });
          let worst = 0,
            mean = 0;
          for (let i = 0; i < unit.hdr.length; i += 4)
            for (let c = 0; c < 3; c++) {
              worst = Math.max(
                worst,
                Math.abs(bright.hdr[i + c] / L - unit.hdr[i + c]) / Math.max(unit.hdr[i + c], 1e-30),
              );
              mean += bright.hdr[i + c] / L / ((unit.hdr.length * 3) / 4);
            }
          out[name] = { worst, mean, nonFinite: unit.nonFinite || bright.nonFinite };
        }
        try {
          ctx.setScene(
            mt.cubeScene({
              albedo: [1, 1, 1],
              density: 10,
              environment: { type: 'constant', radiance: [3e38, 3e38, 3e38] },
            }),
          );
          out.huge = 'accepted';
        } catch (e: any) {
          out.huge = e.code;
        }
        return out;
      } finally {
        ctx.dispose();
      }
    }, backend)) as Record<string, any>;
    for (const name of ['constant', 'latlong']) {
      expect(r[name].nonFinite, name).toBe(false);
      // Float32 scaling by 1e18 is exact up to rounding: the same paths, the same weights.
      expect(r[name].worst, name).toBeLessThan(1e-5);
      expect(Math.abs(r[name].mean - 1), name).toBeLessThan(0.1); // the furnace: the medium shows the sky
    }
    expect(r.huge).toBe('invalid-scene');
  });

  it('an EAM step below a tenth of a voxel is refused at setScene and the previous scene keeps rendering', async () => {
    const r = await page.run(async ({ core, t }, backend) => {
      const ctx = await t.context({ backend, renderer: 'eam', width: 8, height: 8 });
      try {
        const good = t.scene({ volume: core.createProceduralVolume('blob', 64), densityScale: 4 });
        ctx.setScene(good);
        await ctx.renderIterations(2);
        const before = await ctx.readHDR();
        ctx.renderer.setParams({ stepSize: 1e-4 }); // in range on its own, below 0.1 voxel of a 64³ volume
        let code = 'none',
          message = '';
        try {
          ctx.setScene(good);
        } catch (e: any) {
          code = e.code;
          message = e.message;
        }
        let zero = 'none';
        try {
          ctx.renderer.setParams({ stepSize: 0 });
        } catch (e: any) {
          zero = e.code;
        }
        ctx.renderer.setParams({ stepSize: undefined });
        await ctx.renderIterations(2);
        return { code, message, zero, same: t.sameBits(before, await ctx.readHDR()) };
      } finally {
        ctx.dispose();
      }
    }, backend);
    expect(r.code).toBe('invalid-scene');
    expect(r.message).toMatch(/EAM\.stepSize: 0\.0001 is below the smallest step .* 0\.0015625 world units/);
    expect(r.zero).toBe('invalid-scene');
    expect(r.same).toBe(0);
  });

  it('a constant float32 volume renders as the homogeneous cube (bit-identical to the procedural cube), not empty', async () => {
    const r = await page.run(async ({ core, t }, backend) => {
      const ctx = await t.context({ backend, renderer: 'eam', width: 8, height: 8 });
      try {
        ctx.setScene(
          t.scene({
            volume: core.createVolume([8, 8, 8], 'float32', new Float32Array(512).fill(0.7)),
            densityScale: 4,
          }),
        );
        await ctx.renderIterations(2);
        const constant = await ctx.readHDR();
        ctx.setScene(t.scene({ volume: core.createProceduralVolume('cube', 8), densityScale: 4 }));
        await ctx.renderIterations(2);
        const cube = await ctx.readHDR();
        let alpha = 0;
        for (let i = 3; i < constant.length; i += 4) alpha = Math.max(alpha, constant[i]);
        return { diff: t.sameBits(constant, cube), alpha };
      } finally {
        ctx.dispose();
      }
    }, backend);
    expect(r.alpha).toBeGreaterThan(0.5);
    expect(r.diff).toBe(0);
  });
});
