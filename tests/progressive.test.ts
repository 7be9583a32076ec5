import { describe, expect, it } from 'vitest';
import { BACKENDS, usePage } from './helpers/session.js';

const page = usePage();

describe.each(BACKENDS)('progressive loop on %s', (backend) => {
  it('refines in the background, stops at maxIterations, restarts after a camera change, and presents the LDR image', async () => {
    const r = await page.run(async ({ vpt, core, t }, backend) => {
      const canvas = document.body.appendChild(document.createElement('canvas'));
      const post = [{ type: 'tonemap', operator: 'reinhard' }, { type: 'srgb' }];
      const ctx = await t.context({ backend, canvas, renderer: 'eam', width: 16, height: 12, post });
      const scene = t.scene({
        volume: core.createProceduralVolume('blob', 12),
        densityScale: 8,
        environment: { type: 'constant', radiance: [0.2, 0.2, 0.2] },
      });
      ctx.setScene(scene);
      const seen: number[] = [];
      ctx.onStats((s: any) => seen.push(s.iterations));
      const waitFor = async (pred: () => boolean, ms = 30000) => {
        const t0 = performance.now();
        while (!pred()) {
          if (performance.now() - t0 > ms) return false;
          await new Promise((res) => setTimeout(res, 20));
        }
        return true;
      };
      ctx.start({ maxIterations: 40, frameBudgetMs: 8 });
      const reached = await waitFor(() => ctx.stats.iterations >= 40);
      await new Promise((res) => setTimeout(res, 200));
      const capped = ctx.stats.iterations;
      const msPerIteration = ctx.stats.msPerIteration;
      ctx.updateScene({ camera: { ...scene.camera, position: [1.2, 0.4, 1.4] } });
      const afterChange = ctx.stats.iterations;
      const restarted = await waitFor(() => ctx.stats.iterations >= 40);
      ctx.stop();
      await new Promise((res) => setTimeout(res, 100));
      // What the canvas shows is the LDR image (read through a 2D canvas; row 0 at the top).
      // Headless Chrome snapshots a WebGPU canvas as blank once its frame was presented,
      // so present once more and read it in the same task (screenshots show it on screen).
      ctx.setPost(vpt.post.postChainFromJSON(post));
      ctx.present();
      const c2 = document.createElement('canvas');
      c2.width = 16;
      c2.height = 12;
      const g = c2.getContext('2d')!;
      g.drawImage(canvas, 0, 0);
      const shown = g.getImageData(0, 0, 16, 12).data;
      const ldr: Uint8Array = await ctx.readLDR();
      let maxDiff = 0;
      for (let i = 0; i < shown.length; i += 4)
        for (let c = 0; c < 3; c++) maxDiff = Math.max(maxDiff, Math.abs(shown[i + c] - ldr[i + c]));
      let varied = 0;
      for (let i = 4; i < ldr.length; i += 4) if (ldr[i] !== ldr[0]) varied++;
      ctx.dispose();
      canvas.remove();
      return { reached, capped, msPerIteration, afterChange, restarted, batches: seen.length, maxDiff, varied };
    }, backend);
    expect(r.reached).toBe(true);
    expect(r.capped).toBe(40);
    expect(r.msPerIteration).toBeGreaterThan(0);
    expect(r.batches).toBeGreaterThan(1);
    expect(r.afterChange).toBe(0);
    expect(r.restarted).toBe(true);
    expect(r.varied).toBeGreaterThan(16);
    expect(r.maxDiff).toBe(0);
  });
});
