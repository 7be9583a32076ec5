/**
 * The gallery (apps/gallery) built and served from the repository root with one Chromium, for
 * the gallery's browser tests: built and started in beforeAll, closed in afterAll.
 */
import { execFileSync } from 'node:child_process';
import { fileURLToPath } from 'node:url';
import { afterAll, beforeAll } from 'vitest';
import type { Browser } from 'puppeteer-core';
import { launchChromium, startStaticServer, type StaticServer } from '../../packages/headless/src/index.js';

const ROOT = fileURLToPath(new URL('../..', import.meta.url));

export interface GalleryServer {
  server: StaticServer;
  browser: Browser;
}

/** Registers the hooks; call the returned function inside a test. `enabled: false` skips the build (a skipped suite). */
export function useGalleryServer(enabled = true): () => GalleryServer {
  let server: StaticServer | undefined;
  let browser: Browser | undefined;
  beforeAll(async () => {
    if (!enabled) return;
    execFileSync(process.execPath, ['apps/gallery/build.mjs'], { cwd: ROOT, stdio: 'pipe' });
    server = await startStaticServer(ROOT);
    browser = await launchChromium();
  });
  afterAll(async () => {
    await browser?.close();
    await server?.close();
  });
  return () => {
    if (!server || !browser) throw new Error('the gallery server is not started (useGalleryServer(false)?)');
    return { server, browser };
  };
}
