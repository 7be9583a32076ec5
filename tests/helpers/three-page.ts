/**
 * A headless Chromium page with tests/pages/three.html (three.js, @vpt/three and the built
 * packages) and `window.h3` helpers for building small three.js scenes with a VptVolume.
 */
import type { Browser, Page } from 'puppeteer-core';
import { afterAll, beforeAll } from 'vitest';
import { launchChromium, startStaticServer, type StaticServer } from '../../packages/headless/src/index.js';
import { recordPageErrors } from './page-errors.js';
import { ROOT } from './viewer-page.js';

/** A three.js setup of one size: renderer on its own canvas, compositor, scene, camera. */
export interface ThreeSetup {
  THREE: any;
  renderer: any;
  compositor: any;
  scene: any;
  camera: any;
}

export interface ThreeHelpers {
  /** A WebGLRenderer (size² pixels, pixel ratio 1), a float VptCompositor, a scene and a camera at (0, 0, 2) looking at 0, fovy 40°. */
  setup(size: number): ThreeSetup;
  /** A vpt scene without camera: a procedural volume, a constant TF (colour, opacity), density, background. */
  vptScene(kind: string, n: number, color: number[], opacity: number, density: number, background: number[]): any;
  /** A linear-sRGB three.js colour. */
  linear(rgb: number[]): any;
  /** The compositor's target as top-row-first RGBA floats. */
  readTarget(s: ThreeSetup): Float32Array;
  /** Render the composited scene `frames` times. */
  frames(s: ThreeSetup, frames: number): void;
  /** core's own render of the scene with this camera: HDR, top row first. */
  coreRender(renderer: string, scene: any, size: number, iterations: number): Promise<Float32Array>;
}

declare global {
  interface Window {
    h3: ThreeHelpers;
  }
}

/** Installs `window.h3`; sent with `page.evaluate` (it uses only `window.ref`). */
export function installThreeHelpers(): void {
  const { THREE, core, vt3 } = (window as any).ref;
  window.h3 = {
    setup(size) {
      const canvas = document.createElement('canvas');
      document.body.append(canvas);
      const renderer = new THREE.WebGLRenderer({ canvas, antialias: false });
      renderer.setPixelRatio(1);
      renderer.setSize(size, size, false);
      const compositor = new vt3.VptCompositor(renderer, { type: THREE.FloatType });
      const scene = new THREE.Scene();
      const camera = new THREE.PerspectiveCamera(40, 1, 0.1, 10);
      camera.position.set(0, 0, 2);
      camera.lookAt(0, 0, 0);
      camera.updateMatrixWorld();
      return { THREE, renderer, compositor, scene, camera };
    },
    vptScene(kind, n, color, opacity, density, background) {
      return {
        volume: core.createProceduralVolume(kind, n),
        transferFunction: {
          dimensions: '1d',
          points: [
            { value: 0, color, opacity },
            { value: 1, color, opacity },
          ],
        },
        lights: [],
        environment: { type: 'constant', radiance: background },
        densityScale: density,
        seed: 1,
        sampling: 'exact',
      };
    },
    linear(rgb) {
      return new THREE.Color().setRGB(rgb[0], rgb[1], rgb[2], THREE.LinearSRGBColorSpace);
    },
    readTarget(s) {
      const t = s.compositor.target;
      const w = t.width;
      const h = t.height;
      const px = new Float32Array(w * h * 4);
      s.renderer.readRenderTargetPixels(t, 0, 0, w, h, px);
      const out = new Float32Array(w * h * 4);
      for (let y = 0; y < h; y++) out.set(px.subarray((h - 1 - y) * w * 4, (h - y) * w * 4), y * w * 4);
      return out;
    },
    frames(s, frames) {
      for (let i = 0; i < frames; i++) s.compositor.render(s.scene, s.camera);
    },
    async coreRender(rendererName, scene, size, iterations) {
      const { eam, mcrt } = (window as any).ref;
      const renderer = rendererName === 'mcrt' ? new mcrt.McrtRenderer() : new eam.EamRenderer();
      const ctx = await core.RenderContext.create({ backend: 'webgl2', width: size, height: size, renderer });
      ctx.setScene(scene);
      await ctx.renderIterations(iterations);
      const hdr = await ctx.readHDR();
      ctx.dispose();
      return hdr;
    },
  };
}

export interface ThreePage {
  browser: Browser;
  server: StaticServer;
  page: Page;
  errors: string[];
  run<A extends unknown[], R>(fn: (h3: ThreeHelpers, ...args: A) => R | Promise<R>, ...args: A): Promise<Awaited<R>>;
  close(): Promise<void>;
}

/** `page`: the test page (three.html: WebGLRenderer; three-webgpu.html: three/webgpu). */
export async function openThreePage(pagePath = 'tests/pages/three.html'): Promise<ThreePage> {
  const server = await startStaticServer(ROOT);
  const browser = await launchChromium();
  const page = await browser.newPage();
  const errors = recordPageErrors(page);
  await page.goto(new URL(pagePath, server.url).href);
  // A module that fails to resolve (an import-map entry missing) never sets __ready: say why.
  await page
    .waitForFunction(() => (window as any).__ready === true, { timeout: 60_000 })
    .catch((e: Error) => {
      throw new Error(`${pagePath} did not become ready: ${errors.join('; ') || e.message}`);
    });
  await page.evaluate(installThreeHelpers);
  return {
    browser,
    server,
    page,
    errors,
    async run(fn, ...args) {
      const h = await page.evaluateHandle(() => window.h3);
      try {
        return (await page.evaluate(fn as (h: unknown, ...a: unknown[]) => unknown, h, ...args)) as never;
      } finally {
        await h.dispose();
      }
    },
    async close() {
      await page.close().catch(() => {});
      await browser.close().catch(() => {});
      await server.close();
    },
  };
}

/** One three.js page for a test file (opened in beforeAll, closed in afterAll). */
export function useThreePage(pagePath?: string): () => ThreePage {
  let p: ThreePage | undefined;
  beforeAll(async () => {
    p = await openThreePage(pagePath);
  });
  afterAll(async () => {
    await p?.close();
  });
  return () => {
    if (!p) throw new Error('three page not open');
    return p;
  };
}
