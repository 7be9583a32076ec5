import { describe, expect, it } from 'vitest';
import { BACKENDS, usePage } from './helpers/session.js';

const page = usePage();
// A dense sphere under a grey sky (the volume is made in the page): every pixel's samples differ.
const SPHERE = { densityScale: 6, seed: 5, environment: { type: 'constant', radiance: [0.5, 0.5, 0.5] } };

describe.each(BACKENDS)('accumulation on %s', (backend) => {
  it('the running mean after N iterations equals the mean of the N single-iteration images', async () => {
    const r = await page.run(
      async ({ core, t }, backend, sphere) => {
        const ctx = await t.context({ backend, renderer: 'eam', width: 16, height: 16 });
        ctx.setScene(t.scene({ volume: core.createProceduralVolume('sphere', 12), ...sphere }));
        const N = 12;
        const sum = new Float64Array(16 * 16 * 4);
        let spread = 0;
        let first: Float32Array | null = null;
        for (let k = 0; k < N; k++) {
          ctx.iterate(1);
          const f: Float32Array = await ctx.readFrame();
          first ??= f;
          for (let i = 0; i < f.length; i++) {
            sum[i] += f[i];
            spread = Math.max(spread, Math.abs(f[i] - first[i]));
          }
        }
        const hdr: Float32Array = await ctx.readHDR();
        let maxErr = 0;
        for (let i = 0; i < hdr.length; i++) maxErr = Math.max(maxErr, Math.abs(hdr[i] - sum[i] / N));
        const stats = ctx.stats;
        ctx.dispose();
        return { maxErr, spread, iterations: stats.iterations };
      },
      backend,
      SPHERE,
    );
    expect(r.iterations).toBe(12);
    expect(r.spread).toBeGreaterThan(0.01); // the single images really differ (jitter)
    expect(r.maxErr).toBeLessThan(1e-5);
  });

  it.each(['eam', 'mcrt'])(
    'setSampleStart: %s estimates over disjoint sample ranges average to the estimate over their union',
    async (renderer) => {
      const r = await page.run(
        async ({ core, t }, backend, renderer, sphere) => {
          const ctx = await t.context({ backend, renderer, width: 16, height: 16 });
          ctx.setScene(t.scene({ volume: core.createProceduralVolume('sphere', 12), ...sphere }));
          const N = 6;
          const estimate = async (start: number, n: number): Promise<Float32Array> => {
            ctx.setSampleStart(start);
            await ctx.renderIterations(n);
            return ctx.readHDR();
          };
          const union = await estimate(0, 2 * N);
          const first = await estimate(0, N);
          const second = await estimate(N, N);
          const elsewhere = await estimate(3 * N, N);
          let maxErr = 0,
            halvesDiffer = 0,
            elsewhereDiffers = 0;
          for (let i = 0; i < union.length; i++) {
            maxErr = Math.max(maxErr, Math.abs(union[i] - (first[i] + second[i]) / 2));
            halvesDiffer = Math.max(halvesDiffer, Math.abs(first[i] - second[i]));
            elsewhereDiffers = Math.max(elsewhereDiffers, Math.abs(elsewhere[i] - second[i]));
          }
          const codes: string[] = [];
          for (const bad of [-1, 1.5, 2 ** 32, NaN])
            try {
              ctx.setSampleStart(bad);
            } catch (e) {
              codes.push((e as { code?: string }).code ?? 'none');
            }
          ctx.dispose();
          return { maxErr, halvesDiffer, elsewhereDiffers, codes };
        },
        backend,
        renderer,
        SPHERE,
      );
      // The running mean of samples [0, 2N) is the mean of [0, N) and [N, 2N) up to float rounding.
      expect(r.maxErr).toBeLessThan(1e-5);
      // ... and the two halves, and another range, really drew other numbers.
      expect(r.halvesDiffer).toBeGreaterThan(1e-3);
      expect(r.elsewhereDiffers).toBeGreaterThan(1e-3);
      expect(r.codes).toEqual(['invalid-scene', 'invalid-scene', 'invalid-scene', 'invalid-scene']);
    },
  );

  it('changing the camera resets accumulation', async () => {
    const r = await page.run(async ({ core, t }, backend) => {
      const ctx = await t.context({ backend, renderer: 'eam', width: 16, height: 16 });
      const scene = t.scene({ volume: core.createProceduralVolume('sphere', 12), densityScale: 6, seed: 5 });
      ctx.setScene(scene);
      ctx.iterate(5);
      const before = ctx.stats.iterations;
      ctx.updateScene({ camera: { ...scene.camera, position: [1.5, 0.3, 1.2] } });
      const afterChange = ctx.stats.iterations;
      ctx.iterate(1);
      const single: Float32Array = await ctx.readFrame();
      const hdr: Float32Array = await ctx.readHDR();
      // A fresh context with the moved camera gives the same first image.
      const fresh = await t.context({ backend, renderer: 'eam', width: 16, height: 16 });
      fresh.setScene({ ...scene, camera: { ...scene.camera, position: [1.5, 0.3, 1.2] } });
      await fresh.renderIterations(1);
      const freshHdr: Float32Array = await fresh.readHDR();
      ctx.dispose();
      fresh.dispose();
      return { before, afterChange, sameAsSingle: t.sameBits(hdr, single), sameAsFresh: t.sameBits(hdr, freshHdr) };
    }, backend);
    expect(r.before).toBe(5);
    expect(r.afterChange).toBe(0);
    expect(r.sameAsSingle).toBe(0);
    expect(r.sameAsFresh).toBe(0);
  });
});
