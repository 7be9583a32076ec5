import { readFileSync, writeFileSync } from 'node:fs';
import { describe, expect, it } from 'vitest';
import { HEAD_SIDECAR, installViewerHelpers, ROOT, useViewerPage } from './helpers/viewer-page.js';

/**
 * `<vpt-viewer layout="slices" | "quad">` (docs/architecture.md, "Viewer layouts"): axial,
 * coronal and sagittal panes drawn by the slice renderer, a linked crosshair (click, tap,
 * wheel), window/level by right-drag in data units, the value probe and the orientation
 * labels, on a desktop and a phone viewport.
 *
 * The bundled head's axes are PIR (x toward the back, y toward the neck, z toward the right),
 * so, derived by hand from the radiological convention: axial cuts y, its screen's horizontal
 * runs along z from right (patient's right, R, on the left) and its vertical along x (face, A,
 * on top); coronal cuts x (horizontal z reversed, vertical y: S on top); sagittal cuts z
 * (horizontal x: A on the left, vertical y).
 */
const viewer = useViewerPage();
const HEAD = readFileSync(`${ROOT}${HEAD_SIDECAR.replace(/\.json$/, '.raw')}`);
const headVoxel = (x: number, y: number, z: number) => HEAD[x + 128 * (y + 128 * z)];
const PANES = ['axial', 'coronal', 'sagittal'] as const;

type Rect = { left: number; top: number; width: number; height: number };

/** A <vpt-viewer> filling the page (window.__el), its panes drawn; returns once they are. */
async function createFull(attrs: Record<string, string>): Promise<void> {
  await viewer().run(async (vt, attrs) => {
    document.body.style.margin = '0';
    document.querySelectorAll('vpt-viewer').forEach((e) => e.remove());
    const el = vt.create(attrs, 'width:100%;height:100vh');
    el.__changes = [];
    el.addEventListener('vpt-change', (e: CustomEvent) => el.__changes.push(e.detail));
    (window as any).__el = el;
    await vt.converged(el);
    for (let t = 0; t < 600; t++) {
      const names = ['axial', 'coronal', 'sagittal'];
      if (names.every((n) => (el.paneContext(n)?.stats.iterations ?? 0) >= 1)) return;
      await vt.frames(2);
    }
    throw new Error('the slice panes were not drawn');
  }, attrs);
}

async function stageRect(name: string): Promise<Rect> {
  return viewer().page.evaluate((name) => {
    const r = (window as any).__el.shadowRoot.querySelector(`[data-stage="${name}"]`).getBoundingClientRect();
    return { left: r.left, top: r.top, width: r.width, height: r.height };
  }, name);
}

/** Page coordinates of a point of a stage, (fx, fy) from its top-left corner. */
const at = (r: Rect, fx: number, fy: number) => ({ x: r.left + fx * r.width, y: r.top + fy * r.height });

async function screenshot(name: string): Promise<void> {
  const png = await viewer().page.screenshot({ type: 'png' });
  writeFileSync(`/tmp/${name}.png`, png);
}

/**
 * The pane's HDR image (top row first) against the head's voxels: pixel (i, j) of a W × H
 * image holds the voxel at column ⌊(i + ½)/W · n⌋ and row ⌊(j + ½)/H · m⌋ (nearest, fitted),
 * through the window. At a boundary float rounding may pick the neighbour: either is accepted.
 */
function worstPaneError(
  hdr: number[],
  size: { width: number; height: number },
  voxel: (col: number, row: number) => number,
  dims: [number, number],
  window: [number, number],
): number {
  const w = (d: number) => Math.min(1, Math.max(0, (d - (window[0] - window[1] / 2)) / window[1]));
  const cands = (p: number, n: number, N: number) => {
    const s = ((p + 0.5) / N) * n;
    return [...new Set([Math.floor(s - 1e-4), Math.floor(s + 1e-4)])].filter((c) => c >= 0 && c < n);
  };
  let worst = 0;
  for (let j = 0; j < size.height; j++)
    for (let i = 0; i < size.width; i++) {
      const got = hdr[4 * (i + size.width * j)];
      let best = Infinity;
      for (const c of cands(i, dims[0], size.width))
        for (const r of cands(j, dims[1], size.height)) best = Math.min(best, Math.abs(got - w(voxel(c, r))));
      worst = Math.max(worst, best);
    }
  return worst;
}

const HEAD_ATTRS = { src: HEAD_SIDECAR, backend: 'webgl2', panels: 'none', 'max-samples': '2' };

describe('<vpt-viewer layout>', () => {
  it('quad at 1280×800: three slice panes and the 3D view, slice images are the windowed voxels, labels, no console errors', async () => {
    const vp = viewer();
    await vp.page.setViewport({ width: 1280, height: 800, deviceScaleFactor: 1 });
    const errorsBefore = vp.errors.length;
    await createFull({ ...HEAD_ATTRS, layout: 'quad' });
    const r = await vp.run(async () => {
      const el = (window as any).__el;
      el.sliceWindow = [90, 180];
      await el.updateComplete;
      const root = el.shadowRoot;
      const rect = (s: string) => {
        const b = root.querySelector(s).getBoundingClientRect();
        return { left: b.left, top: b.top, width: b.width, height: b.height };
      };
      const panes: Record<string, unknown> = {};
      for (const n of ['axial', 'coronal', 'sagittal']) {
        const ctx = el.paneContext(n);
        panes[n] = {
          renderer: ctx.renderer.name,
          params: ctx.renderer.getParams(),
          size: ctx.size,
          hdr: n === 'axial' ? Array.from(await ctx.readHDR()) : [],
          labels: Object.fromEntries(
            [...root.querySelectorAll(`[data-stage="${n}"] .orient`)].map((s: any) => [s.dataset.edge, s.textContent]),
          ),
          rect: rect(`[data-pane="${n}"]`),
        };
      }
      return {
        panes,
        view: rect('.view'),
        mainRenderer: el.context.renderer.name,
        mainSamples: el.samples,
        crosshair: el.crosshair,
        errors: el.__events.filter((e: { type: string }) => e.type === 'error'),
        scrollWidth: document.documentElement.scrollWidth,
        innerWidth: window.innerWidth,
      };
    });
    await screenshot('layouts-quad-1280');
    expect(r.errors).toEqual([]);
    expect(vp.errors.slice(errorsBefore)).toEqual([]);
    expect(r.mainRenderer).toBe('eam'); // the 3D view keeps its own renderer
    expect(r.mainSamples).toBe(2);
    expect(r.crosshair).toEqual([64, 64, 42]);
    const panes = r.panes as Record<string, any>;
    // Quad: axial, coronal above; sagittal and the 3D view below, each a quarter.
    expect(panes.axial.rect.top).toBe(panes.coronal.rect.top);
    expect(panes.sagittal.rect.top).toBeGreaterThan(panes.axial.rect.top + 300);
    expect(r.view.top).toBe(panes.sagittal.rect.top);
    expect(r.view.left).toBeGreaterThan(600);
    expect(r.view.width).toBeGreaterThan(600);
    for (const n of PANES) {
      expect(panes[n].renderer).toBe('slice');
      expect(panes[n].params).toMatchObject({ fit: true, window: [90, 180] });
    }
    expect(panes.axial.params).toMatchObject({ axis: 'y', index: 64 });
    expect(panes.coronal.params).toMatchObject({ axis: 'x', index: 64 });
    expect(panes.sagittal.params).toMatchObject({ axis: 'z', index: 42 });
    expect(panes.axial.labels).toEqual({ top: 'A', bottom: 'P', left: 'R', right: 'L' });
    expect(panes.coronal.labels).toEqual({ top: 'S', bottom: 'I', left: 'R', right: 'L' });
    expect(panes.sagittal.labels).toEqual({ top: 'S', bottom: 'I', left: 'A', right: 'P' });
    // The axial pane's image (the slice renderer's y = 64 plane: columns x, rows z) is the windowed voxels.
    const worst = worstPaneError(
      panes.axial.hdr,
      panes.axial.size,
      (x, z) => headVoxel(x, 64, z),
      [128, 84],
      [90, 180],
    );
    expect(worst).toBeLessThan(1e-6);
    expect(r.scrollWidth).toBeLessThanOrEqual(r.innerWidth);
  });

  it('the default layout is the 3D view alone; an unknown layout is a typed error and stays 3d', async () => {
    const r = await viewer().run(async (vt) => {
      const el = vt.blob('mip', 1);
      await vt.converged(el);
      const before = el.shadowRoot.querySelectorAll('.pane').length;
      el.setAttribute('layout', 'triple');
      await el.updateComplete;
      const out = {
        before,
        after: el.shadowRoot.querySelectorAll('.pane').length,
        layout: el.layout,
        pane: el.paneContext('axial'),
        errors: el.__events.filter((e: { type: string }) => e.type === 'error').map((e: any) => e.message),
      };
      el.remove();
      return out;
    });
    expect(r.before).toBe(0);
    expect(r.after).toBe(0);
    expect(r.layout).toBe('3d');
    expect(r.pane).toBeNull();
    expect(r.errors).toHaveLength(1);
    expect(r.errors[0]).toMatch(/layout: "triple"/);
  });

  it('crosshair: a click moves the other panes, the wheel one voxel per notch, right-drag sets the window; typed vpt-change', async () => {
    const vp = viewer();
    await vp.page.setViewport({ width: 1280, height: 800, deviceScaleFactor: 1 });
    await createFull({ ...HEAD_ATTRS, layout: 'slices' });
    await vp.run(async () => {
      const el = (window as any).__el;
      el.sliceWindow = [100, 50];
      await el.updateComplete;
    });
    // Axial: horizontal z from 83 (left) to 0, vertical x from 0 (top) down.
    const axial = await stageRect('axial');
    const p = at(axial, 1 - 20.5 / 84, 40.5 / 128);
    await vp.page.mouse.click(p.x, p.y);
    const afterClick = await vp.run(async () => {
      const el = (window as any).__el;
      await el.updateComplete;
      return {
        crosshair: el.crosshair,
        coronal: el.paneContext('coronal').renderer.getParams().index,
        sagittal: el.paneContext('sagittal').renderer.getParams().index,
        axial: el.paneContext('axial').renderer.getParams().index,
        lines: [...el.shadowRoot.querySelectorAll('[data-stage="axial"] .cross-v, [data-stage="axial"] .cross-h')].map(
          (d: any) => d.getAttribute('style'),
        ),
      };
    });
    expect(afterClick.crosshair).toEqual([40, 64, 20]);
    expect(afterClick.coronal).toBe(40);
    expect(afterClick.sagittal).toBe(20);
    expect(afterClick.axial).toBe(64);
    // The crosshair lines cross at the clicked voxel's centre.
    expect(afterClick.lines).toEqual([
      `left:${(100 * (1 - 20.5 / 84)).toFixed(3)}%`,
      `top:${(100 * (40.5 / 128)).toFixed(3)}%`,
    ]);
    // Three notches down on the axial pane: three voxels along y.
    for (let i = 0; i < 3; i++) await vp.page.mouse.wheel({ deltaY: 100 });
    // Right-drag on the sagittal pane: a quarter of its width to the right, a tenth of its height down.
    const sag = await stageRect('sagittal');
    const a = at(sag, 0.5, 0.5);
    const dx = Math.round(0.25 * sag.width),
      dy = Math.round(0.1 * sag.height);
    await vp.page.mouse.move(a.x, a.y);
    await vp.page.mouse.down({ button: 'right' });
    await vp.page.mouse.move(a.x + dx, a.y + dy);
    await vp.page.mouse.up({ button: 'right' });
    const r = await vp.run(async () => {
      const el = (window as any).__el;
      await el.updateComplete;
      const ctx = el.paneContext('axial');
      return {
        crosshair: el.crosshair,
        window: el.sliceWindow,
        axialIndex: ctx.renderer.getParams().index,
        size: ctx.size,
        hdr: Array.from(await ctx.readHDR()),
        changes: el.__changes,
      };
    });
    expect(r.crosshair).toEqual([40, 67, 20]);
    expect(r.axialIndex).toBe(67);
    let lo = 255,
      hi = 0;
    for (const v of HEAD) {
      lo = Math.min(lo, v);
      hi = Math.max(hi, v);
    }
    const range = hi - lo;
    expect(r.window![0]).toBeCloseTo(100 + (dy / sag.height) * range, 6);
    expect(r.window![1]).toBeCloseTo(50 + (dx / sag.width) * range, 6);
    // Typed events: the crosshair after the click and after each notch, then the window.
    const changes = r.changes as { property: string; value: number[] }[];
    expect(changes.filter((c) => c.property === 'crosshair').map((c) => c.value)).toEqual([
      [40, 64, 20],
      [40, 65, 20],
      [40, 66, 20],
      [40, 67, 20],
    ]);
    expect(changes.at(-1)).toEqual({ property: 'window', value: r.window });
    const worst = worstPaneError(r.hdr as number[], r.size, (x, z) => headVoxel(x, 67, z), [128, 84], r.window!);
    expect(worst).toBeLessThan(1e-6);
    await screenshot('layouts-slices-1280');
  });

  it('the probe shows the raw data value in data units and the voxel index (a scaled int16 NIfTI)', async () => {
    const vp = viewer();
    await vp.page.setViewport({ width: 1280, height: 800, deviceScaleFactor: 1 });
    // 6 × 5 × 4 int16 voxels raw = i + 10 j + 100 k − 50, stored with scl_slope 2 and scl_inter −1000:
    // data value 2·raw − 1000. The sform puts x toward L, y toward P, z toward S.
    const dims = [6, 5, 4];
    const raw = (i: number, j: number, k: number) => i + 10 * j + 100 * k - 50;
    const buf = new ArrayBuffer(352 + 2 * 6 * 5 * 4);
    const dv = new DataView(buf);
    dv.setInt32(0, 348, true);
    [3, ...dims, 1, 1, 1, 1].forEach((d, i) => dv.setInt16(40 + 2 * i, d, true));
    dv.setInt16(70, 4, true); // int16
    dv.setInt16(72, 16, true);
    [1, 1, 1, 1, 0, 0, 0, 0].forEach((d, i) => dv.setFloat32(76 + 4 * i, d, true));
    dv.setFloat32(108, 352, true);
    dv.setFloat32(112, 2, true);
    dv.setFloat32(116, -1000, true);
    dv.setUint8(123, 2);
    dv.setInt16(254, 1, true); // sform_code
    [-1, 0, 0, 0, 0, -1, 0, 0, 0, 0, 1, 0].forEach((d, i) => dv.setFloat32(280 + 4 * i, d, true));
    [0x6e, 0x2b, 0x31, 0].forEach((c, i) => dv.setUint8(344 + i, c));
    for (let k = 0; k < 4; k++)
      for (let j = 0; j < 5; j++)
        for (let i = 0; i < 6; i++) dv.setInt16(352 + 2 * (i + 6 * (j + 5 * k)), raw(i, j, k), true);
    const bytes = Array.from(new Uint8Array(buf));
    await vp.run(async (vt, bytes) => {
      document.body.style.margin = '0';
      document.querySelectorAll('vpt-viewer').forEach((e) => e.remove());
      const el = vt.create(
        { backend: 'webgl2', panels: 'none', 'max-samples': '1', layout: 'slices' },
        'width:100%;height:100vh',
      );
      (window as any).__el = el;
      await el.load(new File([new Uint8Array(bytes)], 'probe.nii'));
      await vt.converged(el);
      for (let t = 0; t < 600; t++) {
        if (['axial', 'coronal', 'sagittal'].every((n) => (el.paneContext(n)?.stats.iterations ?? 0) >= 1)) return;
        await vt.frames(2);
      }
      throw new Error('the slice panes were not drawn');
    }, bytes);
    // Axial cuts z (k = 2, the middle); x runs toward L: to the right, unmirrored; y toward P: down.
    const axial = await stageRect('axial');
    const p = at(axial, 4.5 / 6, 1.5 / 5);
    await vp.page.mouse.move(p.x, p.y);
    const r = await vp.run(async () => {
      const el = (window as any).__el;
      await el.updateComplete;
      const root = el.shadowRoot;
      return {
        reading: el.probeReading,
        text: root.querySelector('[data-probe="axial"]')?.textContent,
        direct: el.probe([5, 4, 3]),
        type: el.loadedVolume.type,
        labels: Object.fromEntries(
          [...root.querySelectorAll('[data-stage="axial"] .orient')].map((s: any) => [s.dataset.edge, s.textContent]),
        ),
        errors: el.__events.filter((e: { type: string }) => e.type === 'error'),
      };
    });
    expect(r.errors).toEqual([]);
    expect(r.labels).toEqual({ top: 'A', bottom: 'P', left: 'R', right: 'L' });
    expect(r.reading).toEqual({ pane: 'axial', index: [4, 1, 2], value: 2 * raw(4, 1, 2) - 1000 });
    expect(r.text).toContain(`${2 * raw(4, 1, 2) - 1000}`);
    expect(r.text).toContain('[4, 1, 2]');
    expect(r.direct).toBe(2 * raw(5, 4, 3) - 1000);
  });

  it('phone 390×844: panes stack, a tap moves the crosshair, no horizontal overflow, no console errors (slices and quad)', async () => {
    const vp = viewer();
    // Emulating a phone (touch) reloads the page: wait for it and install the helpers again.
    await vp.page.setViewport({ width: 390, height: 844, deviceScaleFactor: 1, isMobile: true, hasTouch: true });
    await vp.page.waitForFunction(() => (window as any).__ready === true, { timeout: 60_000 });
    await vp.page.evaluate(installViewerHelpers);
    const errorsBefore = vp.errors.length;
    await createFull({ ...HEAD_ATTRS, layout: 'slices' });
    const rects = await Promise.all(PANES.map((n) => stageRect(n)));
    for (const rect of rects) {
      expect(rect.left).toBeGreaterThanOrEqual(0);
      expect(rect.left + rect.width).toBeLessThanOrEqual(390.5);
    }
    expect(rects[1].top).toBeGreaterThan(rects[0].top + rects[0].height - 1);
    expect(rects[2].top).toBeGreaterThan(rects[1].top + rects[1].height - 1);
    expect(rects[2].top + rects[2].height).toBeLessThanOrEqual(844.5);
    // Sagittal: horizontal x (A on the left, unmirrored), vertical y (top down).
    const p = at(rects[2], 30.5 / 128, 70.5 / 128);
    await vp.page.touchscreen.tap(p.x, p.y);
    const r = await vp.run(async () => {
      const el = (window as any).__el;
      await el.updateComplete;
      return {
        crosshair: el.crosshair,
        axial: el.paneContext('axial').renderer.getParams().index,
        scrollWidth: document.documentElement.scrollWidth,
        innerWidth: window.innerWidth,
      };
    });
    await screenshot('layouts-slices-phone');
    expect(r.crosshair).toEqual([30, 70, 42]);
    expect(r.axial).toBe(70);
    expect(r.scrollWidth).toBeLessThanOrEqual(r.innerWidth);

    await createFull({ ...HEAD_ATTRS, layout: 'quad' });
    const q = await vp.run(async () => {
      const el = (window as any).__el;
      const v = el.shadowRoot.querySelector('.view').getBoundingClientRect();
      return {
        view: { top: v.top, width: v.width, height: v.height },
        scrollWidth: document.documentElement.scrollWidth,
        innerWidth: window.innerWidth,
        errors: el.__events.filter((e: { type: string }) => e.type === 'error'),
      };
    });
    await screenshot('layouts-quad-phone');
    expect(q.errors).toEqual([]);
    expect(q.view.top).toBeGreaterThan(600); // the 3D view below the three stacked panes
    expect(q.view.width).toBeGreaterThan(380);
    expect(q.scrollWidth).toBeLessThanOrEqual(q.innerWidth);
    expect(vp.errors.slice(errorsBefore)).toEqual([]);
  });
});
