import { describe, expect, it } from 'vitest';
import type { Page } from 'puppeteer-core';
import { rendererNames } from '../packages/core/src/index.js';
import { useGalleryServer } from './helpers/gallery-server.js';
import { recordPageErrors } from './helpers/page-errors.js';

// Issue 28: the gallery on a phone (390×844, touch), compare.html on a 1280-px screen, a bad
// deep link, and no failed request (HTTP errors and failed requests, net::ERR_ABORTED included).
const FAST = 'scale=0.1&max=2&backend=webgl2';
const gallery = useGalleryServer();

interface Opened {
  page: Page;
  errors: string[];
  failed: string[];
  /** URLs of the requests that finished, in order. */
  finished: string[];
}

async function open(path: string, viewport: Parameters<Page['setViewport']>[0]): Promise<Opened> {
  const { server, browser } = gallery();
  const page = await browser.newPage();
  const errors = recordPageErrors(page);
  const failed: string[] = [];
  const finished: string[] = [];
  // Every failed request counts, the loader worker's included (puppeteer reports a dedicated
  // worker's requests on its page).
  page.on('requestfailed', (r) => failed.push(`${r.url()} ${r.failure()?.errorText ?? ''}`));
  page.on('requestfinished', (r) => finished.push(r.url()));
  page.on('response', (r) => {
    if (r.status() >= 400) failed.push(`HTTP ${r.status()} ${r.url()}`);
  });
  await page.setViewport(viewport);
  await page.goto(new URL(`apps/gallery/dist/${path}`, server.url).href);
  await page.waitForFunction(() => (window as any).__galleryReady === true || (window as any).__compareReady === true, {
    timeout: 120_000,
    polling: 100,
  });
  return { page, errors, failed, finished };
}

const PHONE = { width: 390, height: 844, deviceScaleFactor: 1, isMobile: true, hasTouch: true };

/** Page code: the widths that decide horizontal overflow, and what sticks out past the screen. */
function overflow(screenWidth: number) {
  const out: string[] = [];
  const check = (root: Document | ShadowRoot) => {
    for (const e of root.querySelectorAll('*')) {
      const r = e.getBoundingClientRect();
      if (r.width > 0 && r.right > screenWidth + 0.5) out.push(`${e.tagName.toLowerCase()}.${e.className}`);
      if (e.shadowRoot) check(e.shadowRoot);
    }
  };
  check(document);
  return { scrollWidth: document.documentElement.scrollWidth, innerWidth: window.innerWidth, outside: out };
}

/** The width of a PNG from its IHDR chunk. */
function pngWidth(png: Uint8Array): number {
  return new DataView(png.buffer, png.byteOffset).getUint32(16);
}

describe('the gallery on a phone (390×844, touch)', () => {
  it('nothing overflows horizontally, the viewer is above the fold, and a tab tapped by touch switches the renderer', async () => {
    const { page, errors, failed } = await open(`index.html?${FAST}`, PHONE);
    try {
      const before = await page.evaluate(overflow, 390);
      expect(before.innerWidth).toBe(390);
      expect(before.scrollWidth).toBeLessThanOrEqual(before.innerWidth);
      expect(before.outside).toEqual([]);
      const shot = await page.screenshot({ fullPage: true });
      expect(pngWidth(shot)).toBeLessThanOrEqual(390);
      const box = await page.evaluate(() => {
        const r = document.getElementById('viewer')!.getBoundingClientRect();
        return { top: r.top, bottom: r.bottom, height: r.height };
      });
      expect(box.height).toBeGreaterThan(200);
      expect(box.bottom).toBeLessThanOrEqual(844);
      // Touch: tap the "Path traced" tab.
      const tab = await page.evaluate(() => {
        const input = document.querySelector('#renderer-choice input[value="mcrt"]')!;
        const r = input.closest('label')!.getBoundingClientRect();
        return { x: r.left + r.width / 2, y: r.top + r.height / 2, right: r.right };
      });
      expect(tab.right).toBeLessThanOrEqual(390);
      await page.touchscreen.tap(tab.x, tab.y);
      await page.waitForFunction(() => (window as any).gallery.viewer.renderer === 'mcrt', { timeout: 60_000 });
      await page.evaluate(() => (window as any).gallery.viewer.whenSettled());
      const after = await page.evaluate(overflow, 390);
      expect(after.scrollWidth).toBeLessThanOrEqual(390);
      expect(after.outside).toEqual([]);
      expect(errors).toEqual([]);
      expect(failed).toEqual([]);
    } finally {
      await page.close();
    }
  });

  it('compare.html fits the phone too', async () => {
    const { page, errors, failed } = await open(`compare.html?${FAST}`, PHONE);
    try {
      const o = await page.evaluate(overflow, 390);
      expect(o.scrollWidth).toBeLessThanOrEqual(390);
      expect(o.outside).toEqual([]);
      expect(errors).toEqual([]);
      expect(failed).toEqual([]);
    } finally {
      await page.close();
    }
  });
});

describe('compare.html on a 1280-px screen', () => {
  it("uses the screen's width: a view per renderer of the catalog, in one row across it", async () => {
    const { page, errors, failed } = await open(`compare.html?${FAST}`, { width: 1280, height: 720 });
    try {
      const r = await page.evaluate(() =>
        [...document.querySelectorAll('#grid vpt-viewer')].map((v) => {
          const b = v.getBoundingClientRect();
          return { top: Math.round(b.top), right: b.right, width: b.width };
        }),
      );
      expect(r).toHaveLength(rendererNames().length);
      expect(new Set(r.map((v) => v.top)).size).toBe(1);
      expect(Math.max(...r.map((v) => v.right))).toBeGreaterThan(1280 * 0.95);
      expect(errors).toEqual([]);
      expect(failed).toEqual([]);
    } finally {
      await page.close();
    }
  });
});

describe('a bad deep link', () => {
  it('says what it could not follow instead of silently showing the default view', async () => {
    const { page, failed } = await open(`index.html?${FAST}&dataset=no-such-volume&renderer=raytrace&camera=1,2`, {
      width: 1000,
      height: 700,
    });
    try {
      const notice = await page.evaluate(() => {
        const p = document.getElementById('link-error')!;
        return { hidden: p.hidden, text: p.textContent ?? '', role: p.getAttribute('role') };
      });
      expect(notice.hidden).toBe(false);
      expect(notice.role).toBe('alert');
      expect(notice.text).toMatch(/dataset "no-such-volume" is not in this gallery/);
      expect(notice.text).toMatch(/renderer "raytrace"/);
      expect(notice.text).toMatch(/camera/);
      expect(failed).toEqual([]);
    } finally {
      await page.close();
    }
    const good = await open(`index.html?${FAST}&dataset=blob&renderer=mip`, { width: 1000, height: 700 });
    try {
      expect(await good.page.evaluate(() => document.getElementById('link-error')!.hidden)).toBe(true);
    } finally {
      await good.page.close();
    }
  });
});

describe('requests the gallery logs as failed', () => {
  // Chromium logged the loader worker's .json/.raw requests net::ERR_ABORTED in about 2 loads of
  // 3 while a script read their body stream: it cancels the URL loader when that stream ends
  // before the network's completion arrives. fetchWithPolicy now reads the bytes natively and
  // counts a clone's; several loads, so that the race would have shown.
  it('no page logs a request as failed, the volume and its sidecar finish, over several loads', async () => {
    // The bundled head, a sidecar and its raw file, named so that fetched datasets change nothing.
    const head = 'mri_head_volpack_brainsmall_128x128x84_uint8';
    const pages = ['index.html', 'index.html', 'index.html', 'compare.html', 'index.html', 'compare.html'];
    for (const path of pages) {
      const { page, failed, finished } = await open(`${path}?${FAST}&dataset=${head}`, { width: 400, height: 300 });
      try {
        const volume = finished.filter((u) => u.includes(`/data/${head}.`)).map((u) => u.slice(u.lastIndexOf('.')));
        expect(volume.sort(), path).toEqual(['.json', '.raw']);
        expect(failed, path).toEqual([]);
      } finally {
        await page.close();
      }
    }
  });
});
