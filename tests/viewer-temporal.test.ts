import { describe, expect, it } from 'vitest';
import { useViewerPage } from './helpers/viewer-page.js';

/**
 * The viewer's `temporal` attribute (docs/architecture.md, "Temporal reuse"): on by default, so a
 * camera move reprojects the image shown into the new view (pixels stand for more samples than
 * the new ones); 'off' restarts from nothing; a bad value is a typed error naming the attribute.
 */
const viewer = useViewerPage();

describe('<vpt-viewer temporal>', () => {
  it('reuses the image across a camera move by default, not with temporal="off", and refuses bad values', async () => {
    const r = await viewer().page.evaluate(async () => {
      const vt = window.vt;
      const el = vt.blob('eam', 100000);
      await el.whenSettled();
      await vt.next(el, 'progress');
      // The resolve pass is a lazy chunk, turned on once the context is open.
      for (let k = 0; k < 200 && !el.context.temporalReuse; k++) await vt.frames(1);
      await vt.frames(4);
      const move = async (dx: number) => {
        const c = el.camera;
        el.camera = { ...c, position: [c.position[0] + dx, c.position[1], c.position[2]] };
        await el.updateComplete;
        await vt.frames(2);
        const stats = el.context.stats;
        const state: Float32Array | null = await el.context.readTemporalState();
        let took = 0;
        if (state) for (let i = 1; i < state.length; i += 4) if (state[i] > stats.iterations) took++;
        return { took, pixels: state ? state.length / 4 : 0 };
      };
      const defaultMode = el.temporal;
      const on = await move(0.02);
      el.setAttribute('temporal', 'sometimes');
      await el.updateComplete;
      const bad = el.__events.filter((e: { type: string }) => e.type === 'error').pop();
      el.setAttribute('temporal', 'off');
      await el.updateComplete;
      await vt.frames(2);
      const offReuse = el.context.temporalReuse;
      const off = await move(0.02);
      el.remove();
      return { defaultMode, on, bad, offReuse, off };
    });
    expect(r.defaultMode).toBe('on');
    expect(r.on.pixels).toBeGreaterThan(0);
    expect(r.on.took).toBeGreaterThan(0.2 * r.on.pixels);
    expect(r.bad).toMatchObject({ code: 'invalid-scene', source: 'attribute' });
    expect(r.bad.message).toMatch(/temporal/);
    expect(r.offReuse).toBe(false);
    expect(r.off).toEqual({ took: 0, pixels: 0 });
  }, 300_000);
});
