/**
 * One headless Chromium page per test file with `window.vpt` = { core, mip, eam, post }, `window.t` (in-page.ts) and `window.tv` (test-volumes.ts)
 * loaded from the built packages (run `pnpm build` first); `window.mt` (mcrt-in-page.ts) too with `{ mcrt: true }`.
 */
import { afterAll, beforeAll } from 'vitest';
import { openVptPage, type VptPageSession } from '../../packages/headless/src/index.js';
import { installInPageHelpers } from './in-page.js';
import { installMcrtHelpers } from './mcrt-in-page.js';
import { installTestVolumes } from './test-volumes.js';

/**
 * What a test body run in the page receives first: the page's API and the installed helpers,
 * loosely typed as test bodies use them (`mt` only with `usePage({ mcrt: true })`).
 */
export interface PageEnv {
  vpt: any;
  core: any;
  t: any;
  tv: any;
  mt: any;
}

export interface PageAccess {
  /** The open session (its `page`, `server`…). */
  (): VptPageSession;
  /**
   * Run `fn` in the page, like `page.evaluate(fn, ...args)` (puppeteer sends its compiled
   * source, so it may use only its parameters), with the page's API and helpers as its first
   * argument: `page.run(async ({ t, core }, backend) => …, backend)`.
   */
  run<A extends unknown[], R>(fn: (env: PageEnv, ...args: A) => R | Promise<R>, ...args: A): Promise<Awaited<R>>;
}

export function usePage(options: { mcrt?: boolean } = {}): PageAccess {
  let session: VptPageSession | undefined;
  beforeAll(async () => {
    session = await openVptPage();
    await session.page.evaluate(installInPageHelpers);
    await session.page.evaluate(installTestVolumes);
    if (options.mcrt) await installMcrtHelpers(session.page);
  });
  afterAll(async () => {
    await session?.close();
  });
  const access = () => {
    if (!session) throw new Error('page not open');
    return session;
  };
  const run: PageAccess['run'] = async (fn, ...args) => {
    const { page } = access();
    const env = await page.evaluateHandle((): PageEnv => ({
      vpt: window.vpt,
      core: window.vpt.core,
      t: window.t,
      tv: window.tv,
      mt: window.mt,
    }));
    try {
      return (await page.evaluate(fn as (env: unknown, ...a: unknown[]) => unknown, env, ...args)) as never;
    } finally {
      await env.dispose();
    }
  };
  return Object.assign(access, { run });
}

export const BACKENDS = ['webgl2', 'webgpu'] as const;
