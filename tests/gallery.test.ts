import fs from 'node:fs';
import { fileURLToPath } from 'node:url';
import { describe, expect, it } from 'vitest';
import type { Page } from 'puppeteer-core';
import { rendererNames } from '../packages/core/src/index.js';
import { useGalleryServer } from './helpers/gallery-server.js';
import { recordPageErrors } from './helpers/page-errors.js';

// The gallery (apps/gallery): README's first command builds and serves it. It must build,
// every page must load and render without console errors, and a link must restore the view.
const DIST = fileURLToPath(new URL('../apps/gallery/dist/', import.meta.url));
// Tiny renders (a tenth of the element's pixels) and few samples: SwiftShader is slow.
const FAST = 'scale=0.1&max=2';

const gallery = useGalleryServer();

type GalleryPage = 'gallery' | 'compare';

/** Page code: the gallery or comparison page has started, and each of its viewers has `samples` samples. */
function pageReady(which: GalleryPage, samples: number): boolean {
  const w = window as any;
  if (which === 'gallery') return w.__galleryReady === true && w.gallery.viewer.samples >= samples;
  return w.__compareReady === true && w.compare.views.every((v: { samples: number }) => v.samples >= samples);
}

async function open(path: string, which: GalleryPage, samples = 0): Promise<{ page: Page; errors: string[] }> {
  const { server, browser } = gallery();
  const page = await browser.newPage();
  const errors = recordPageErrors(page);
  page.on('response', (r) => {
    if (r.status() >= 400) errors.push(`HTTP ${r.status()} ${r.url()}`);
  });
  await page.setViewport({ width: 1000, height: 700 });
  await page.goto(new URL(`apps/gallery/dist/${path}`, server.url).href);
  try {
    await page.waitForFunction(pageReady, { timeout: 90_000, polling: 100 }, which, samples);
  } catch (e) {
    throw new Error(`${path}: not ready (${which}, ${samples} samples); console errors: ${JSON.stringify(errors)}`, {
      cause: e,
    });
  }
  return { page, errors };
}

/** Distinct colours in a viewer's displayed image, and its sample count. */
interface ImageSummary {
  distinct: number;
  samples: number;
  kind: string;
  renderer: string;
}

/** Page code: the summary of the gallery's viewer or of each comparison view. */
function imageSummaries(which: GalleryPage): Promise<ImageSummary[]> {
  const summary = async (el: any): Promise<ImageSummary> => {
    const ldr: Uint8Array = await el.context.readLDR();
    const s = new Set<number>();
    for (let i = 0; i < ldr.length; i += 4) s.add(ldr[i] * 65536 + ldr[i + 1] * 256 + ldr[i + 2]);
    return { distinct: s.size, samples: el.samples, kind: el.context.backend.kind, renderer: el.context.renderer.name };
  };
  const w = window as any;
  return Promise.all((which === 'gallery' ? [w.gallery.viewer] : w.compare.views).map(summary));
}

describe('gallery build', () => {
  it('builds the site with one command: pages, the viewer bundle with its loader worker, the data and a manifest listing it', () => {
    for (const f of [
      'index.html',
      'compare.html',
      'assets/gallery.js',
      'assets/compare.js',
      'assets/vpt-viewer.bundle.js',
      'scenes/head-eam.json',
      'data/mri_head_volpack_brainsmall_128x128x84_uint8.raw',
    ]) {
      expect(fs.existsSync(DIST + f), f).toBe(true);
    }
    const workers = fs
      .readdirSync(DIST + 'assets', { recursive: true })
      .map(String)
      .filter((f) => f.endsWith('loader-worker.js'));
    expect(workers.length).toBeGreaterThan(0);
    const manifest = JSON.parse(fs.readFileSync(DIST + 'data/manifest.json', 'utf8'));
    const head = manifest.datasets.find((d: { id: string }) => d.id === 'mri_head_volpack_brainsmall_128x128x84_uint8');
    expect(head).toMatchObject({
      url: 'data/mri_head_volpack_brainsmall_128x128x84_uint8.json',
      bundled: true,
      dims: [128, 128, 84],
      type: 'uint8',
    });
  });
});

describe('gallery pages', () => {
  it.each(['webgl2', 'webgpu'])(
    'smoke: the gallery page renders the bundled head on %s without console errors (not flat: > 20 colours)',
    async (backend) => {
      const { page, errors } = await open(`index.html?backend=${backend}&${FAST}`, 'gallery', 2);
      const [r] = await page.evaluate(imageSummaries, 'gallery' as GalleryPage);
      const state = await page.evaluate(() => ({
        search: location.search,
        pressed: document.querySelector('[aria-pressed="true"]')?.getAttribute('data-id'),
      }));
      await page.close();
      expect(errors).toEqual([]);
      expect(r.kind).toBe(backend);
      expect(r.renderer).toBe('eam');
      expect(r.distinct).toBeGreaterThan(20); // an image of the head, not a flat fill
      expect(state.pressed).toBe('mri_head_volpack_brainsmall_128x128x84_uint8');
      expect(state.search).toMatch(
        /dataset=mri_head_volpack_brainsmall_128x128x84_uint8&renderer=eam&tf=tissue&camera=/,
      );
    },
  );

  it('smoke: the comparison page renders the same dataset with every catalog renderer without console errors (not flat)', async () => {
    const { page, errors } = await open(`compare.html?dataset=blob&${FAST}`, 'compare', 1);
    const r = await page.evaluate(imageSummaries, 'compare' as GalleryPage);
    const cameras = await page.evaluate(() => (window as any).compare.views.map((v: any) => JSON.stringify(v.camera)));
    await page.close();
    expect(errors).toEqual([]);
    expect(r.map((x) => x.renderer)).toEqual(rendererNames());
    for (const x of r) expect(x.distinct, x.renderer).toBeGreaterThan(3);
    expect(new Set(cameras).size).toBe(1); // one camera for all
  });
});

describe('gallery: the cut-open head', () => {
  it('is listed, opens path traced with the clip of scenes/head-mcrt-clip.json, and the plain head drops the clip', async () => {
    const scene = JSON.parse(
      fs.readFileSync(new URL('../apps/gallery/scenes/head-mcrt-clip.json', import.meta.url), 'utf8'),
    );
    const { page, errors } = await open(`index.html?dataset=mri_head_cut&${FAST}`, 'gallery', 1);
    const [r] = await page.evaluate(imageSummaries, 'gallery' as GalleryPage);
    const cut = await page.evaluate(() => {
      const v = (window as any).gallery.viewer;
      return {
        clip: v.clip,
        sceneClip: v.context.getScene().clip,
        pressed: document.querySelector('[aria-pressed="true"]')?.getAttribute('data-id'),
        title: document.querySelector('[data-id="mri_head_cut"] .t')?.textContent,
      };
    });
    await page.click('[data-id="mri_head_volpack_brainsmall_128x128x84_uint8"]');
    // select() ends by writing the URL, after the preset is applied.
    await page.waitForFunction(() => location.search.includes('dataset=mri_head_volpack'), { timeout: 60_000 });
    await page.evaluate(() => (window as any).gallery.viewer.whenSettled());
    const plain = await page.evaluate(() => {
      const v = (window as any).gallery.viewer;
      return { clip: v.clip, sceneClip: v.context.getScene().clip ?? null };
    });
    await page.close();
    expect(errors).toEqual([]);
    expect(r.renderer).toBe('mcrt');
    expect(r.distinct).toBeGreaterThan(20);
    expect(cut).toEqual({
      clip: scene.clip,
      sceneClip: scene.clip,
      pressed: 'mri_head_cut',
      title: expect.stringMatching(/cut open/),
    });
    expect(plain).toEqual({ clip: null, sceneClip: null });
  });
});

describe('gallery: the head in slices', () => {
  it('is listed and opens in layout="quad" (three drawn slice panes and the 3D view); the plain head goes back to 3d', async () => {
    const { page, errors } = await open(`index.html?dataset=mri_head_slices&${FAST}`, 'gallery', 1);
    await page.waitForFunction(
      () =>
        ['axial', 'coronal', 'sagittal'].every(
          (n) => ((window as any).gallery.viewer.paneContext(n)?.stats.iterations ?? 0) >= 1,
        ),
      { timeout: 60_000 },
    );
    const quad = await page.evaluate(() => {
      const v = (window as any).gallery.viewer;
      return {
        layout: v.layout,
        panes: v.shadowRoot.querySelectorAll('.pane').length,
        title: document.querySelector('[data-id="mri_head_slices"] .t')?.textContent,
      };
    });
    await page.click('[data-id="mri_head_volpack_brainsmall_128x128x84_uint8"]');
    await page.waitForFunction(() => location.search.includes('dataset=mri_head_volpack'), { timeout: 60_000 });
    await page.evaluate(() => (window as any).gallery.viewer.whenSettled());
    const plain = await page.evaluate(() => {
      const v = (window as any).gallery.viewer;
      return { layout: v.layout, panes: v.shadowRoot.querySelectorAll('.pane').length };
    });
    await page.close();
    expect(errors).toEqual([]);
    expect(quad).toEqual({ layout: 'quad', panes: 3, title: expect.stringMatching(/in slices/) });
    expect(plain).toEqual({ layout: '3d', panes: 0 });
  });
});

describe('gallery deep links', () => {
  const camera = { position: [0.3, 1.2, 1.1], target: [0.05, 0, 0], up: [0, 1, 0], fovy: 0.6 };
  const cam = [...camera.position, ...camera.target, ...camera.up, camera.fovy].join(',');

  it('a link restores dataset, renderer, transfer function, camera, exposure, tone mapper and density', async () => {
    const { page, errors } = await open(
      `index.html?dataset=blob&renderer=mip&tf=hot&camera=${cam}&exposure=1.5&tone=reinhard&density=33&${FAST}`,
      'gallery',
      1,
    );
    const s = await page.evaluate(() => {
      const v = (window as any).gallery.viewer;
      return {
        src: v.src,
        renderer: v.context.renderer.name,
        tf: v.transferFunction,
        camera: v.camera,
        exposure: v.exposure,
        tone: v.toneMapper,
        density: v.densityScale,
        pressed: document.querySelector('[aria-pressed="true"]')?.getAttribute('data-id'),
      };
    });
    // (A string, so Vitest does not rewrite the dynamic import.)
    const hot = await page.evaluate(
      `import('/apps/gallery/dist/assets/vpt-viewer.bundle.js').then((m) => m.transferFunctionPreset('hot'))`,
    );
    await page.close();
    expect(errors).toEqual([]);
    expect(s.src).toBe('procedural:blob?size=64');
    expect(s.pressed).toBe('blob');
    expect(s.renderer).toBe('mip');
    expect(s.camera).toEqual(camera);
    expect(s.exposure).toBe(1.5);
    expect(s.tone).toBe('reinhard');
    expect(s.density).toBe(33);
    expect(s.tf.points.length).toBe(4);
    expect(s.tf).toEqual(hot);
  });

  it('after changing the view (drag, renderer, transfer function), the page URL reopens the same view', async () => {
    const { page, errors } = await open(`index.html?dataset=ramp&renderer=eam&${FAST}`, 'gallery', 1);
    // Drag on the canvas, switch the renderer with the radio button, pick a TF preset in the panel.
    const box = await page.evaluate(() => {
      const r = (window as any).gallery.viewer.shadowRoot.querySelector('canvas').getBoundingClientRect();
      return { x: r.x + r.width / 2, y: r.y + r.height / 2 };
    });
    await page.mouse.move(box.x, box.y);
    await page.mouse.down();
    for (let i = 1; i <= 5; i++) await page.mouse.move(box.x + 12 * i, box.y + 4 * i);
    await page.mouse.up();
    await page.click('input[name="renderer"][value="mcrt"]');
    await page.waitForFunction(() => (window as any).gallery.viewer.context.renderer.name === 'mcrt', {
      timeout: 60_000,
    });
    await page.evaluate(() => {
      const v = (window as any).gallery.viewer;
      const select = v.shadowRoot.querySelector('details select') as HTMLSelectElement; // the preset list
      select.value = 'cool';
      select.dispatchEvent(new Event('change'));
    });
    // The URL follows changes 250 ms after the last one (longer while SwiftShader compiles).
    await page.waitForFunction(() => location.search.includes('tf=cool'), { timeout: 60_000 });
    const before = await page.evaluate(() => {
      const v = (window as any).gallery.viewer;
      return {
        url: location.href,
        renderer: v.renderer,
        tf: v.transferFunction,
        camera: v.camera,
        density: v.densityScale,
      };
    });
    await page.close();
    expect(errors).toEqual([]);
    expect(before.url).toMatch(/renderer=mcrt/);
    expect(before.url).toMatch(/tf=cool/);

    const again = await open(before.url.split('/apps/gallery/dist/')[1], 'gallery');
    const after = await again.page.evaluate(() => {
      const v = (window as any).gallery.viewer;
      return {
        renderer: v.renderer,
        tf: v.transferFunction,
        camera: v.camera,
        density: v.densityScale,
        dataset: (window as any).gallery.current.dataset.id,
      };
    });
    await again.page.close();
    expect(again.errors).toEqual([]);
    expect(after.dataset).toBe('ramp');
    expect(after.renderer).toBe('mcrt');
    expect(after.tf).toEqual(before.tf);
    expect(after.density).toBe(before.density);
    for (const k of ['position', 'target', 'up'] as const) {
      for (let i = 0; i < 3; i++) expect(after.camera[k][i]).toBeCloseTo(before.camera[k][i], 3);
    }
    expect(after.camera.position).not.toEqual([0, 0, 0]);
  });

  it('a comparison link sets one camera on all four views', async () => {
    const { page, errors } = await open(`compare.html?dataset=sphere&camera=${cam}&${FAST}`, 'compare');
    const cameras = await page.evaluate(() => (window as any).compare.views.map((v: any) => v.camera));
    await page.close();
    expect(errors).toEqual([]);
    for (const c of cameras) expect(c).toEqual(camera);
  });
});
