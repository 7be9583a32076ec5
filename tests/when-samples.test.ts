import { describe, expect, it } from 'vitest';
import { BACKENDS, usePage } from './helpers/session.js';

const page = usePage();

// RenderContext.whenSamples(n) and readHDR() right after a scene change: the README's
// "Use it from code" snippet reads the image straight after updateScene().
describe.each(BACKENDS)('waiting for samples on %s', (backend) => {
  it('whenSamples waits for the background loop or runs the iterations itself; readHDR right after a change waits for the first sample', async () => {
    const r = await page.run(async ({ core, t }, backend) => {
      const canvas = document.body.appendChild(document.createElement('canvas'));
      const post = [{ type: 'tonemap', operator: 'aces' }, { type: 'srgb' }];
      const ctx = await t.context({ backend, canvas, renderer: 'eam', width: 12, height: 12, post });
      const errors: string[] = [];
      const code = async (p: () => Promise<unknown>) => {
        try {
          await p();
          return 'resolved';
        } catch (e) {
          return (e as any).code;
        }
      };
      errors.push(await code(() => ctx.whenSamples(1))); // no scene yet
      const scene = t.scene({
        volume: core.createProceduralVolume('blob', 12),
        densityScale: 8,
        environment: { type: 'constant', radiance: [0.2, 0.2, 0.2] },
      });
      ctx.setScene(scene);
      // Not started: whenSamples runs the iterations itself.
      const direct = (await ctx.whenSamples(5)).iterations;
      // Started: it waits for the loop.
      ctx.start({ frameBudgetMs: 4 });
      const looped = (await ctx.whenSamples(12)).iterations;
      // A change resets; readHDR straight after it waits for the first iteration instead of throwing.
      ctx.updateScene({ camera: { ...scene.camera, position: [1.2, 0.4, 1.4] } });
      const afterChange = ctx.stats.iterations;
      const hdr: Float32Array = await ctx.readHDR();
      let finite = true,
        nonZero = 0;
      for (const v of hdr) {
        if (!Number.isFinite(v)) finite = false;
        if (v !== 0) nonZero++;
      }
      ctx.stop();
      ctx.start({ maxIterations: 3 });
      errors.push(await code(() => ctx.whenSamples(10))); // the loop stops short of 10
      ctx.stop();
      ctx.dispose();
      canvas.remove();
      errors.push(await code(() => ctx.whenSamples(1)));
      return { errors, direct, looped, afterChange, finite, nonZero, length: hdr.length };
    }, backend);
    expect(r.errors).toEqual(['invalid-scene', 'invalid-scene', 'disposed']);
    expect(r.direct).toBeGreaterThanOrEqual(5);
    expect(r.looped).toBeGreaterThanOrEqual(12);
    expect(r.afterChange).toBe(0);
    expect(r.length).toBe(12 * 12 * 4);
    expect(r.finite).toBe(true);
    expect(r.nonZero).toBeGreaterThan(12 * 12); // a lit background and a blob, not an empty image
  });
});
