import fs from 'node:fs';
import { afterAll, beforeAll, describe, expect, it } from 'vitest';
import type { Browser } from 'puppeteer-core';
import { chromiumExecutable, launchChromium } from '../src/chromium.js';
import { startStaticServer, type StaticServer } from '../src/server.js';

// Launches the system Chromium: skipped where it is not installed (.ci/run installs it).
describe.skipIf(!fs.existsSync(chromiumExecutable()))('launchChromium', () => {
  let browser: Browser, server: StaticServer;
  beforeAll(async () => {
    browser = await launchChromium();
    server = await startStaticServer(null);
  }, 60_000);
  afterAll(async () => {
    await browser?.close();
    await server?.close();
  });

  it('offers WebGL 2 with float render targets and a WebGPU adapter on SwiftShader', async () => {
    const page = await browser.newPage();
    // A served page, not about:blank: WebGPU needs a secure context (http://127.0.0.1).
    await page.goto(server.url);
    const caps = await page.evaluate(async () => {
      const gl = document.createElement('canvas').getContext('webgl2');
      const ext = gl?.getExtension('WEBGL_debug_renderer_info');
      const adapter =
        'gpu' in navigator
          ? await (navigator as unknown as { gpu: { requestAdapter(): Promise<unknown> } }).gpu.requestAdapter()
          : null;
      return {
        webgl2: !!gl,
        colorBufferFloat: !!gl?.getExtension('EXT_color_buffer_float'),
        glRenderer: gl && ext ? String(gl.getParameter(ext.UNMASKED_RENDERER_WEBGL)) : '',
        webgpu: !!adapter,
        secure: window.isSecureContext,
      };
    });
    await page.close();
    expect(caps.secure).toBe(true);
    expect(caps.webgl2).toBe(true);
    expect(caps.colorBufferFloat).toBe(true);
    expect(caps.glRenderer).toMatch(/SwiftShader/i);
    expect(caps.webgpu).toBe(true);
  }, 60_000);

  it('uses a fresh profile per launch and removes it on close', async () => {
    const b = await launchChromium({ webgpu: false });
    const args = b.process()?.spawnargs ?? [];
    const profile = args.find((a) => a.startsWith('--user-data-dir='))?.slice('--user-data-dir='.length);
    expect(profile).toMatch(/vpt-chromium-/);
    expect(args).toContain('--use-angle=swiftshader');
    expect(args).not.toContain('--enable-unsafe-webgpu');
    await b.close();
    await new Promise((r) => setTimeout(r, 200));
    expect(fs.existsSync(profile!)).toBe(false);
  }, 60_000);
});
