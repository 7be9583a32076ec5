import { afterAll, beforeAll, describe, expect, it } from 'vitest';
import { fileURLToPath } from 'node:url';
import type { Browser } from 'puppeteer-core';
import { launchChromium, startStaticServer, type StaticServer } from '../packages/headless/src/index.js';
import { backendConformance } from './helpers/backend-conformance-page.js';
import { BACKENDS, usePage } from './helpers/session.js';

const page = usePage();

/**
 * The backend conformance suite checks each GpuBackend against values computed in JS:
 * exact uniform packing (vec3/float/mat4), MRT outputs, the top-row-first pixel convention,
 * texture formats and readback, canvas presentation, the shared validation, limits,
 * shader-compile errors, loss/restore and dispose, a line per check; the post page checks
 * the post steps across backends and against the CPU references.
 */
describe('backend conformance pages', () => {
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

  async function run(pagePath: string, result: string): Promise<{ value: unknown; log: string[] }> {
    const page = await browser.newPage();
    const log: string[] = [];
    page.on('console', (m) => log.push(m.text()));
    page.on('pageerror', (e) => log.push(`pageerror: ${(e as Error).message}`));
    await page.goto(new URL(pagePath, server.url).href);
    await page.waitForFunction(() => (window as any).__done === true, { timeout: 180_000 });
    const value = await page.evaluate(result);
    await page.close();
    return { value, log };
  }

  // One suite (helpers/backend-conformance-page.ts), run once per backend in the headless page.
  it.each(BACKENDS)('%s backend passes every check', async (kind) => {
    const { failures, log } = await page().page.evaluate(backendConformance, kind);
    expect(log.filter((l) => /FAIL/.test(l))).toEqual([]);
    expect(log.filter((l) => /PASS/.test(l)).length).toBeGreaterThan(10);
    expect(failures).toBe(0);
  });

  it('post steps agree between the backends and with the CPU references', async () => {
    const { value } = await run('tests/pages/post.html', 'window.__postResult');
    const r = value as { ok: boolean; checks: number; failures: string[] };
    expect(r.failures).toEqual([]);
    expect(r.checks).toBeGreaterThan(10);
    expect(r.ok).toBe(true);
  });
});
