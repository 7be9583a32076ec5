import { readFileSync, writeFileSync } from 'node:fs';
import { describe, expect, it } from 'vitest';
import { HEAD_SIDECAR, ROOT, useViewerPage } from './helpers/viewer-page.js';

/**
 * The slice panes and the 3D view together (docs/architecture.md, "Viewer and gallery"):
 * `crosshair-3d="slice" | "clip"` moves the 3D view's slice plane or a clip plane with the
 * crosshair; the panes honour `clip`; the panes take the page's WebGL 2 context slots; and a
 * `load()` called before the element's first update is kept.
 *
 * The bundled head's axes are PIR; its axial pane cuts y, coronal x, sagittal z (see
 * tests/viewer-layouts.test.ts for the derivation).
 */
const viewer = useViewerPage();
const HEAD = readFileSync(`${ROOT}${HEAD_SIDECAR.replace(/\.json$/, '.raw')}`);
const headVoxel = (x: number, y: number, z: number) => HEAD[x + 128 * (y + 128 * z)];
const HEAD_ATTRS = { src: HEAD_SIDECAR, backend: 'webgl2', panels: 'none', 'max-samples': '2' };
/** The head's box: 128 × 128 × 84 voxels of equal spacing, longest side 1. */
const BOX_SIZE = [1, 1, 84 / 128];

type Rect = { left: number; top: number; width: number; height: number };

async function createFull(attrs: Record<string, string>): Promise<void> {
  await viewer().run(async (vt, attrs) => {
    document.body.style.margin = '0';
    document.querySelectorAll('vpt-viewer').forEach((e) => e.remove());
    const el = vt.create(attrs, 'width:100%;height:100vh');
    (window as any).__el = el;
    await vt.converged(el);
    for (let t = 0; t < 600; t++) {
      if (['axial', 'coronal', 'sagittal'].every((n) => (el.paneContext(n)?.stats.iterations ?? 0) >= 1)) return;
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
const at = (r: Rect, fx: number, fy: number) => ({ x: r.left + fx * r.width, y: r.top + fy * r.height });

/** The 3D view's scene (its RenderContext's), the crosshair, and a read of its HDR image. */
async function viewState() {
  return viewer().run(async (vt) => {
    const el = (window as any).__el;
    await el.updateComplete;
    await vt.converged(el);
    const scene = el.context.getScene();
    return {
      crosshair: el.crosshair,
      window: el.sliceWindow,
      slicePlane: scene.slicePlane ?? null,
      clip: scene.clip ?? null,
      hdr: Array.from((await el.context.readHDR()) as Float32Array),
      paneClips: ['axial', 'coronal', 'sagittal'].map((n) => el.paneContext(n).getScene().clip ?? null),
      errors: el.__events.filter((e: { type: string }) => e.type === 'error'),
    };
  });
}

function maxDiff(a: number[], b: number[]): number {
  let m = 0;
  for (let i = 0; i < a.length; i++) m = Math.max(m, Math.abs(a[i] - b[i]));
  return m;
}

describe('<vpt-viewer layout="quad"> crosshair-3d', () => {
  it('"slice": a click on the coronal pane moves the axial plane, and with it the 3D view\'s slice plane', async () => {
    const vp = viewer();
    await vp.page.setViewport({ width: 1280, height: 800, deviceScaleFactor: 1 });
    await createFull({ ...HEAD_ATTRS, layout: 'quad', 'crosshair-3d': 'slice', 'crosshair-pane': 'axial' });
    const before = await viewState();
    expect(before.errors).toEqual([]);
    // At load: the axial plane through the crosshair's y, windowed as the panes.
    expect(before.slicePlane).toEqual({ axis: 'y', index: before.crosshair[1], window: before.window });
    // Coronal cuts x; its screen's vertical runs along y from the top (S) down: click at y = 30.
    const coronal = await stageRect('coronal');
    const p = at(coronal, 0.5, 30.5 / 128);
    await vp.page.mouse.click(p.x, p.y);
    const after = await viewState();
    writeFileSync('/tmp/viewer-crosshair-3d-slice.png', await vp.page.screenshot({ type: 'png' }));
    expect(after.crosshair[1]).toBe(30);
    expect(after.slicePlane).toEqual({ axis: 'y', index: 30, window: after.window });
    // The plane moved in the image.
    expect(maxDiff(before.hdr, after.hdr)).toBeGreaterThan(0.05);
    // The wheel on the axial pane moves it one layer per notch, in the 3D view too.
    const axial = await stageRect('axial');
    const c = at(axial, 0.5, 0.5);
    await vp.page.mouse.move(c.x, c.y);
    await vp.page.mouse.wheel({ deltaY: 100 });
    const wheeled = await viewState();
    expect(wheeled.slicePlane).toMatchObject({ axis: 'y', index: 31 });
    expect(wheeled.errors).toEqual([]);
  });

  it("\"clip\": a clip plane at the followed pane's layer, after the clip attribute's own; the panes keep the attribute's clip only", async () => {
    const vp = viewer();
    await vp.page.setViewport({ width: 1280, height: 800, deviceScaleFactor: 1 });
    const own = { planes: [{ normal: [-1, 0, 0], offset: 0.45 }] };
    await createFull({
      ...HEAD_ATTRS,
      layout: 'quad',
      'crosshair-3d': 'clip',
      'crosshair-pane': 'sagittal',
      clip: JSON.stringify(own),
    });
    const axialStage = await stageRect('axial');
    // Axial: horizontal z from 83 (left) to 0; click at z = 20.
    const p = at(axialStage, 1 - 20.5 / 84, 0.5);
    await vp.page.mouse.click(p.x, p.y);
    const r = await viewState();
    expect(r.crosshair[2]).toBe(20);
    // Sagittal cuts z: the plane removes z above the centre of layer 20 (box z from -42/128).
    const offset = -BOX_SIZE[2] / 2 + ((20 + 0.5) * BOX_SIZE[2]) / 84;
    expect(r.clip.planes).toHaveLength(2);
    expect(r.clip.planes[0]).toEqual(own.planes[0]);
    expect(r.clip.planes[1].normal).toEqual([0, 0, 1]);
    expect(r.clip.planes[1].offset).toBeCloseTo(offset, 12);
    for (const c of r.paneClips) expect(c).toEqual(own);
  });
});

describe('slice panes honour clip', () => {
  it('the axial pane is cut where the clip removes the plane and is the windowed voxels elsewhere', async () => {
    const vp = viewer();
    await vp.page.setViewport({ width: 1280, height: 800, deviceScaleFactor: 1 });
    // Removes z > 0 (the box's z runs from -42/128 to 42/128: layers 42 and up).
    await createFull({
      ...HEAD_ATTRS,
      layout: 'slices',
      clip: JSON.stringify({ planes: [{ normal: [0, 0, 1], offset: 0 }] }),
    });
    const r = await vp.run(async () => {
      const el = (window as any).__el;
      el.sliceWindow = [90, 180];
      await el.updateComplete;
      const ctx = el.paneContext('axial');
      return { size: ctx.size, hdr: Array.from((await ctx.readHDR()) as Float32Array), crosshair: el.crosshair };
    });
    // The axial image: columns x (128), rows z (84), fitted; y at the crosshair.
    const { width: W, height: H } = r.size;
    const y = r.crosshair[1];
    const w = (d: number) => Math.min(1, Math.max(0, (d - 0) / 180));
    let kept = 0,
      cut = 0,
      worst = 0;
    for (let j = 0; j < H; j++) {
      const zc = ((j + 0.5) / H) * 84;
      if (Math.abs(zc - 42) < 0.01) continue;
      for (let i = 0; i < W; i++) {
        const xc = ((i + 0.5) / W) * 128;
        if (Math.abs(xc - Math.round(xc)) < 1e-3 || Math.abs(zc - Math.round(zc)) < 1e-3) continue;
        const px = 4 * (i + W * j);
        if (zc > 42) {
          cut++;
          expect(r.hdr[px + 3]).toBe(0);
        } else {
          kept++;
          worst = Math.max(worst, Math.abs(r.hdr[px] - w(headVoxel(Math.floor(xc), y, Math.floor(zc)))));
        }
      }
    }
    expect(kept).toBeGreaterThan(1000);
    expect(cut).toBeGreaterThan(1000);
    expect(worst).toBeLessThan(1e-6);
  });
});

describe("slice panes take the page's WebGL 2 context slots", () => {
  it("four quad viewers (16 contexts) on one page: at most 12 open, none of them lost, the last viewer's panes drawn", async () => {
    const vp = viewer();
    await vp.page.setViewport({ width: 1280, height: 800, deviceScaleFactor: 1 });
    const r = await vp.run(
      async (vt, attrs) => {
        document.body.style.margin = '0';
        document.querySelectorAll('vpt-viewer').forEach((e) => e.remove());
        const els: any[] = [];
        for (let i = 0; i < 4; i++) {
          const el = vt.create(
            { ...attrs, layout: 'quad', src: 'procedural:blob?size=16' },
            'width:600px;height:400px',
          );
          els.push(el);
          await vt.converged(el);
          for (let t = 0; t < 600; t++) {
            if (['axial', 'coronal', 'sagittal'].every((n) => (el.paneContext(n)?.stats.iterations ?? 0) >= 1)) break;
            await vt.frames(2);
          }
        }
        await vt.frames(10);
        // The contexts open now; one the browser took away (past its own cap) reads as lost.
        const contexts = els.flatMap((el) =>
          [el.context, ...['axial', 'coronal', 'sagittal'].map((p) => el.paneContext(p))].filter((c) => c),
        );
        const live = contexts.length;
        const lost = contexts.filter((c) => c.backend.isLost).length;
        const last = els[3];
        const lastPanes = ['axial', 'coronal', 'sagittal'].map((p) => last.paneContext(p)?.stats.iterations ?? 0);
        const errors = els.flatMap((el) => el.__events.filter((e: { type: string }) => e.type === 'error'));
        els.forEach((el) => el.remove());
        return { live, lost, lastPanes, errors };
      },
      { backend: 'webgl2', panels: 'none', 'max-samples': '1' },
    );
    expect(r.errors).toEqual([]);
    expect(r.lost).toBe(0);
    expect(r.live).toBeLessThanOrEqual(12);
    expect(r.live).toBeGreaterThanOrEqual(8);
    expect(r.lastPanes.every((n: number) => n >= 1)).toBe(true);
  });
});

describe('load() before the first update', () => {
  it('el.load(file) right after the element is created loads the file', async () => {
    // A 4 × 3 × 2 uint8 NIfTI-1: voxel value i + 4 j + 12 k + 1.
    const dims = [4, 3, 2];
    const buf = new ArrayBuffer(352 + 24);
    const dv = new DataView(buf);
    dv.setInt32(0, 348, true);
    [3, ...dims, 1, 1, 1, 1].forEach((d, i) => dv.setInt16(40 + 2 * i, d, true));
    dv.setInt16(70, 2, true); // uint8
    dv.setInt16(72, 8, true);
    [1, 1, 1, 1, 0, 0, 0, 0].forEach((d, i) => dv.setFloat32(76 + 4 * i, d, true));
    dv.setFloat32(108, 352, true);
    [0x6e, 0x2b, 0x31, 0].forEach((c, i) => dv.setUint8(344 + i, c));
    for (let v = 0; v < 24; v++) dv.setUint8(352 + v, v + 1);
    const bytes = Array.from(new Uint8Array(buf));
    const r = await viewer().run(async (vt, bytes) => {
      document.querySelectorAll('vpt-viewer').forEach((e) => e.remove());
      const el = vt.create({ backend: 'webgl2', panels: 'none', 'max-samples': '1' });
      const updatedBefore = el.hasUpdated;
      await el.load(new File([new Uint8Array(bytes)], 'tiny.nii'));
      await vt.converged(el);
      const v = el.loadedVolume;
      const out = {
        updatedBefore,
        dims: v ? Array.from(v.dims) : null,
        data: v ? Array.from(v.data as Uint8Array) : null,
        samples: el.samples,
        errors: el.__events.filter((e: { type: string }) => e.type === 'error'),
      };
      el.remove();
      return out;
    }, bytes);
    expect(r.updatedBefore).toBe(false);
    expect(r.errors).toEqual([]);
    expect(r.dims).toEqual(dims);
    expect(r.data).toEqual(Array.from({ length: 24 }, (_, i) => i + 1));
    expect(r.samples).toBe(1);
  });
});
