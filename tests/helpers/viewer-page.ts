/**
 * A headless Chromium page with tests/pages/viewer.html (the <vpt-viewer> bundle plus
 * the built packages for reference renders) and `window.vt` helpers for driving
 * elements from page.evaluate.
 */
import { fileURLToPath } from 'node:url';
import type { Browser, Page } from 'puppeteer-core';
import { afterAll, beforeAll } from 'vitest';
import {
  launchChromium,
  openVptPage,
  startStaticServer,
  type StaticServer,
  type VptPageSession,
} from '../../packages/headless/src/index.js';
import { recordPageErrors } from './page-errors.js';

export const ROOT = fileURLToPath(new URL('../..', import.meta.url));
export const HEAD_SIDECAR = '/data/mri_head_volpack_brainsmall_128x128x84_uint8.json';

/** One recorded `vpt-*` event of an element made by `vt.create`. */
export interface RecordedViewerEvent {
  type: string;
  phase?: string;
  samples?: number;
  reason?: string;
  code?: string;
  message?: string;
  source?: string;
  property?: string;
}

/** `window.vt`: helpers for driving <vpt-viewer> elements from page.evaluate. */
export interface ViewerHelpers {
  /** A <vpt-viewer> with these attributes and a record of its events (el.__events). */
  create(attrs: Record<string, string>, style?: string): any;
  /** create() of the tests' small viewer: a 16³ procedural blob on WebGL 2, no panels, this renderer and sample cap. */
  blob(renderer: string, maxSamples: number): any;
  /** The next event of this type ('load' for vpt-load…) after now (rejects after timeoutMs). */
  next(el: HTMLElement, type: string, timeoutMs?: number): Promise<any>;
  /** Resolves when the element has converged (now or later). */
  converged(el: any, timeoutMs?: number): Promise<void>;
  ldr(el: any): Promise<number[]>;
  frames(n?: number): Promise<void>;
  shadowText(el: HTMLElement, selector: string): string | null;
}

declare global {
  interface Window {
    vt: ViewerHelpers;
  }
}

/** Installs `window.vt`; sent with `page.evaluate(installViewerHelpers)` (typed page code, no strings). */
export function installViewerHelpers(): void {
  window.vt = {
    create(attrs, style = 'width:24px;height:24px') {
      const el = document.createElement('vpt-viewer') as unknown as HTMLElement & { __events: RecordedViewerEvent[] };
      el.__events = [];
      for (const type of ['load', 'progress', 'converged', 'error', 'change']) {
        el.addEventListener('vpt-' + type, (e) => {
          const d = (e as CustomEvent).detail || {};
          el.__events.push({
            type,
            phase: d.phase,
            samples: d.samples,
            reason: d.reason,
            code: d.code,
            message: d.message,
            source: d.source,
            property: d.property,
          });
        });
      }
      for (const [k, v] of Object.entries(attrs)) el.setAttribute(k, v);
      el.setAttribute('style', style);
      document.body.append(el);
      return el;
    },
    blob(renderer, maxSamples) {
      return window.vt.create({
        src: 'procedural:blob?size=16',
        renderer,
        backend: 'webgl2',
        panels: 'none',
        'max-samples': String(maxSamples),
      });
    },
    next(el, type, timeoutMs = 90000) {
      return new Promise((resolve, reject) => {
        const events = (el as HTMLElement & { __events?: RecordedViewerEvent[] }).__events ?? [];
        const t = setTimeout(
          () =>
            reject(
              new Error(
                'no ' + type + ' event within ' + timeoutMs + ' ms; events: ' + JSON.stringify(events.slice(-8)),
              ),
            ),
          timeoutMs,
        );
        el.addEventListener(
          'vpt-' + type,
          (e) => {
            clearTimeout(t);
            resolve((e as CustomEvent).detail);
          },
          { once: true },
        );
      });
    },
    async converged(el, timeoutMs = 90000) {
      await el.whenSettled();
      if (el.converged) return;
      await this.next(el, 'converged', timeoutMs);
    },
    async ldr(el) {
      return Array.from((await el.context.readLDR()) as Uint8Array);
    },
    frames(n = 4) {
      return new Promise<void>((r) => {
        const f = () => (n-- <= 0 ? r() : requestAnimationFrame(f));
        f();
      });
    },
    shadowText(el, selector) {
      const n = el.shadowRoot?.querySelector(selector);
      return n ? (n.textContent ?? '').trim() : null;
    },
  };
}

/** Per-pixel comparison of two RGBA8 images (alpha ignored). */
export function compareRgba(
  a: ArrayLike<number>,
  b: ArrayLike<number>,
): { maxDiff: number; meanDiff: number; differingPixels: number } {
  let max = 0,
    sum = 0,
    differing = 0;
  for (let i = 0; i < a.length; i += 4) {
    let pixelDiff = 0;
    for (let c = 0; c < 3; c++) {
      const d = Math.abs(a[i + c] - b[i + c]);
      pixelDiff = Math.max(pixelDiff, d);
      sum += d;
    }
    if (pixelDiff > 0) differing++;
    max = Math.max(max, pixelDiff);
  }
  return { maxDiff: max, meanDiff: sum / ((a.length / 4) * 3), differingPixels: differing };
}

export function distinctGreys(rgba: ArrayLike<number>): number {
  const s = new Set<number>();
  for (let i = 0; i < rgba.length; i += 4) s.add(rgba[i] * 65536 + rgba[i + 1] * 256 + rgba[i + 2]);
  return s.size;
}

export interface ViewerPage {
  browser: Browser;
  server: StaticServer;
  page: Page;
  /** Console errors and uncaught exceptions seen so far. */
  errors: string[];
  /**
   * Run `fn` in the page, like `page.evaluate(fn, ...args)`, with the viewer helpers
   * (`window.vt`, loosely typed as test bodies use them) as its first argument.
   */
  run<A extends unknown[], R>(fn: (vt: any, ...args: A) => R | Promise<R>, ...args: A): Promise<Awaited<R>>;
  close(): Promise<void>;
}

export async function openViewerPage(browser?: Browser): Promise<ViewerPage> {
  const server = await startStaticServer(ROOT);
  const b = browser ?? (await launchChromium());
  const page = await b.newPage();
  const errors = recordPageErrors(page);
  await page.setViewport({ width: 400, height: 300, deviceScaleFactor: 1 });
  await page.goto(new URL('tests/pages/viewer.html', server.url).href);
  await page.waitForFunction(() => (window as any).__ready === true, { timeout: 60_000 });
  await page.evaluate(installViewerHelpers);
  return {
    browser: b,
    server,
    page,
    errors,
    async run(fn, ...args) {
      const vt = await page.evaluateHandle(() => (window as any).vt);
      try {
        return (await page.evaluate(fn as (vt: unknown, ...a: unknown[]) => unknown, vt, ...args)) as never;
      } finally {
        await vt.dispose();
      }
    },
    async close() {
      await page.close().catch(() => {});
      if (!browser) await b.close().catch(() => {});
      await server.close();
    },
  };
}

/**
 * One viewer page for a test file, opened in beforeAll (in front: requestAnimationFrame, which
 * drives refinement, stops in a background tab) and closed in afterAll; call the returned
 * function inside a test.
 */
export function useViewerPage(): () => ViewerPage {
  let vp: ViewerPage | undefined;
  beforeAll(async () => {
    vp = await openViewerPage();
    await vp.page.bringToFront();
  });
  afterAll(async () => {
    await vp?.close();
  });
  return () => {
    if (!vp) throw new Error('the viewer page is not open');
    return vp;
  };
}

/** The exposure step of a scene file's post chain (the element takes it as an attribute). */
export function sceneExposure(desc: { post?: unknown }): number {
  const steps = (Array.isArray(desc.post) ? desc.post : []) as { type?: string; exposure?: number }[];
  return steps.find((s) => s.type === 'exposure')?.exposure ?? 0;
}

/** What a gallery scene file (`readSceneFile`) needs to hand a `<vpt-viewer>`. */
export interface SceneFileLike {
  transferFunction?: unknown;
  camera?: unknown;
  environment?: unknown;
  densityScale?: number;
  seed?: number;
  post?: unknown;
}

/**
 * The attributes that make a `<vpt-viewer>` render what `vpt-render` renders for a scene file
 * on the bundled head: the same transfer function, camera, environment, density, seed and
 * exposure, ACES as the scene files' tone mapper, and `maxSamples` iterations, no panels.
 */
export function sceneFileAttributes(
  desc: SceneFileLike,
  opts: { renderer: string; backend: string; maxSamples: number },
): Record<string, string> {
  return {
    src: HEAD_SIDECAR,
    renderer: opts.renderer,
    backend: opts.backend,
    panels: 'none',
    'transfer-function': JSON.stringify(desc.transferFunction),
    camera: JSON.stringify(desc.camera),
    environment: JSON.stringify(desc.environment),
    'density-scale': String(desc.densityScale),
    seed: String(desc.seed),
    exposure: String(sceneExposure(desc)),
    'tone-mapper': 'aces',
    'max-samples': String(opts.maxSamples),
  };
}

/**
 * A viewer page and a headless `vpt-render` page in the same browser (tests compare the
 * viewer's images with the headless renderer's), the viewer in front: requestAnimationFrame,
 * which drives refinement, does not run in a background tab.
 */
export async function openViewerAndHeadless(): Promise<{
  vp: ViewerPage;
  headless: VptPageSession;
  close(): Promise<void>;
}> {
  const vp = await openViewerPage();
  const headless = await openVptPage({ browser: vp.browser });
  await vp.page.bringToFront();
  return {
    vp,
    headless,
    async close() {
      await headless.close();
      await vp.close();
    },
  };
}
