// Development helper: serve the repository root on 127.0.0.1 and open one page in
// headless Chromium (SwiftShader WebGL 2 + WebGPU), printing the page's console.
// Usage: node tools/dev-browser.mjs tests/pages/some-page.html [timeoutSeconds]
// The page signals completion by setting `window.__done = true` (or times out).
import { parseCliOrExit } from '@vpt/cli-options';

const { page: pagePath, timeout: timeoutSeconds } = parseCliOrExit({
  name: 'node tools/dev-browser.mjs',
  synopsis: 'PAGE [TIMEOUT]',
  summary:
    "Serve the repository root on 127.0.0.1 and open PAGE in headless Chromium, printing the page's console,\n" +
    'until the page sets window.__done = true (needs pnpm run build).',
  positionals: [
    { key: 'page', name: 'PAGE', type: 'string', required: true, description: 'a path under the repository root' },
    { key: 'timeout', name: 'TIMEOUT', type: 'number', min: 0, default: 60, description: 'seconds to wait' },
  ],
});
// After the arguments, so that --help works before a build.
const { launchChromium, pageWithErrors, REPO_ROOT, startStaticServer } = await import('./tool-browser.mjs');

const server = await startStaticServer(REPO_ROOT);
const browser = await launchChromium({ webgpu: true });
try {
  const { page } = await pageWithErrors(browser, { echo: true });
  await page.goto(new URL(pagePath, server.url).href);
  const timeout = timeoutSeconds * 1000;
  try {
    await page.waitForFunction(() => window.__done === true, { timeout, polling: 100 });
  } catch {
    console.log('[dev-browser] timed out');
  }
} finally {
  await browser.close();
  await server.close();
}
