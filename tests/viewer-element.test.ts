import { afterAll, beforeAll, describe, expect, it } from 'vitest';
import { decodePNG, readSceneFile, type VptPageSession } from '../packages/headless/src/index.js';
import {
  compareRgba,
  distinctGreys,
  openViewerAndHeadless,
  installViewerHelpers,
  sceneFileAttributes,
  type ViewerPage,
} from './helpers/viewer-page.js';

// <vpt-viewer> from its one-file bundle in a plain page, against the headless renderer.
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
const SAMPLES = 8;

describe('<vpt-viewer> renders what the headless renderer renders', () => {
  it.each(['webgl2', 'webgpu'] as const)(
    'the bundled head with EAM on %s: same LDR image as vpt-render of the same scene, and a non-empty canvas on screen',
    async (backend) => {
      const { description, baseDir } = readSceneFile('apps/gallery/scenes/head-eam.json');
      const desc = { ...description, width: SIZE, height: SIZE, iterations: SAMPLES, backend };
      const ref = await headless.render(desc, { baseDir });

      const attrs = {
        ...sceneFileAttributes(desc, { renderer: 'eam', backend, maxSamples: SAMPLES }),
        // The screenshot below compares the canvas alone: no progress bar or stats line over it.
        'hide-progress': '',
        'hide-stats': '',
      };
      const got = await vp.run(
        async (vt, attrs, size) => {
          const el = vt.create(attrs, `width:${size}px;height:${size}px;position:absolute;left:0;top:0`);
          el.id = 'match';
          await vt.converged(el);
          const r = {
            kind: el.context.backend.kind,
            size: el.context.size,
            samples: el.samples,
            ldr: await vt.ldr(el),
            events: el.__events.map((e: any) => e.type),
          };
          return r;
        },
        attrs,
        SIZE,
      );
      expect(got.kind).toBe(backend);
      expect(got.size).toEqual({ width: SIZE, height: SIZE });
      expect(got.samples).toBe(SAMPLES);
      expect(got.events).toContain('load');
      expect(got.events).not.toContain('error');
      const cmp = compareRgba(got.ldr, ref.ldr!);
      // Same seed, same kernels, same backend: SwiftShader gives the same bits; allow one LSB.
      expect(cmp.maxDiff).toBeLessThanOrEqual(1);
      expect(distinctGreys(ref.ldr!)).toBeGreaterThan(50);

      // What is on screen: the element's canvas shows the same image (compositing may round).
      const shot = decodePNG(
        (await vp.page.screenshot({ clip: { x: 0, y: 0, width: SIZE, height: SIZE } })) as Uint8Array,
      );
      expect(distinctGreys(shot.rgba)).toBeGreaterThan(50);
      expect(compareRgba(shot.rgba, ref.ldr!).meanDiff).toBeLessThan(3);
      await vp.page.evaluate(() => document.getElementById('match')!.remove());
    },
  );
});

describe('<vpt-viewer> attributes', () => {
  const BLOB = {
    src: 'procedural:blob?size=24',
    renderer: 'eam',
    backend: 'webgl2',
    panels: 'none',
    'max-samples': '4',
    'density-scale': '20',
    'transfer-function': 'ramp',
    environment: '{"type":"constant","radiance":[0.1,0.1,0.1]}',
  };

  it('changing renderer, transfer-function and camera changes the image and restarts the sample count; setting current values does not', async () => {
    const r = await vp.run(async (vt, attrs) => {
      const el = vt.create(attrs);
      await vt.converged(el);
      const out: Record<string, unknown> = {};

      // Setting every attribute to the value it already has: no reset, no new convergence.
      el.__events.length = 0;
      for (const name of ['renderer', 'transfer-function', 'camera', 'max-samples', 'density-scale', 'backend'])
        el.setAttribute(name, el.getAttribute(name));
      el.camera = JSON.parse(el.getAttribute('camera'));
      await el.whenSettled();
      await vt.frames(10);
      out.same = { samples: el.samples, events: el.__events.map((e: any) => `${e.type}:${e.samples}`) };

      const changes: [string, string][] = [
        ['transfer-function', 'hot'],
        ['renderer', 'mip'], // after the TF change: MIP shows the raw maximum, whatever the TF
        ['camera', JSON.stringify({ position: [0.2, 1.6, 0.9], target: [0, 0, 0], up: [0, 1, 0], fovy: 0.7 })],
      ];
      let before = await vt.ldr(el);
      out.changes = [];
      for (const [name, value] of changes) {
        el.__events.length = 0;
        const converged = vt.next(el, 'converged');
        el.setAttribute(name, value);
        await el.whenSettled();
        await converged;
        const after = await vt.ldr(el);
        let differing = 0;
        for (let i = 0; i < after.length; i += 4)
          if (after[i] !== before[i] || after[i + 1] !== before[i + 1] || after[i + 2] !== before[i + 2]) differing++;
        const samples = el.__events
          .filter((e: any) => e.type === 'progress' && e.phase === 'refining')
          .map((e: any) => e.samples);
        (out.changes as unknown[]).push({
          name,
          differing,
          firstSamples: samples[0],
          lastSamples: samples[samples.length - 1],
          reflected: el.getAttribute(name),
        });
        before = after;
      }
      out.tfProperty = el.transferFunction.points.length;
      el.remove();
      return out;
    }, BLOB);
    const same = r.same as { samples: number; events: string[] };
    expect(same.samples).toBe(4);
    expect(same.events).toEqual([]);
    for (const c of r.changes as {
      name: string;
      differing: number;
      firstSamples: number;
      lastSamples: number;
      reflected: string;
    }[]) {
      expect(c.differing, c.name).toBeGreaterThan(24 * 24 * 0.1);
      // Accumulation started over: converged at 4, the element reports no progress without a restart
      // (\`same\` above); a loop that fills its frame budget may reach 4 again in the first frame.
      expect(c.firstSamples, c.name).toBeLessThanOrEqual(4);
      expect(c.lastSamples, c.name).toBe(4);
    }
    expect((r.changes as { reflected: string }[])[0].reflected).toBe('hot');
    expect(r.tfProperty).toBe(4); // the "hot" preset's control points, as an object
  });

  it('reflects properties to attributes and reports invalid values with a typed error, keeping the last valid one', async () => {
    const r = await vp.run(async (vt, attrs) => {
      const el = vt.create(attrs);
      await el.whenSettled();
      el.camera = { position: [0, 0, 2.5], target: [0, 0, 0], up: [0, 1, 0], fovy: 0.6 };
      el.exposure = 1.5;
      el.lights = [{ type: 'directional', direction: [1, 1, 1], irradiance: [2, 2, 2] }];
      await el.updateComplete;
      const reflected = {
        camera: JSON.parse(el.getAttribute('camera')),
        exposure: el.getAttribute('exposure'),
        lights: JSON.parse(el.getAttribute('lights')),
      };
      const errors: unknown[] = [];
      el.addEventListener('vpt-error', (e: CustomEvent) =>
        errors.push({
          code: e.detail.code,
          message: e.detail.message,
          source: e.detail.source,
          isVptError: e.detail.error.name,
        }),
      );
      el.setAttribute('transfer-function', '{"dimensions":"1d","points":[{"value":2}]');
      await el.updateComplete;
      el.setAttribute('transfer-function', 'no-such-preset');
      await el.updateComplete;
      el.setAttribute('max-samples', '-3');
      await el.updateComplete;
      const kept = {
        tf: el.transferFunction.points.length,
        maxSamples: el.maxSamples,
        banner: vt.shadowText(el, '[part=error] p'),
      };
      el.remove();
      return { reflected, errors, kept };
    }, BLOB);
    expect(r.reflected.camera).toEqual({ position: [0, 0, 2.5], target: [0, 0, 0], up: [0, 1, 0], fovy: 0.6 });
    expect(r.reflected.exposure).toBe('1.5');
    expect(r.reflected.lights[0].irradiance).toEqual([2, 2, 2]);
    expect(r.errors).toHaveLength(3);
    for (const e of r.errors as { code: string; source: string }[]) {
      expect(e.code).toBe('invalid-scene');
      expect(e.source).toBe('attribute');
    }
    const [json, preset, max] = r.errors as { message: string }[];
    expect(json.message).toMatch(/transfer-function: not valid JSON/);
    expect(preset.message).toMatch(/unknown preset "no-such-preset" \(presets: ramp, tissue/);
    expect(max.message).toMatch(/max-samples: must be an integer/);
    expect(r.kept.tf).toBe(2); // still the ramp
    expect(r.kept.maxSamples).toBe(4);
    expect(r.kept.banner).toMatch(/max-samples/);
  });

  it('number attributes above their maximum (seed 2^32, exposure 100, resolution-scale 5) are refused, keeping the last valid value', async () => {
    const r = await vp.run(async (vt, attrs) => {
      const el = vt.create({ ...attrs, seed: '7', exposure: '0.5', 'resolution-scale': '1' });
      await el.whenSettled();
      const errors: { code: string; source: string; message: string }[] = [];
      el.addEventListener('vpt-error', (e: CustomEvent) =>
        errors.push({ code: e.detail.code, source: e.detail.source, message: e.detail.message }),
      );
      for (const [name, value] of [
        ['seed', '4294967296'],
        ['exposure', '100'],
        ['resolution-scale', '5'],
      ]) {
        el.setAttribute(name, value);
        await el.updateComplete;
      }
      const kept = { seed: el.seed, exposure: el.exposure, resolutionScale: el.resolutionScale };
      el.remove();
      return { errors, kept };
    }, BLOB);
    expect(r.errors.map((e) => [e.code, e.source])).toEqual([
      ['invalid-scene', 'attribute'],
      ['invalid-scene', 'attribute'],
      ['invalid-scene', 'attribute'],
    ]);
    expect(r.errors[0].message).toMatch(/seed: must be an integer in \[0, 4294967295\]/);
    expect(r.errors[1].message).toMatch(/exposure: must be a number in \[-64, 64\]/);
    expect(r.errors[2].message).toMatch(/resolution-scale: must be a number in \[0.05, 4\]/);
    expect(r.kept).toEqual({ seed: 7, exposure: 0.5, resolutionScale: 1 });
  });
});

describe('<vpt-viewer> size', () => {
  it('renders at the element size times the device pixel ratio and follows container resizes', async () => {
    const sizes = async (page: typeof vp.page) =>
      page.evaluate(async () => {
        const vt = (window as any).vt;
        const el = vt.create(
          { src: 'procedural:blob?size=8', renderer: 'mip', backend: 'webgl2', panels: 'none', 'max-samples': '1' },
          'width:20px;height:12px',
        );
        await vt.converged(el);
        const read = async () => {
          await vt.frames(3);
          return [el.context.size.width, el.context.size.height, el.shadowRoot.querySelector('canvas').width];
        };
        const first = await read();
        el.style.width = '30px';
        const resized = await read();
        el.setAttribute('resolution-scale', '0.5');
        const scaled = await read();
        el.remove();
        return { first, resized, scaled };
      });
    expect(await sizes(vp.page)).toEqual({ first: [20, 12, 20], resized: [30, 12, 30], scaled: [15, 6, 15] });
    // A second page on a screen with two device pixels per CSS pixel.
    const hi = await vp.browser.newPage();
    await hi.setViewport({ width: 400, height: 300, deviceScaleFactor: 2 });
    await hi.goto(vp.page.url());
    await hi.waitForFunction(() => (window as any).__ready === true);
    await hi.evaluate(installViewerHelpers);
    const at2 = await sizes(hi);
    await hi.close();
    await vp.page.bringToFront();
    expect(at2).toEqual({ first: [40, 24, 40], resized: [60, 24, 60], scaled: [30, 12, 30] });
  });
});

describe('<vpt-viewer> stopping rules', () => {
  it('with a renderer that estimates its error, progress reports it and refinement stops at target-error', async () => {
    const r = await vp.run(async (vt) => {
      const el = vt.create(
        {
          src: 'procedural:blob?size=16',
          renderer: 'mcrt',
          backend: 'webgl2',
          panels: 'none',
          'max-samples': '4096',
          'target-error': '0.2',
          'density-scale': '20',
        },
        'width:16px;height:16px',
      );
      const done = await vt.next(el, 'converged', 180000);
      await vt.frames(10);
      const errors = el.__events
        .filter((e: any) => e.type === 'progress' && e.phase === 'refining')
        .map((e: any) => e.samples);
      const estimate = await el.context.estimateError();
      const out = { done, samplesLater: el.samples, progressCount: errors.length, estimate };
      el.remove();
      return out;
    });
    expect(r.done.reason).toBe('target-error');
    expect(r.done.error).toBeLessThanOrEqual(0.2);
    expect(r.done.samples).toBeLessThan(4096);
    expect(r.samplesLater).toBe(r.done.samples); // held where it stopped
    // The estimate from the context agrees that the image is at (or below) the target.
    expect(r.estimate.relativeRmse).toBeLessThanOrEqual(0.2);
  });
});

describe('<vpt-viewer> interaction', () => {
  it('dragging on the canvas orbits the camera, changes the image, and returns to full resolution when still', async () => {
    await vp.run(async (vt) => {
      // A ramp (value = x), not a blob: a round blob looks the same from every side.
      const el = vt.create(
        {
          src: 'procedural:ramp?size=16',
          renderer: 'eam',
          backend: 'webgl2',
          panels: 'none',
          'max-samples': '4',
          'density-scale': '4',
          environment: '{"type":"constant","radiance":[0,0,0]}',
        },
        'width:48px;height:48px;position:absolute;left:100px;top:100px',
      );
      el.id = 'drag';
      await vt.converged(el);
      (window as any).dragBefore = { camera: el.getAttribute('camera'), ldr: await vt.ldr(el) };
      el.__events.length = 0;
    });
    await vp.page.mouse.move(124, 124);
    await vp.page.mouse.down();
    for (let i = 1; i <= 6; i++) await vp.page.mouse.move(124 + 4 * i, 124 + i);
    await vp.page.mouse.up();
    const r = await vp.run(async (vt) => {
      const el = document.getElementById('drag') as any;
      const before = (window as any).dragBefore;
      // Converged may come from the reduced-resolution image; wait for the full-size one of the new
      // view (which a fast loop may have reached before this runs).
      while (el.getAttribute('camera') === before.camera || el.context.size.width !== 48 || !el.converged)
        await vt.next(el, 'converged');
      const after = await vt.ldr(el);
      let differing = 0;
      for (let i = 0; i < after.length; i += 4) if (after[i] !== before.ldr[i]) differing++;
      const out = {
        cameraBefore: JSON.parse(before.camera),
        cameraAfter: JSON.parse(el.getAttribute('camera')),
        property: el.camera,
        differing,
        size: el.context.size,
        changeEvents: el.__events.filter((e: any) => e.type === 'change').map((e: any) => e.property),
      };
      el.remove();
      return out;
    });
    expect(r.cameraAfter.position).not.toEqual(r.cameraBefore.position);
    expect(r.property.position).toEqual(r.cameraAfter.position);
    // Orbiting keeps the distance to the target.
    const dist = (c: { position: number[] }) => Math.hypot(...c.position);
    expect(dist(r.cameraAfter)).toBeCloseTo(dist(r.cameraBefore), 4);
    expect(r.differing).toBeGreaterThan(48 * 48 * 0.2);
    expect(r.size).toEqual({ width: 48, height: 48 });
    expect(r.changeEvents.length).toBeGreaterThan(0);
    expect(new Set(r.changeEvents)).toEqual(new Set(['camera']));
  });
});

describe('<vpt-viewer> keyboard', () => {
  it("arrows orbit and +/- zoom the focused canvas; the transfer-function editor's points move and delete from the keyboard", async () => {
    const attrs = {
      src: 'procedural:ramp?size=16',
      renderer: 'eam',
      backend: 'webgl2',
      panels: 'tf',
      'max-samples': '2',
      'resolution-scale': '0.2',
      'transfer-function': 'tissue',
    };
    await vp.run(async (vt, attrs) => {
      const el = vt.create(attrs, 'width:380px;height:300px;position:absolute;left:0;top:0');
      el.id = 'keys';
      await vt.converged(el);
      el.shadowRoot.querySelector('canvas').focus();
      (window as any).keysBefore = el.camera;
    }, attrs);
    await vp.page.keyboard.press('ArrowLeft');
    const orbit = await vp.page.evaluate(() => (document.getElementById('keys') as any).camera);
    await vp.page.keyboard.press('+');
    const zoom = await vp.page.evaluate(() => (document.getElementById('keys') as any).camera);
    const before = await vp.page.evaluate(() => (window as any).keysBefore);
    const dist = (c: { position: number[] }) => Math.hypot(...c.position);
    expect(orbit.position).not.toEqual(before.position);
    expect(dist(orbit)).toBeCloseTo(dist(before), 4); // an orbit, not a zoom
    // Five degrees about the up axis (y): the angle between the two positions.
    const cos =
      orbit.position.reduce((a: number, x: number, i: number) => a + x * before.position[i], 0) /
      (dist(orbit) * dist(before));
    const horizontal = Math.hypot(before.position[0], before.position[2]) / dist(before);
    expect(Math.acos(Math.min(1, cos))).toBeCloseTo(((5 * Math.PI) / 180) * horizontal, 2);
    expect(dist(zoom)).toBeCloseTo(dist(orbit) / 1.1, 4);

    // 380 px is too narrow for a sidebar: the panels are a closed overlay; the button opens it.
    const overlay = await vp.page.evaluate(async () => {
      const el = document.getElementById('keys') as any;
      const before = {
        aside: !!el.shadowRoot.querySelector('aside'),
        button: el.shadowRoot.querySelector('[part=panels-toggle]').textContent.trim(),
      };
      el.shadowRoot.querySelector('[part=panels-toggle]').click();
      await el.updateComplete;
      return {
        before,
        aside: !!el.shadowRoot.querySelector('aside'),
        button: el.shadowRoot.querySelector('[part=panels-toggle]').textContent.trim(),
      };
    });
    expect(overlay).toEqual({ before: { aside: false, button: 'Settings' }, aside: true, button: 'Close' });
    // The third control point of the "tissue" preset: value 0.3, opacity 0.02.
    await vp.page.evaluate(() => {
      const el = document.getElementById('keys') as any;
      el.__events.length = 0;
      el.shadowRoot.querySelector('vpt-tf-editor').shadowRoot.querySelectorAll('.pt')[2].focus();
    });
    await vp.page.keyboard.press('ArrowUp');
    await vp.page.keyboard.press('ArrowRight');
    const moved = await vp.page.evaluate(() => {
      const el = document.getElementById('keys') as any;
      return {
        point: el.transferFunction.points[2],
        attribute: JSON.parse(el.getAttribute('transfer-function')).points[2],
        events: el.__events.filter((e: any) => e.type === 'change').map((e: any) => e.property),
      };
    });
    await vp.page.keyboard.press('Delete');
    const after = await vp.page.evaluate(() => {
      const el = document.getElementById('keys') as any;
      const r = {
        count: el.transferFunction.points.length,
        focused: el.shadowRoot.querySelector('vpt-tf-editor').shadowRoot.activeElement?.getAttribute('aria-label'),
      };
      el.remove();
      return r;
    });
    // One step is 1% of the opacity axis, which spans [0, 1] for this preset, and 0.01 in value.
    expect(moved.point.opacity).toBeCloseTo(0.03, 6);
    expect(moved.point.value).toBeCloseTo(0.31, 6);
    expect(moved.attribute).toEqual(moved.point);
    expect(moved.events).toEqual(['transferFunction', 'transferFunction']);
    expect(after.count).toBe(5);
    expect(after.focused).toMatch(/Control point 3 of 5/);
  });
});

describe('<vpt-viewer> failures', () => {
  it('a bad src fires a clear load error and shows it; a good src afterwards loads and renders', async () => {
    const r = await vp.run(async (vt) => {
      const el = vt.create({
        src: '/data/no-such-volume.json',
        renderer: 'mip',
        backend: 'webgl2',
        panels: 'none',
        'max-samples': '2',
      });
      const err = await vt.next(el, 'error');
      await el.updateComplete;
      const banner = vt.shadowText(el, '[part=error] p');
      const loaded = vt.next(el, 'load');
      el.src = 'procedural:sphere?size=16';
      await loaded;
      await vt.converged(el);
      await el.updateComplete;
      const ldr = await vt.ldr(el);
      let lit = 0;
      for (let i = 0; i < ldr.length; i += 4) if (ldr[i] > 0) lit++;
      const centre = ldr[(12 * 24 + 12) * 4],
        corner = ldr[0];
      const out = {
        code: err.code,
        source: err.source,
        message: err.message,
        banner,
        bannerAfter: vt.shadowText(el, '[part=error] p'),
        lit,
        centre,
        corner,
        samples: el.samples,
      };
      el.remove();
      return out;
    });
    expect(r.code).toBe('load-failed');
    expect(r.source).toBe('src');
    expect(r.message).toMatch(/no-such-volume\.json was not found \(HTTP 404\)/);
    expect(r.banner).toBe(r.message);
    expect(r.bannerAfter).toBeNull();
    // The sphere: a lit disc in the middle of a black MIP background.
    expect(r.centre).toBeGreaterThan(100);
    expect(r.corner).toBe(0);
    expect(r.lit).toBeGreaterThan(24 * 24 * 0.1);
    expect(r.samples).toBe(2);
  });

  it('a renderer that cannot be loaded fails alone; the element keeps rendering and accepts another renderer', async () => {
    const r = await vp.run(async (vt) => {
      const viewer = (window as any).ref.viewer;
      viewer.registerRenderer({
        name: 'broken',
        label: 'Broken',
        packageName: '@example/renderer-broken',
        load: () => Promise.reject(new Error('network down')),
      });
      const el = vt.create({
        src: 'procedural:blob?size=16',
        renderer: 'eam',
        backend: 'webgl2',
        panels: 'none',
        'max-samples': '2',
      });
      await vt.converged(el);
      const err = vt.next(el, 'error');
      el.renderer = 'broken';
      const e = await err;
      await el.whenSettled();
      const stillEam = el.context.renderer.name;
      const conv = vt.next(el, 'converged');
      el.renderer = 'mip';
      await el.whenSettled();
      await conv;
      const out = { code: e.code, message: e.message, source: e.source, stillEam, now: el.context.renderer.name };
      el.remove();
      return out;
    });
    expect(r.code).toBe('load-failed');
    expect(r.source).toBe('renderer');
    expect(r.message).toMatch(
      /"broken" renderer is not available: @example\/renderer-broken could not be loaded \(network down\)/,
    );
    expect(r.stillEam).toBe('eam');
    expect(r.now).toBe('mip');
  });

  it('a lost GPU context shows a message, recovers, and refines again', async () => {
    const r = await vp.run(async (vt) => {
      const el = vt.create({
        src: 'procedural:blob?size=16',
        renderer: 'eam',
        backend: 'webgl2',
        panels: 'none',
        'max-samples': '3',
      });
      await vt.converged(el);
      const restored = el.context.backend.simulateLoss(300);
      await vt.frames(2);
      await el.updateComplete;
      const during = vt.shadowText(el, '.lost p');
      await restored;
      await vt.next(el, 'converged');
      await el.updateComplete;
      const out = { during, after: vt.shadowText(el, '.lost p'), samples: el.samples };
      el.remove();
      return out;
    });
    expect(r.during).toMatch(/GPU context was lost/);
    expect(r.after).toBeNull();
    expect(r.samples).toBe(3);
  });
});

describe('<vpt-viewer> export', () => {
  it('screenshot is a PNG of the displayed image; HDR export writes PFM and OpenEXR', async () => {
    const r = await vp.run(async (vt) => {
      const el = vt.create(
        { src: 'procedural:blob?size=16', renderer: 'eam', backend: 'webgl2', panels: 'none', 'max-samples': '2' },
        'width:20px;height:12px',
      );
      await vt.converged(el);
      const png = new Uint8Array(await (await el.screenshot()).arrayBuffer());
      const pfm = await el.exportHDR('pfm');
      const exr = await el.exportHDR('exr');
      const hdr = await el.context.readHDR();
      // First pixel of the PFM's first stored row = bottom-left of the image.
      const pfmHeader = new TextDecoder().decode(pfm.slice(0, 12));
      const headerLen = 'PF\n20 12\n-1.0\n'.length;
      const first = new DataView(pfm.buffer, pfm.byteOffset + headerLen, 12);
      const bottomLeft = (12 - 1) * 20 * 4;
      const out = {
        png: Array.from(png.slice(0, 8)),
        pngBytes: png.length,
        pfmHeader,
        pfmBytes: pfm.length,
        pfmFirst: [first.getFloat32(0, true), first.getFloat32(4, true), first.getFloat32(8, true)],
        hdrBottomLeft: [hdr[bottomLeft], hdr[bottomLeft + 1], hdr[bottomLeft + 2]],
        exrMagic: new DataView(exr.buffer, exr.byteOffset, 4).getUint32(0, true),
        exrBytes: exr.length,
      };
      el.remove();
      return out;
    });
    expect(r.png).toEqual([0x89, 0x50, 0x4e, 0x47, 0x0d, 0x0a, 0x1a, 0x0a]);
    expect(r.pngBytes).toBeGreaterThan(60);
    expect(r.pfmHeader.startsWith('PF\n20 12\n')).toBe(true);
    expect(r.pfmBytes).toBe('PF\n20 12\n-1.0\n'.length + 20 * 12 * 12);
    for (let c = 0; c < 3; c++) expect(r.pfmFirst[c]).toBeCloseTo(r.hdrBottomLeft[c], 6);
    expect(r.exrMagic).toBe(20000630); // OpenEXR magic number
    expect(r.exrBytes).toBeGreaterThan(300);
  });
});

describe('<vpt-viewer> small and narrow', () => {
  it('a 400x300 element shows only its image at rest (panels an overlay behind a button), with a progress bar and a stats line that attributes hide; Escape closes the overlay', async () => {
    const r = await vp.run(async (vt) => {
      const el = vt.create(
        {
          src: 'procedural:blob?size=16',
          renderer: 'eam',
          backend: 'webgl2',
          'max-samples': '100000',
          'resolution-scale': '0.1',
        },
        'width:400px;height:300px;position:absolute;left:0;top:0',
      );
      await vt.next(el, 'progress');
      while (!el.stats) await vt.frames(1);
      await el.updateComplete;
      const q = (sel: string) => el.shadowRoot.querySelector(sel);
      const view = q('.view').getBoundingClientRect();
      const atRest = {
        aside: !!q('aside'),
        view: [view.width, view.height],
        bar: !!q('[part=progress]'),
        stats: q('[part=stats]')?.textContent ?? '',
      };
      const barValue = Number(q('[part=progress]')?.getAttribute('aria-valuenow'));
      q('[part=panels-toggle]').click();
      await el.updateComplete;
      const opened = q('aside')?.getBoundingClientRect();
      q('aside').dispatchEvent(new KeyboardEvent('keydown', { key: 'Escape', bubbles: true, composed: true }));
      await el.updateComplete;
      const closed = !q('aside');
      el.setAttribute('hide-progress', '');
      el.setAttribute('hide-stats', '');
      await el.updateComplete;
      const hidden = { bar: !!q('[part=progress]'), stats: !!q('[part=stats]') };
      // Wide: the panels sit beside the image again.
      el.style.width = '900px';
      await vt.frames(3);
      await el.updateComplete;
      const wide = { aside: !!q('aside'), view: q('.view').getBoundingClientRect().width };
      el.remove();
      return { atRest, barValue, opened: opened && [opened.width, opened.height], closed, hidden, wide };
    });
    expect(r.atRest.aside).toBe(false);
    expect(r.atRest.view).toEqual([400, 300]); // the image has the whole element
    expect(r.atRest.bar).toBe(true);
    expect(r.barValue).toBeGreaterThanOrEqual(0);
    expect(r.barValue).toBeLessThan(100);
    expect(r.atRest.stats).toMatch(/^\d+ \/ 100000 spp · [\d.]+ ms\/it · \d+×\d+/);
    expect(r.opened).toEqual([400, 300]); // the overlay covers the element only when opened
    expect(r.closed).toBe(true);
    expect(r.hidden).toEqual({ bar: false, stats: false });
    expect(r.wide.aside).toBe(true);
    expect(r.wide.view).toBeGreaterThan(500);
    expect(r.wide.view).toBeLessThan(900);
  });
});

describe('<vpt-viewer> renderer changes while a renderer package loads', () => {
  it('a slow renderer load that lands after the page chose another renderer never renders (the gallery deep-link race)', async () => {
    const r = await vp.run(async (vt) => {
      const viewer = (window as any).ref.viewer;
      // "slow" is EAM behind a load that resolves only when the test says so.
      let release!: () => void;
      const gate = new Promise<void>((res) => {
        release = res;
      });
      const eam = viewer.rendererEntry('eam');
      viewer.registerRenderer({
        ...eam,
        name: 'slow',
        label: 'Slow',
        load: async () => {
          await gate;
          return eam.load();
        },
      });
      const el = vt.create({
        src: 'procedural:blob?size=16',
        renderer: 'slow',
        backend: 'webgl2',
        panels: 'none',
        'max-samples': '3',
      });
      await vt.frames(3);
      el.renderer = 'mip'; // while the context still waits for "slow"
      await vt.frames(2);
      release();
      const seen: string[] = [];
      const record = () => {
        if (el.context && el.samples > 0) seen.push(el.context.renderer.name);
      };
      el.addEventListener('vpt-progress', record);
      await vt.converged(el);
      record();
      el.remove();
      return { seen: [...new Set(seen)], final: el.renderer };
    });
    expect(r.final).toBe('mip');
    expect(r.seen).toEqual(['mip']);
  });
});
