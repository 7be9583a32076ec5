// What the tools share: headless Chromium and the static server from @vpt/headless (run
// `pnpm run build` first), and a page that collects its console errors.
export { launchChromium, startStaticServer } from '../packages/headless/dist/index.js';

/** The repository root, which the tools serve. */
export const REPO_ROOT = new URL('..', import.meta.url).pathname;

/** A new page whose console errors and uncaught exceptions land in `errors` (and, with `echo`, on stdout). */
export async function pageWithErrors(browser, { echo = false } = {}) {
  const page = await browser.newPage();
  const errors = [];
  page.on('console', (m) => {
    if (echo) console.log(`[page ${m.type()}] ${m.text()}`);
    if (m.type() === 'error') errors.push(m.text());
  });
  page.on('pageerror', (e) => {
    if (echo) console.log(`[page error] ${e.message}`);
    errors.push(e.message);
  });
  return { page, errors };
}
