import { afterAll, beforeAll, describe, expect, it } from 'vitest';
import { readSceneFile, validateSceneDescription, type VptPageSession } from '../packages/headless/src/index.js';
import {
  compareRgba,
  distinctGreys,
  openViewerAndHeadless,
  sceneFileAttributes,
  type ViewerPage,
} from './helpers/viewer-page.js';

/**
 * The viewer's clipping (docs/architecture.md, "Clipping"): the `clip` attribute takes the
 * scene file's JSON and renders what vpt-render renders for that scene file; the Clip panel's
 * controls change the clip, the image and fire a typed `vpt-change`; a bad value is a typed
 * error that leaves the element rendering.
 */
let vp: ViewerPage;
let headless: VptPageSession;

let pages: Awaited<ReturnType<typeof openViewerAndHeadless>> | undefined;
beforeAll(async () => {
  pages = await openViewerAndHeadless();
  ({ vp, headless } = pages);
});
afterAll(async () => {
  await pages?.close();
});

const SIZE = 32;
const SAMPLES = 6;
// The cut of the gallery's cut-open head (scenes/head-mcrt-clip.json): the half toward the camera, and a box.
const CLIP = {
  planes: [{ normal: [-1, 0, 0], offset: 0 }],
  box: { min: [-0.5, -0.3, -0.5], max: [0.5, 0.5, 0.3] },
};

describe('<vpt-viewer clip>', () => {
  it('the attribute renders what vpt-render renders for the scene file with that clip (EAM, WebGL 2)', async () => {
    const { description, baseDir } = readSceneFile('apps/gallery/scenes/head-eam.json');
    const desc = { ...description, width: SIZE, height: SIZE, iterations: SAMPLES, backend: 'webgl2' as const };
    // The scene-file check accepts the clip as given.
    expect(validateSceneDescription({ ...desc, clip: CLIP }).clip).toEqual(CLIP);
    const ref = await headless.render({ ...desc, clip: CLIP } as typeof desc, { baseDir });
    const whole = await headless.render(desc, { baseDir });
    const attrs = {
      ...sceneFileAttributes(desc, { renderer: 'eam', backend: 'webgl2', maxSamples: SAMPLES }),
      clip: JSON.stringify(CLIP),
    };
    const got = await vp.run(
      async (vt, attrs, size) => {
        const el = vt.create(attrs, `width:${size}px;height:${size}px`);
        await vt.converged(el);
        const r = {
          samples: el.samples,
          clip: el.clip,
          sceneClip: el.context.getScene().clip,
          ldr: await vt.ldr(el),
          events: el.__events.map((e: { type: string }) => e.type),
        };
        el.remove();
        return r;
      },
      attrs,
      SIZE,
    );
    expect(got.events).not.toContain('error');
    expect(got.samples).toBe(SAMPLES);
    expect(got.clip).toEqual(CLIP);
    expect(got.sceneClip).toEqual(CLIP);
    // Same kernels, seed and backend: the same bits (one LSB allowed, as viewer-element.test.ts).
    expect(compareRgba(got.ldr, ref.ldr!).maxDiff).toBeLessThanOrEqual(1);
    expect(distinctGreys(ref.ldr!)).toBeGreaterThan(20);
    // And the cut shows: the unclipped head differs.
    expect(compareRgba(ref.ldr!, whole.ldr!).differingPixels).toBeGreaterThan(50);
  });

  it("the Clip panel: a plane's checkbox, slider and flip change the clip and the image, each with a typed vpt-change", async () => {
    const r = await vp.run(async (vt) => {
      // Wide enough for the sidebar beside the image; a tenth of the pixels rendered.
      const el = vt.create(
        {
          src: 'procedural:blob?size=16',
          renderer: 'eam',
          backend: 'webgl2',
          panels: 'clip',
          'max-samples': '2',
          'resolution-scale': '0.1',
        },
        'width:660px;height:160px',
      );
      const values: unknown[] = [];
      el.addEventListener('vpt-change', (e: CustomEvent) => values.push(e.detail));
      await vt.converged(el);
      const q = (sel: string) => el.shadowRoot.querySelector(sel);
      const image = async () => Array.from((await el.context.readHDR()) as Float32Array);
      const settle = async () => {
        await el.updateComplete;
        await vt.converged(el);
      };
      const before = await image();
      q('details').open = true;
      q('[data-clip="on-x"]').click(); // a plane at x = 0, keeping x <= 0
      await settle();
      const on = { clip: el.clip, attribute: JSON.parse(el.getAttribute('clip')), img: await image() };
      const slider = q('[data-clip="plane-x"]') as HTMLInputElement;
      const range = { min: Number(slider.min), max: Number(slider.max) };
      // Dragging the slider: input events as it moves, each one a new clip and image.
      for (const value of ['-0.1', '-0.2']) {
        slider.value = value;
        slider.dispatchEvent(new Event('input', { bubbles: true, composed: true }));
        await el.updateComplete;
      }
      await settle();
      const dragged = { clip: el.clip, sceneClip: el.context.getScene().clip, img: await image() };
      q('[data-clip="flip-x"]').click();
      await settle();
      const flipped = { clip: el.clip, img: await image() };
      q('[data-clip="on-x"]').click();
      await settle();
      const off = { clip: el.clip, attribute: el.getAttribute('clip'), sceneClip: el.context.getScene().clip ?? null };
      const after = await image();
      const changes = el.__events.filter((e: { type: string }) => e.type === 'change').map((e: any) => e.property);
      const errors = el.__events.filter((e: { type: string }) => e.type === 'error');
      el.remove();
      const differ = (a: number[], b: number[]) => a.some((x, i) => x !== b[i]);
      return {
        on: { clip: on.clip, attribute: on.attribute, changed: differ(before, on.img) },
        range,
        dragged: { clip: dragged.clip, sceneClip: dragged.sceneClip, changed: differ(on.img, dragged.img) },
        flipped: { clip: flipped.clip, changed: differ(dragged.img, flipped.img) },
        off: { ...off, same: !differ(before, after) },
        changes,
        values,
        errors,
      };
    });
    expect(r.errors).toEqual([]);
    const x = (offset: number, sign = 1) => ({ planes: [{ normal: [sign, 0, 0], offset }] });
    expect(r.on).toEqual({ clip: x(0), attribute: x(0), changed: true });
    expect(r.range).toEqual({ min: -0.5, max: 0.5 }); // the blob's box
    expect(r.dragged).toEqual({ clip: x(-0.2), sceneClip: x(-0.2), changed: true });
    expect(r.flipped).toEqual({ clip: x(0.2, -1), changed: true });
    // Unchecked: nothing cut, no attribute, the unclipped variant's image bit for bit.
    expect(r.off).toEqual({ clip: null, attribute: null, sceneClip: null, same: true });
    expect(r.changes).toEqual(['clip', 'clip', 'clip', 'clip', 'clip']);
    expect(r.values).toEqual([
      { property: 'clip', value: x(0) },
      { property: 'clip', value: x(-0.1) },
      { property: 'clip', value: x(-0.2) },
      { property: 'clip', value: x(0.2, -1) },
      { property: 'clip', value: null },
    ]);
  });

  it('the crop box: six sliders, each bound kept inside the box and ordered', async () => {
    const r = await vp.run(async (vt) => {
      const el = vt.create(
        {
          src: 'procedural:blob?size=16',
          renderer: 'mip',
          backend: 'webgl2',
          panels: 'clip',
          'max-samples': '1',
          'resolution-scale': '0.1',
        },
        'width:660px;height:160px',
      );
      await vt.converged(el);
      const q = (sel: string) => el.shadowRoot.querySelector(sel);
      q('details').open = true;
      q('[data-clip="box"]').click();
      await el.updateComplete;
      const full = el.clip;
      const move = async (name: string, value: string) => {
        const s = q(`[data-clip="${name}"]`) as HTMLInputElement;
        s.value = value;
        s.dispatchEvent(new Event('input', { bubbles: true, composed: true }));
        await el.updateComplete;
      };
      await move('box-max-z', '0.1');
      await move('box-min-z', '0.3'); // past max z: stops at it
      await move('box-min-y', '-0.2');
      await vt.converged(el);
      const sliders = [...el.shadowRoot.querySelectorAll('[data-clip^="box-"]')].map((s: any) => s.dataset.clip);
      const out = { full, clip: el.clip, sliders, sceneClip: el.context.getScene().clip };
      el.remove();
      return out;
    });
    expect(r.full).toEqual({ box: { min: [-0.5, -0.5, -0.5], max: [0.5, 0.5, 0.5] } });
    expect(r.clip).toEqual({ box: { min: [-0.5, -0.2, 0.1], max: [0.5, 0.5, 0.1] } });
    expect(r.sceneClip).toEqual(r.clip);
    expect(r.sliders).toEqual(['box-min-x', 'box-min-y', 'box-min-z', 'box-max-x', 'box-max-y', 'box-max-z']);
  });

  it("dragging a plane's handle on the image moves the plane along its axis, toward the pointer", async () => {
    const page = vp.page;
    const start = await vp.run(async (vt) => {
      const el = vt.create(
        {
          src: 'procedural:blob?size=16',
          renderer: 'eam',
          backend: 'webgl2',
          panels: 'clip',
          'max-samples': '2',
          'resolution-scale': '0.1',
          clip: '{"planes":[{"normal":[1,0,0],"offset":0}]}',
        },
        'width:660px;height:200px;position:absolute;left:0;top:0',
      );
      el.id = 'handles';
      await vt.converged(el);
      await el.updateComplete;
      const h = el.shadowRoot.querySelector('[data-clip-handle="x"]').getBoundingClientRect();
      return { x: h.x + h.width / 2, y: h.y + h.height / 2, img: Array.from(await el.context.readHDR()) as number[] };
    });
    // A real pointer drag (puppeteer's mouse: pointerdown, moves, pointerup).
    const to = { x: start.x + 40, y: start.y + 12 };
    await page.mouse.move(start.x, start.y);
    await page.mouse.down();
    for (let i = 1; i <= 4; i++)
      await page.mouse.move(start.x + (i / 4) * (to.x - start.x), start.y + (i / 4) * (to.y - start.y));
    await page.mouse.up();
    const after = await vp.run(async (vt, to) => {
      const el = document.getElementById('handles') as any;
      await vt.converged(el);
      await el.updateComplete;
      const h = el.shadowRoot.querySelector('[data-clip-handle="x"]').getBoundingClientRect();
      const out = {
        clip: el.clip,
        handle: { x: h.x + h.width / 2, y: h.y + h.height / 2 },
        img: Array.from(await el.context.readHDR()) as number[],
        changes: el.__events.filter((e: { type: string }) => e.type === 'change').map((e: any) => e.property),
        camera: el.camera,
      };
      el.remove();
      return { ...out, to };
    }, to);
    const offset = after.clip.planes[0].offset;
    expect(after.clip.planes[0].normal).toEqual([1, 0, 0]);
    expect(Math.abs(offset)).toBeGreaterThan(0.01);
    // The handle lands where the pointer projects onto the axis: closer to the pointer than it started.
    const dist = (a: { x: number; y: number }) => Math.hypot(a.x - to.x, a.y - to.y);
    expect(dist(after.handle)).toBeLessThan(dist(start) - 5);
    expect(new Set(after.changes)).toEqual(new Set(['clip'])); // the camera did not orbit
    expect(after.img.some((x, i) => x !== start.img[i])).toBe(true);
  });

  it('a bad clip attribute is a typed error naming the field; the last valid clip stays and the element renders', async () => {
    const r = await vp.run(async (vt) => {
      const el = vt.blob('eam', 2);
      el.setAttribute('clip', '{"planes":[{"normal":[0,1,0],"offset":0.1}]}');
      await vt.converged(el);
      const good = el.clip;
      const errors: any[] = [];
      for (const bad of [
        '{"planes": [',
        '{"planes":[{"normal":[0,0,0],"offset":0}]}',
        '{"box":{"min":[1],"max":[1,1,1]}}',
      ]) {
        el.setAttribute('clip', bad);
        await el.updateComplete;
        const e = el.__events.filter((x: { type: string }) => x.type === 'error').pop();
        errors.push({ code: e?.code, source: e?.source, message: e?.message, kept: el.clip });
      }
      // Still usable: a new valid value renders.
      el.setAttribute('clip', '{"planes":[{"normal":[0,-1,0],"offset":0.1}]}');
      await vt.converged(el);
      const out = { good, errors, after: el.clip, samples: el.samples, scene: el.context.getScene().clip };
      el.remove();
      return out;
    });
    const good = { planes: [{ normal: [0, 1, 0], offset: 0.1 }] };
    expect(r.good).toEqual(good);
    expect(r.errors.map((e) => [e.code, e.source])).toEqual([
      ['invalid-scene', 'attribute'],
      ['invalid-scene', 'attribute'],
      ['invalid-scene', 'attribute'],
    ]);
    expect(r.errors[0].message).toMatch(/<vpt-viewer> clip: not valid JSON/);
    expect(r.errors[1].message).toMatch(/<vpt-viewer> clip: clip\.planes\[0\]\.normal: must have a nonzero length/);
    expect(r.errors[2].message).toMatch(/<vpt-viewer> clip: clip\.box\.min/);
    for (const e of r.errors) expect(e.kept).toEqual(good);
    const after = { planes: [{ normal: [0, -1, 0], offset: 0.1 }] };
    expect(r.after).toEqual(after);
    expect(r.scene).toEqual(after);
    expect(r.samples).toBe(2);
  });
});
