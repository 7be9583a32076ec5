/**
 * One headless Chromium page per test file with `window.vpt` = { core, mip, eam, post }, `window.t` (in-page.ts) and `window.tv` (test-volumes.ts)
 * loaded from the built packages (run `pnpm build` first).
 */
import { afterAll, beforeAll } from 'vitest';
import { openVptPage, type VptPageSession } from '../../packages/headless/src/index.js';
import { installInPageHelpers } from './in-page.js';
import { installTestVolumes } from './test-volumes.js';

export function usePage(): () => VptPageSession {
  let session: VptPageSession | undefined;
  beforeAll(async () => {
    session = await openVptPage();
    await session.page.evaluate(installInPageHelpers);
    await session.page.evaluate(installTestVolumes);
  });
  afterAll(async () => {
    await session?.close();
  });
  return () => {
    if (!session) throw new Error('page not open');
    return session;
  };
}

export const BACKENDS = ['webgl2', 'webgpu'] as const;
