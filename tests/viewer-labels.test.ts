import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { afterAll, describe, expect, it } from 'vitest';
import { writeZarrFolder } from '../packages/loaders/test/zarr-fixtures.js';
import { useViewerPage } from './helpers/viewer-page.js';

// <vpt-viewer labels="…" > (labels-layer.ts): a label volume (NRRD with 3D Slicer's segment
// names) over a raw + sidecar image on the same grid. Hiding a label in the Labels panel gives
// the image of a label volume with that id set to 0, bit for bit; the hover readout names the
// label a pixel's ray meets first (an analytic geometry); a label volume on another grid is a
// typed error in the banner, the image still renders, and a valid one afterwards draws.
const viewer = useViewerPage();
const dir = fs.mkdtempSync(path.join(os.tmpdir(), 'vpt-viewer-labels-'));
afterAll(() => fs.rmSync(dir, { recursive: true, force: true }));

const N = 16;
/** The image: a ramp along x, so every pixel has some emission under the labels. */
function image(): Uint8Array {
  const v = new Uint8Array(N ** 3);
  for (let z = 0; z < N; z++)
    for (let y = 0; y < N; y++) for (let x = 0; x < N; x++) v[x + N * (y + N * z)] = 40 + 8 * x;
  return v;
}
/**
 * Labels: the box [4, 12) × [4, 10) × [4, 12) of voxels (not symmetric in y, so a flipped slice
 * shows), id 1 ("left") where x < 8, id 2 ("right") where x ≥ 8; `drop` set to 0.
 */
function labels(dims: [number, number, number], drop = 0): Uint8Array {
  const v = new Uint8Array(dims[0] * dims[1] * dims[2]);
  for (let z = 0; z < dims[2]; z++)
    for (let y = 0; y < dims[1]; y++)
      for (let x = 0; x < dims[0]; x++) {
        const inside = x >= 4 && x < 12 && y >= 4 && y < 10 && z >= 4 && z < 12;
        const id = inside ? (x < 8 ? 1 : 2) : 0;
        v[x + dims[0] * (y + dims[1] * z)] = id === drop ? 0 : id;
      }
  return v;
}
/** A raw NRRD (uint8, spacing 1) with 3D Slicer's segment keys. */
function nrrd(dims: [number, number, number], data: Uint8Array): Buffer {
  const header = [
    'NRRD0004',
    'type: uint8',
    'dimension: 3',
    `sizes: ${dims.join(' ')}`,
    'spacings: 1 1 1',
    'encoding: raw',
    'Segment0_Name:=left',
    'Segment0_LabelValue:=1',
    'Segment1_Name:=right',
    'Segment1_LabelValue:=2',
    '',
    '',
  ].join('\n');
  return Buffer.concat([Buffer.from(header, 'latin1'), Buffer.from(data)]);
}

fs.writeFileSync(path.join(dir, 'image.raw'), image());
fs.writeFileSync(
  path.join(dir, 'image.json'),
  JSON.stringify({ file: 'image.raw', dims: [N, N, N], type: 'uint8', spacing: [1, 1, 1] }),
);
fs.writeFileSync(path.join(dir, 'labels.nrrd'), nrrd([N, N, N], labels([N, N, N])));
fs.writeFileSync(path.join(dir, 'labels-no1.nrrd'), nrrd([N, N, N], labels([N, N, N], 1)));
fs.writeFileSync(path.join(dir, 'labels-half.nrrd'), nrrd([N, N, 8], labels([N, N, 8])));

// The camera looks down −z at the box (centred at 0, side 1) from z = 2, fovy 40°: the ray
// through film point (fx, 0.5) crosses x = 1.5·(2fx − 1)·tan 20° at the front face (z = 0.5)
// and 2.5·(…) at the back. fx = 0.35: x ∈ [−0.218, −0.164], voxel column 4–5, at y = 0 (row 8),
// inside the label box's left half (id 1) from z index 11; fx = 0.65: columns 10–11, id 2;
// fy = 0.02: y > 0.5 at the front face and beyond, outside the box.
const CAMERA = { position: [0, 0, 2], target: [0, 0, 0], up: [0, 1, 0], fovy: (40 * Math.PI) / 180 };

describe('<vpt-viewer labels>', () => {
  it('draws the labels, names them from the file, hides one from the panel as if its voxels were 0, and reports the hovered label', async () => {
    const base = viewer().server.mount(dir);
    const r = await viewer().run(
      async (vt, base: string, camera: unknown) => {
        const el = vt.create(
          {
            src: `${base}image.json`,
            renderer: 'eam',
            backend: 'webgl2',
            panels: 'labels',
            denoise: 'off',
            temporal: 'off',
            'max-samples': '3',
            camera: JSON.stringify(camera),
          },
          'width:40px;height:40px',
        );
        await vt.next(el, 'load');
        await vt.converged(el);
        const none = await vt.ldr(el);
        el.setAttribute('labels', `${base}labels.nrrd`);
        await el.whenSettled();
        await vt.converged(el);
        const all = await vt.ldr(el);
        const table = el.labelTable.map((e: { id: number; name?: string; visible?: boolean }) => [
          e.id,
          e.name,
          e.visible,
        ]);
        const size = { ...el.context.size };
        // Hover: pointer moves over the view at film points.
        const view = el.shadowRoot.querySelector('.view') as HTMLElement;
        const hovers: unknown[] = [];
        el.addEventListener('vpt-hover', (e: CustomEvent) => hovers.push(e.detail.label?.id ?? null));
        const at = (fx: number, fy: number) => {
          const rect = view.getBoundingClientRect();
          view.dispatchEvent(
            new PointerEvent('pointermove', {
              clientX: rect.left + fx * rect.width,
              clientY: rect.top + fy * rect.height,
              bubbles: true,
            }),
          );
          const h = el.hoveredLabel;
          const tip = el.shadowRoot.querySelector('[part=label-tip]') as HTMLElement | null;
          return { id: h?.id ?? null, name: h?.name ?? null, tip: tip && !tip.hidden ? tip.textContent : null };
        };
        const hoverLeft = at(0.35, 0.5);
        const hoverRight = at(0.65, 0.5);
        const hoverOut = at(0.5, 0.02);
        // The Labels panel (the overlay of a narrow element, opened by the toolbar button).
        (el.shadowRoot.querySelector('[part=panels-toggle]') as HTMLElement).click();
        await el.updateComplete;
        await vt.frames(2);
        const rows = [...el.shadowRoot.querySelectorAll('[data-label-id]')].map((n) =>
          (n as HTMLElement).textContent!.trim().replace(/\s+/g, ' '),
        );
        const changes: unknown[] = [];
        el.addEventListener('vpt-change', (e: CustomEvent) => changes.push(e.detail.property));
        const box = el.shadowRoot.querySelector('[data-label-id="1"] input[type=checkbox]') as HTMLInputElement;
        box.click();
        await el.whenSettled();
        await vt.converged(el);
        const hidden = await vt.ldr(el);
        const hoverHidden = at(0.35, 0.5);
        const hoverRightAgain = at(0.65, 0.5);
        // Visible again, then its opacity slider to 0 (drawn as hidden) and to 0.5 (between).
        box.click();
        await el.whenSettled();
        const slide = async (value: string) => {
          const range = el.shadowRoot.querySelector('[data-label-id="1"] input[type=range]') as HTMLInputElement;
          range.value = value;
          range.dispatchEvent(new Event('input', { bubbles: true }));
          await el.whenSettled();
          await vt.converged(el);
          return {
            image: await vt.ldr(el),
            opacity: el.labelTable.find((e: { id: number }) => e.id === 1).opacity,
            visible: el.labelTable.find((e: { id: number }) => e.id === 1).visible,
          };
        };
        const transparent = await slide('0');
        const half = await slide('0.5');
        el.setAttribute('labels', `${base}labels-no1.nrrd`);
        await el.whenSettled();
        await vt.converged(el);
        const removed = await vt.ldr(el);
        const errors = el.__events.filter((e: { type: string }) => e.type === 'error');
        el.remove();
        return {
          none,
          all,
          hidden,
          transparent,
          half,
          removed,
          table,
          size,
          hoverLeft,
          hoverRight,
          hoverOut,
          hoverHidden,
          hoverRightAgain,
          rows,
          changes,
          hovers,
          errors,
        };
      },
      base,
      CAMERA,
    );
    expect(r.errors).toEqual([]);
    expect(r.table).toEqual([
      [1, 'left', true],
      [2, 'right', true],
    ]);
    expect(r.rows).toEqual(['1 left', '2 right']);
    // The labels change the image; hiding label 1 changes it again; the same as id 1 set to 0, bit for bit.
    const differ = (a: number[], b: number[]) => a.some((x, i) => x !== b[i]);
    expect(differ(r.all, r.none)).toBe(true);
    expect(differ(r.hidden, r.all)).toBe(true);
    expect(r.hidden).toEqual(r.removed);
    expect(r.changes).toContain('labelTable');
    // The opacity slider: 0 draws label 1 as absent (bit for bit), 0.5 draws it between.
    expect(r.transparent.opacity).toBe(0);
    expect(r.transparent.visible).toBe(true);
    expect(r.transparent.image).toEqual(r.removed);
    expect(r.half.opacity).toBe(0.5);
    expect(differ(r.half.image, r.all)).toBe(true);
    expect(differ(r.half.image, r.removed)).toBe(true);
    // Hover (a square view, so the geometry above holds).
    expect(r.size.width).toBe(r.size.height);
    expect(r.hoverLeft).toEqual({ id: 1, name: 'left', tip: 'left' });
    expect(r.hoverRight).toEqual({ id: 2, name: 'right', tip: 'right' });
    expect(r.hoverOut).toEqual({ id: null, name: null, tip: null });
    // Label 1 hidden: the ray through its half meets no visible label.
    expect(r.hoverHidden.id).toBeNull();
    expect(r.hoverRightAgain.id).toBe(2);
    // vpt-hover fires on each change of label, the last when the next label file loads (nothing hovered then).
    expect(r.hovers).toEqual([1, 2, null, 2, null]);
    expect(viewer().errors).toEqual([]);
  });

  it('refuses a label volume on another grid (and a missing file) with a typed error, keeps rendering the image, then draws a valid one', async () => {
    const base = viewer().server.mount(dir);
    const r = await viewer().run(
      async (vt, base: string, camera: unknown) => {
        const attrs = {
          src: `${base}image.json`,
          renderer: 'eam',
          backend: 'webgl2',
          panels: 'none',
          denoise: 'off',
          temporal: 'off',
          'max-samples': '2',
          camera: JSON.stringify(camera),
        };
        const ref = vt.create(attrs);
        await vt.next(ref, 'load');
        await vt.converged(ref);
        const none = await vt.ldr(ref);
        ref.setAttribute('labels', `${base}labels.nrrd`);
        await ref.whenSettled();
        await vt.converged(ref);
        const withLabels = await vt.ldr(ref);
        ref.remove();

        const el = vt.create({ ...attrs, labels: `${base}labels-half.nrrd` });
        const error = await vt.next(el, 'error');
        await el.whenSettled();
        await vt.converged(el);
        const banner = vt.shadowText(el, '[part=error]');
        const mismatched = await vt.ldr(el);
        // A label file that is not there: a typed load error, the image as before.
        el.setAttribute('labels', `${base}missing.nrrd`);
        const missing = await vt.next(el, 'error');
        await el.whenSettled();
        await vt.converged(el);
        const missingImage = await vt.ldr(el);
        el.setAttribute('labels', `${base}labels.nrrd`);
        await el.whenSettled();
        await vt.converged(el);
        const fixed = await vt.ldr(el);
        const bannerAfter = vt.shadowText(el, '[part=error]');
        el.remove();
        return {
          none,
          withLabels,
          mismatched,
          fixed,
          banner,
          bannerAfter,
          error: { code: error.code, source: error.source, name: error.error?.name },
          missing: { code: missing.code, source: missing.source, reason: missing.error?.reason },
          missingImage,
        };
      },
      base,
      CAMERA,
    );
    expect(r.error).toMatchObject({ code: 'invalid-scene', source: 'labels' });
    expect(r.banner).toMatch(/16×16×8.*not the image's 16×16×16/);
    // The image renders as without labels; a valid label file then draws as it does on a fresh viewer.
    expect(r.mismatched).toEqual(r.none);
    expect(r.missing).toMatchObject({ code: 'load-failed', source: 'labels', reason: 'not-found' });
    expect(r.missingImage).toEqual(r.none);
    expect(r.fixed).toEqual(r.withLabels);
    expect((r.fixed as number[]).some((x, i) => x !== (r.none as number[])[i])).toBe(true);
    expect(r.bannerAfter).toBeNull();
  });

  it("loads an OME-Zarr image's label group (labels/<name>) with its image-label names and colours, at the level the image shows", async () => {
    // Two levels each (16³ and 8³): the element shows the image's 8³ level first, then 16³.
    const store = path.join(dir, 'image.ome.zarr');
    const two = { levels: 2 };
    await writeZarrFolder(store, { dims: [N, N, N], type: 'uint8', spacing: [1, 1, 1], images: [[image()]] }, two);
    const group = path.join(store, 'labels', 'organs');
    await writeZarrFolder(
      group,
      { dims: [N, N, N], type: 'uint8', spacing: [1, 1, 1], images: [[labels([N, N, N])]] },
      two,
    );
    const attrsFile = path.join(group, '.zattrs');
    const attrs = JSON.parse(fs.readFileSync(attrsFile, 'utf8'));
    attrs['image-label'] = {
      version: '0.4',
      colors: [
        { 'label-value': 1, rgba: [255, 0, 0, 255] },
        { 'label-value': 2, rgba: [0, 0, 255, 255] },
      ],
      properties: [
        { 'label-value': 1, name: 'liver' },
        { 'label-value': 2, name: 'tumour' },
      ],
    };
    fs.writeFileSync(attrsFile, JSON.stringify(attrs));
    const base = viewer().server.mount(dir);
    const r = await viewer().run(
      async (vt, base: string, camera: unknown) => {
        const el = vt.create(
          {
            src: `${base}image.ome.zarr`,
            labels: `${base}image.ome.zarr/labels/organs`,
            renderer: 'eam',
            backend: 'webgl2',
            panels: 'none',
            'max-samples': '2',
            camera: JSON.stringify(camera),
          },
          'width:40px;height:40px',
        );
        await el.whenSettled();
        await vt.converged(el);
        const view = el.shadowRoot.querySelector('.view') as HTMLElement;
        const rect = view.getBoundingClientRect();
        view.dispatchEvent(
          new PointerEvent('pointermove', {
            clientX: rect.left + 0.35 * rect.width,
            clientY: rect.top + 0.5 * rect.height,
            bubbles: true,
          }),
        );
        const out = {
          table: el.labelTable,
          hover: el.hoveredLabel,
          dims: el.context.getScene().labels?.volume.dims,
          loads: el.__events.filter((e: { type: string }) => e.type === 'load').length,
          errors: el.__events.filter((e: { type: string }) => e.type === 'error'),
        };
        el.remove();
        // The image held at its coarser level: the label group's level of that grid is drawn.
        const coarse = vt.create(
          {
            src: `${base}image.ome.zarr#level=1`,
            labels: `${base}image.ome.zarr/labels/organs`,
            renderer: 'eam',
            backend: 'webgl2',
            panels: 'none',
            'max-samples': '1',
          },
          'width:16px;height:16px',
        );
        await coarse.whenSettled();
        await vt.converged(coarse);
        const coarseOut = {
          dims: coarse.context.getScene().labels?.volume.dims,
          names: coarse.labelTable?.map((e: { name?: string }) => e.name),
          errors: coarse.__events.filter((e: { type: string }) => e.type === 'error'),
        };
        coarse.remove();
        return { ...out, coarse: coarseOut };
      },
      base,
      CAMERA,
    );
    // Refined from level 1 to 0 (two vpt-load), labels following without an error.
    expect(r.errors).toEqual([]);
    expect(r.loads).toBe(2);
    expect(r.dims).toEqual([N, N, N]);
    expect(r.coarse.errors).toEqual([]);
    expect(r.coarse.dims).toEqual([N / 2, N / 2, N / 2]);
    expect(r.coarse.names).toEqual(['liver', 'tumour']);
    expect(r.table).toEqual([
      { id: 1, name: 'liver', color: [1, 0, 0], opacity: 1, visible: true },
      { id: 2, name: 'tumour', color: [0, 0, 1], opacity: 1, visible: true },
    ]);
    expect(r.hover).toMatchObject({ id: 1, name: 'liver' });
  });

  it("with the slice renderer names the label of the plane's voxel under the pointer, where the image shows its colour; in the slice panes the probe's", async () => {
    const base = viewer().server.mount(dir);
    const r = await viewer().run(async (vt, base: string) => {
      const W = 32;
      const el = vt.create(
        {
          src: `${base}image.json`,
          labels: `${base}labels.nrrd`,
          renderer: 'slice',
          'renderer-params': JSON.stringify({ axis: 'z', index: 8, fit: true }),
          backend: 'webgl2',
          panels: 'none',
          'max-samples': '1',
        },
        `width:${W}px;height:${W}px`,
      );
      await el.whenSettled();
      await vt.converged(el);
      const { width, height } = el.context.size;
      const ldr = await vt.ldr(el);
      const view = el.shadowRoot.querySelector('.view') as HTMLElement;
      const rect = view.getBoundingClientRect();
      const cells: { id: number | null; rgb: string }[] = [];
      for (let y = 0; y < height; y++)
        for (let x = 0; x < width; x++) {
          view.dispatchEvent(
            new PointerEvent('pointermove', {
              clientX: rect.left + ((x + 0.5) / width) * rect.width,
              clientY: rect.top + ((y + 0.5) / height) * rect.height,
              bubbles: true,
            }),
          );
          const i = 4 * (y * width + x);
          cells.push({ id: el.hoveredLabel?.id ?? null, rgb: `${ldr[i]},${ldr[i + 1]},${ldr[i + 2]}` });
        }
      el.remove();
      // The slice panes: the probe's voxel names its label.
      const panes = vt.create(
        { src: `${base}image.json`, labels: `${base}labels.nrrd`, layout: 'slices', backend: 'webgl2', panels: 'none' },
        'width:120px;height:120px',
      );
      await panes.whenSettled();
      await vt.frames(4);
      await panes.whenSettled();
      const stage = panes.shadowRoot.querySelector('[data-stage=axial]') as HTMLElement;
      const probes: {
        index: number[] | null;
        label: { id: number; name?: string; voxel: number[] } | null;
        text: string | null;
      }[] = [];
      for (const [fx, fy] of [
        [0.4, 0.5],
        [0.6, 0.5],
        [0.1, 0.1],
      ]) {
        const sr = stage.getBoundingClientRect();
        stage.dispatchEvent(
          new PointerEvent('pointermove', {
            clientX: sr.left + fx * sr.width,
            clientY: sr.top + fy * sr.height,
            bubbles: true,
          }),
        );
        await panes.updateComplete;
        probes.push({
          index: panes.probeReading?.index ?? null,
          label: panes.hoveredLabel,
          text: (() => {
            const tip = panes.shadowRoot.querySelector('[data-stage=axial] [part=label-tip]') as HTMLElement | null;
            return tip && !tip.hidden ? tip.textContent : null;
          })(),
        });
      }
      panes.remove();
      return { width, height, cells, probes };
    }, base);
    const byId = new Map<number | null, Set<string>>();
    for (const c of r.cells) byId.set(c.id, (byId.get(c.id) ?? new Set()).add(c.rgb));
    // Fitted: pixel (x, y) shows voxel (⌊16x/W⌋, ⌊16y/H⌋) of layer z = 8 (rows from the lowest y
    // index): the hovered label is the label volume's id there, computed here from the fixture.
    const ids = labels([N, N, N]);
    const want = r.cells.map((_, k) => {
      const x = Math.floor(((k % r.width) * N) / r.width),
        y = Math.floor((Math.floor(k / r.width) * N) / r.height);
      return ids[x + N * (y + N * 8)] || null;
    });
    expect(r.cells.map((c) => c.id)).toEqual(want);
    expect([...byId.keys()].sort()).toEqual([1, 2, null]);
    // Each label is one flat colour (opaque over the slice), the two differ, and no background pixel has either.
    expect(byId.get(1)!.size).toBe(1);
    expect(byId.get(2)!.size).toBe(1);
    const [c1] = byId.get(1)!,
      [c2] = byId.get(2)!;
    expect(c1).not.toBe(c2);
    expect(byId.get(null)!.has(c1) || byId.get(null)!.has(c2)).toBe(false);
    // Panes: the hovered label is the probe's voxel's.
    for (const p of r.probes) {
      expect(p.index).not.toBeNull();
      const id = ids[p.index![0] + N * (p.index![1] + N * p.index![2])];
      expect(p.label?.id ?? 0).toBe(id);
      if (p.label) expect(p.label.voxel).toEqual(p.index);
      // The tooltip on the pane names it.
      expect(p.text).toBe(p.label ? p.label.name : null);
    }
    expect(r.probes.map((p) => p.label?.id ?? 0).sort()).toEqual([0, 1, 2]);
  });
});
