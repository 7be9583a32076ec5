import type { CDPSession } from 'puppeteer-core';
import { describe, expect, it } from 'vitest';
import { useViewerPage } from './helpers/viewer-page.js';

/**
 * Issue 28, <vpt-viewer> under load: many viewers on one page (browsers keep about 16 live
 * WebGL contexts per page), connect/disconnect cycles, rapid resizes to 5000 px, a render
 * size beyond the GPU memory budget, and an error banner that must go once a later value
 * renders.
 */
const viewer = useViewerPage();

async function countersAfterGc(cdp: CDPSession): Promise<{ nodes: number; listeners: number }> {
  await cdp.send('HeapProfiler.collectGarbage');
  const m = await viewer().page.metrics();
  return { nodes: m.Nodes ?? NaN, listeners: m.JSEventListeners ?? NaN };
}

describe('<vpt-viewer> under load', () => {
  it('20 WebGL 2 viewers on one page: none is left lost, and once 10 are removed the other 10 all render', async () => {
    const r = await viewer().run(async (vt) => {
      const els: any[] = [];
      for (let i = 0; i < 20; i++) {
        const el = vt.create(
          { src: 'procedural:blob?size=16', renderer: 'mip', backend: 'webgl2', panels: 'none', 'max-samples': '1' },
          'width:16px;height:16px;display:inline-block',
        );
        el.contextRestoreTimeoutMs = 600_000; // a forced loss stays "Restoring…": count it as lost
        els.push(el);
      }
      await Promise.all(els.map((el) => el.whenSettled()));
      await vt.frames(8);
      const lostOverlays = els.filter((el) => el.shadowRoot.querySelector('.lost')).length;
      for (const el of els.slice(10)) el.remove();
      const kept = els.slice(0, 10);
      const ok = (el: any) => el.context && !el.context.backend.isLost && el.samples >= 1;
      const deadline = performance.now() + 60_000;
      while (performance.now() < deadline && !kept.every(ok)) await new Promise((res) => setTimeout(res, 100));
      const rendered = await Promise.all(
        kept.map(async (el) => {
          if (!ok(el)) return false;
          try {
            const ldr: number[] = await vt.ldr(el);
            return ldr.some((v, i) => i % 4 !== 3 && v > 0);
          } catch {
            return false;
          }
        }),
      );
      const errors = kept.flatMap((el) => el.__events.filter((e: any) => e.type === 'error'));
      kept.forEach((el) => el.remove());
      return { lostOverlays, rendered, errors };
    });
    expect(r.lostOverlays).toBe(0);
    expect(r.rendered).toEqual(Array(10).fill(true));
    expect(r.errors).toEqual([]);
    expect(viewer().errors.filter((e) => !/Too many active WebGL contexts/.test(e))).toEqual([]);
  });

  it('50 connect/disconnect cycles hold event listeners and DOM nodes flat', async () => {
    const cdp = await viewer().page.createCDPSession();
    await viewer().run(async (vt) => {
      const el = vt.blob('mip', 1);
      el.id = 'cycled';
      await vt.converged(el);
    });
    const cycles = (n: number) =>
      viewer().run(async (vt, count) => {
        const el = document.getElementById('cycled') as any;
        for (let i = 0; i < count; i++) {
          el.remove();
          await vt.frames(1);
          document.body.append(el);
          await vt.converged(el);
        }
      }, n);
    await cycles(5);
    const before = await countersAfterGc(cdp);
    await cycles(45);
    const after = await countersAfterGc(cdp);
    const samples = await viewer().run(async () => {
      const el = document.getElementById('cycled') as any;
      const n = el.samples;
      el.remove();
      return n;
    });
    await cdp.detach();
    // A leak of one per cycle would add 45 of each.
    expect(after.listeners - before.listeners).toBeLessThanOrEqual(5);
    expect(after.nodes - before.nodes).toBeLessThanOrEqual(5);
    expect(samples).toBeGreaterThanOrEqual(1);
  });

  it('100 rapid resizes up to 5000 px keep the GPU memory within maxGpuBytes, and it renders at the end', async () => {
    const r = await viewer().run(async (vt) => {
      const el = vt.create(
        { src: 'procedural:blob?size=16', renderer: 'mip', backend: 'webgl2', panels: 'none', 'max-samples': '2' },
        'width:24px;height:24px;display:block',
      );
      el.maxGpuBytes = 64 * 2 ** 20; // read when the context opens (after this task)
      await vt.converged(el);
      let peak = 0;
      let largest = 0;
      for (let i = 0; i < 100; i++) {
        const px = i % 2 ? 5000 : 24 + 50 * i;
        el.style.width = `${px}px`;
        el.style.height = `${i % 3 ? px : 5000}px`;
        await vt.frames(1);
        const { width, height } = el.context.size;
        largest = Math.max(largest, width * height);
        peak = Math.max(peak, el.context.gpuBytes().total);
      }
      el.style.width = el.style.height = '5000px';
      await vt.frames(4);
      await el.whenSettled();
      el.maxSamples = 3;
      await vt.converged(el);
      peak = Math.max(peak, el.context.gpuBytes().total);
      const out = {
        peak,
        largest,
        maxPixels: el.context.maxRenderPixels,
        budget: el.context.maxGpuBytes,
        size: el.context.size,
        samples: el.samples,
        errors: el.__events.filter((e: any) => e.type === 'error'),
      };
      el.remove();
      return out;
    });
    expect(r.budget).toBe(64 * 2 ** 20);
    expect(r.peak).toBeLessThanOrEqual(r.budget);
    expect(r.largest).toBeLessThanOrEqual(r.maxPixels);
    expect(r.size.width).toBe(r.size.height); // the aspect is kept
    expect(r.samples).toBeGreaterThanOrEqual(3);
    expect(r.errors).toEqual([]);
    expect(viewer().errors).toEqual([]);
  });

  it('3000×3000 px with resolution-scale=4 on WebGPU renders clamped to the memory budget, with no console error', async () => {
    const r = await viewer().run(async (vt) => {
      const el = vt.create(
        {
          src: 'procedural:blob?size=16',
          renderer: 'mip',
          backend: 'webgpu',
          panels: 'none',
          'max-samples': '1',
          'resolution-scale': '4',
        },
        'width:3000px;height:3000px;display:block',
      );
      await vt.converged(el, 180_000);
      const out = {
        kind: el.context.backend.kind,
        size: el.context.size,
        maxPixels: el.context.maxRenderPixels,
        total: el.context.gpuBytes().total,
        budget: el.context.maxGpuBytes,
        samples: el.samples,
        errors: el.__events.filter((e: any) => e.type === 'error'),
      };
      el.remove();
      return out;
    });
    expect(r.kind).toBe('webgpu');
    expect(r.size.width * r.size.height).toBeLessThanOrEqual(r.maxPixels);
    expect(r.size.width).toBeLessThan(12000);
    expect(r.total).toBeLessThanOrEqual(r.budget);
    expect(r.samples).toBeGreaterThanOrEqual(1);
    expect(r.errors).toEqual([]);
    expect(viewer().errors).toEqual([]);
  });

  it('an attribute error banner goes once a later valid value renders', async () => {
    const r = await viewer().run(async (vt) => {
      const el = vt.create({
        src: 'procedural:blob?size=16',
        renderer: 'mip',
        backend: 'webgl2',
        panels: 'none',
        'max-samples': '1',
      });
      await vt.converged(el);
      const error = vt.next(el, 'error', 20_000);
      el.setAttribute('camera', '{"position":[0,0,"x"]}');
      await error;
      await el.updateComplete;
      const shownAfterBad = vt.shadowText(el, '.error p');
      el.setAttribute('camera', '{"position":[0,0,2.5],"target":[0,0,0]}');
      await el.whenSettled();
      await vt.converged(el);
      await el.updateComplete;
      const shownAfterGood = vt.shadowText(el, '.error p');
      // And the same for exposure: bad, then good.
      const error2 = vt.next(el, 'error', 20_000);
      el.setAttribute('exposure', 'abc');
      await error2;
      await el.updateComplete;
      const shownAfterBadExposure = vt.shadowText(el, '.error p');
      el.setAttribute('exposure', '0.5');
      await el.whenSettled();
      await el.updateComplete;
      const out = {
        shownAfterBad,
        shownAfterGood,
        shownAfterBadExposure,
        shownAfterGoodExposure: vt.shadowText(el, '.error p'),
      };
      el.remove();
      return out;
    });
    expect(r.shownAfterBad).toMatch(/camera/);
    expect(r.shownAfterGood).toBeNull();
    expect(r.shownAfterBadExposure).toMatch(/exposure/);
    expect(r.shownAfterGoodExposure).toBeNull();
  });
});

describe('<vpt-viewer> error readouts', () => {
  it("MCRT: the Progress panel's Est. error agrees with the stats line and never says n/a", async () => {
    const r = await viewer().run(async (vt) => {
      const el = vt.create(
        {
          src: 'procedural:blob?size=16',
          renderer: 'mcrt',
          backend: 'webgl2',
          panels: 'stats',
          'max-samples': '6',
          'resolution-scale': '0.25',
        },
        // Wide enough for the sidebar (panel width + 320 px), so the Progress panel shows.
        'width:700px;height:160px;display:block',
      );
      const panelTexts: string[] = [];
      el.addEventListener('vpt-progress', async () => {
        await el.updateComplete;
        panelTexts.push(vt.shadowText(el, '[data-stat="error"]') ?? '');
      });
      await vt.converged(el);
      await new Promise((res) => setTimeout(res, 1000)); // an estimate that lands after the last batch
      await el.updateComplete;
      const out = {
        panelTexts,
        panel: vt.shadowText(el, '[data-stat="error"]'),
        line: vt.shadowText(el, '.stats-line'),
        error: el.stats?.error ?? null,
      };
      el.remove();
      return out;
    });
    expect(r.panelTexts.length).toBeGreaterThan(0);
    expect(r.panelTexts.filter((t) => t === '' || /n\/a/.test(t))).toEqual([]);
    expect(r.error).not.toBeNull();
    const percent = (100 * r.error!).toFixed(1);
    expect(r.line).toContain(`err ${percent}%`);
    expect(r.panel).toBe(`${(100 * r.error!).toFixed(2)} %`);
  });
});
