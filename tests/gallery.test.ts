import { afterAll, beforeAll, describe, expect, it } from 'vitest';
import { fileURLToPath } from 'node:url';
import type { Browser } from 'puppeteer-core';
import { launchChromium, startStaticServer, type StaticServer } from '../packages/headless/src/index.js';

// README's first command ends with this page running: it must load, refine and stay clean.
describe('demo page (apps/gallery)', () => {
  let server: StaticServer;
  let browser: Browser;
  beforeAll(async () => {
    server = await startStaticServer(fileURLToPath(new URL('..', import.meta.url)));
    browser = await launchChromium();
  });
  afterAll(async () => {
    await browser?.close();
    await server?.close();
  });

  it.each(['webgl2', 'webgpu'])('renders the bundled head progressively on %s without console errors', async (backend) => {
    const page = await browser.newPage();
    const errors: string[] = [];
    page.on('console', (m) => { if (m.type() === 'error') errors.push(m.text()); });
    page.on('pageerror', (e) => errors.push((e as Error).message));
    await page.goto(new URL(`apps/gallery/index.html?backend=${backend}`, server.url).href);
    await page.waitForFunction('window.__demoReady === true', { timeout: 60_000 });
    await page.waitForFunction('window.vptDemo.context && window.vptDemo.context.stats.iterations >= 2', { timeout: 120_000 });
    const r = await page.evaluate(async () => {
      const ctx = (window as any).vptDemo.context;
      ctx.stop();
      const ldr: Uint8Array = await ctx.readLDR();
      const grey = new Set<number>();
      for (let i = 0; i < ldr.length; i += 4) grey.add(ldr[i]);
      return { kind: ctx.backend.kind, distinct: grey.size, stats: (document.getElementById('stats') as HTMLOutputElement).value };
    });
    await page.close();
    expect(errors).toEqual([]);
    expect(r.kind).toBe(backend);
    expect(r.distinct).toBeGreaterThan(50); // an image of the head, not a flat fill
    expect(r.stats).toMatch(/samples\/pixel/);
  });
});
