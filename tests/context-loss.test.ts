import { describe, expect, it } from 'vitest';
import { BACKENDS, usePage } from './helpers/session.js';

const page = usePage();

describe.each(BACKENDS)('GPU loss on %s', (backend) => {
  it('recovers from a loss in the middle of a render and the final image still matches', async () => {
    const r = await page.run(async ({ core, t }, backend) => {
      const scene = t.scene({ volume: core.createProceduralVolume('blob', 12), densityScale: 8, seed: 9 });
      const opts = {
        backend,
        renderer: 'eam',
        width: 16,
        height: 16,
        post: [{ type: 'tonemap', operator: 'reinhard' }, { type: 'srgb' }],
      };
      const reference = await t.context(opts);
      reference.setScene(scene);
      await reference.renderIterations(8);
      const want: Float32Array = await reference.readHDR();
      reference.dispose();

      const ctx = await t.context(opts);
      ctx.setScene(scene);
      ctx.iterate(3);
      let lostSeen = false;
      ctx.backend.onLost(() => {
        lostSeen = true;
      });
      await ctx.backend.simulateLoss(30);
      const afterRestore = ctx.stats.iterations; // accumulation restarted on the new context
      await ctx.renderIterations(8);
      const got: Float32Array = await ctx.readHDR();
      const ldr: Uint8Array = await ctx.readLDR();
      ctx.dispose();
      return { lostSeen, afterRestore, diff: t.sameBits(want, got), ldrLength: ldr.length };
    }, backend);
    expect(r.lostSeen).toBe(true);
    expect(r.afterRestore).toBe(0);
    expect(r.diff).toBe(0);
    expect(r.ldrLength).toBe(16 * 16 * 4);
  });
});
