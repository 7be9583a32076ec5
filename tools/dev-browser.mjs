// Development helper: serve the repository root on 127.0.0.1 and open one page in
// headless Chromium (SwiftShader WebGL 2 + WebGPU), printing the page's console.
// Usage: node tools/dev-browser.mjs tests/pages/some-page.html [timeoutSeconds]
// The page signals completion by setting `window.__done = true` (or times out).
import { launchChromium, pageWithErrors, REPO_ROOT, startStaticServer } from './tool-browser.mjs';

const server = await startStaticServer(REPO_ROOT);
const browser = await launchChromium({ webgpu: true });
try {
  const { page } = await pageWithErrors(browser, { echo: true });
  await page.goto(new URL(process.argv[2], server.url).href);
  const timeout = Number(process.argv[3] ?? 60) * 1000;
  try {
    await page.waitForFunction(() => window.__done === true, { timeout, polling: 100 });
  } catch {
    console.log('[dev-browser] timed out');
  }
} finally {
  await browser.close();
  await server.close();
}
