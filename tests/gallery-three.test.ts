import { describe, expect, it } from 'vitest';
import { useGalleryServer } from './helpers/gallery-server.js';
import { recordPageErrors } from './helpers/page-errors.js';

// The gallery's three.js page (apps/gallery/three): the head as a VptVolume in a three.js scene
// with the viewer's <vpt-tf-editor> editing its transfer function. It loads without console
// errors, and an edit made in the editor (keyboard, as a user would) restarts the volume's
// accumulation and changes the image far more than further refinement does.
const gallery = useGalleryServer();

/** Page code: the compositor's scene target (linear half floats, as stored) and the head's sample count. */
function snapshot(): { px: number[]; samples: number } {
  const t = (window as any).threePage;
  const rt = t.compositor.target;
  const px = new Uint16Array(rt.width * rt.height * 4);
  t.renderer.readRenderTargetPixels(rt, 0, 0, rt.width, rt.height, px);
  return { px: Array.from(px), samples: t.head.sampleCount };
}

/** IEEE 754 half → number. */
function half(h: number): number {
  const e = (h >> 10) & 31;
  const f = h & 1023;
  const v = e === 0 ? f * 2 ** -24 : e === 31 ? (f ? NaN : Infinity) : (1 + f / 1024) * 2 ** (e - 15);
  return h & 32768 ? -v : v;
}

function meanDiff(a: number[], b: number[]): number {
  let s = 0;
  for (let i = 0; i < a.length; i++) if (i % 4 !== 3) s += Math.abs(half(a[i]) - half(b[i]));
  return s / ((a.length * 3) / 4);
}

describe('gallery: three.html', () => {
  it('loads without console errors, and a TF edit in the viewer’s editor changes the volume', async () => {
    const { server, browser } = gallery();
    const page = await browser.newPage();
    const errors = recordPageErrors(page);
    page.on('response', (r) => {
      if (r.status() >= 400) errors.push(`HTTP ${r.status()} ${r.url()}`);
    });
    // A small canvas: SwiftShader is slow.
    await page.setViewport({ width: 320, height: 240 });
    await page.goto(new URL('apps/gallery/dist/three.html', server.url).href);
    const ready = (n: number) =>
      (window as any).__threeReady === true && (window as any).threePage.head.sampleCount >= n;
    await page.waitForFunction(ready, { timeout: 120_000, polling: 100 }, 4);
    // The editor is the viewer's element, holding the head's TF.
    const editor = await page.evaluate(() => {
      const el = document.getElementById('tf-editor') as any;
      return {
        defined: customElements.get('vpt-tf-editor') === el.constructor,
        points: el.value?.points?.length ?? 0,
        same: el.value === (window as any).threePage.head.scene.transferFunction,
      };
    });
    expect(editor).toEqual({ defined: true, points: 6, same: true });
    const a = await page.evaluate(snapshot);
    await page.waitForFunction(ready, { timeout: 120_000, polling: 100 }, a.samples + 4);
    const a2 = await page.evaluate(snapshot);
    // The edit: the third point (value 0.3, opacity 0.02) raised by 5 × 0.1 with Shift+ArrowUp.
    // The sample count is recorded every animation frame from here on.
    await page.evaluate(() => {
      const w = window as any;
      w.__counts = [];
      const tick = () => {
        w.__counts.push(w.threePage.head.sampleCount);
        requestAnimationFrame(tick);
      };
      tick();
      const el = document.getElementById('tf-editor') as any;
      (el.renderRoot.querySelectorAll('.pt')[2] as HTMLElement).focus();
    });
    await page.keyboard.down('Shift');
    for (let i = 0; i < 5; i++) await page.keyboard.press('ArrowUp');
    await page.keyboard.up('Shift');
    const tf = await page.evaluate(() => (window as any).threePage.head.scene.transferFunction.points[2].opacity);
    expect(tf).toBeCloseTo(0.52, 6);
    // Accumulation restarted (the count fell), then a fresh estimate of as many samples as the first one.
    // The restart is awaited first: the edit reaches the scene a frame or more after the key press,
    // so under load the old count could still satisfy `ready` before any frame saw the reset.
    const restarted = await page
      .waitForFunction(
        () => {
          const c: number[] = (window as any).__counts;
          return c.some((x, i) => i > 0 && x < c[i - 1]);
        },
        { timeout: 60_000, polling: 50 },
      )
      .then(
        () => true,
        () => false,
      );
    expect(restarted).toBe(true);
    await page.waitForFunction(ready, { timeout: 120_000, polling: 100 }, a.samples);
    const b = await page.evaluate(snapshot);
    const refine = meanDiff(a.px, a2.px);
    const edit = meanDiff(a.px, b.px);
    // The target holds the scene: the head differs from the flat background.
    expect(new Set(a.px).size).toBeGreaterThan(100);
    expect(edit).toBeGreaterThan(0.01);
    expect(edit).toBeGreaterThan(5 * refine);
    expect(errors).toEqual([]);
    await page.close();
  });
});
