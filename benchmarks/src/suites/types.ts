import type { Page } from 'puppeteer-core';
import type { Backend, Preset, RendererConfig, SceneSpec } from '../configs.js';

export interface SuiteContext {
  page: Page;
  preset: Preset;
  backends: Backend[];
  /** Renderer configurations whose package is in this build. */
  renderers: RendererConfig[];
  mcrtVariants: RendererConfig[];
  /** Fetched real volumes present on this machine (FETCHED_SCENES), for the error suite. */
  fetchedScenes: Record<string, SceneSpec>;
  log: (line: string) => void;
}

/** evaluate `window.bench.<fn>(...args)` in the page. */
export async function bench<T>(page: Page, fn: string, ...args: unknown[]): Promise<T> {
  return page.evaluate(
    (fn, args) => (window as unknown as { bench: Record<string, (...a: unknown[]) => unknown> }).bench[fn](...args),
    fn,
    args,
  ) as Promise<T>;
}
