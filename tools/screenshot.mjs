// Screenshot a page served on 127.0.0.1 once it sets window.__demoReady (for docs and manual checks).
// Usage: node tools/screenshot.mjs <url> <out.png> [waitMs]   (NO_READY=1 for pages without __demoReady)
import { parseCliOrExit } from '@vpt/cli-options';

const { url, out, wait } = parseCliOrExit({
  name: 'node tools/screenshot.mjs',
  synopsis: 'URL OUT.png [WAIT_MS]',
  summary:
    'Screenshot a page once it sets window.__demoReady (NO_READY=1 for pages without it; HEIGHT=N for the\n' +
    'viewport height, default 620; needs pnpm run build).',
  positionals: [
    { key: 'url', name: 'URL', type: 'string', required: true, description: 'the page' },
    { key: 'out', name: 'OUT.png', type: 'string', required: true, description: 'the PNG to write' },
    { key: 'wait', name: 'WAIT_MS', type: 'number', min: 0, default: 15000, description: 'ms to wait after ready' },
  ],
});
// After the arguments, so that --help works before a build.
const { launchChromium, pageWithErrors } = await import('./tool-browser.mjs');

const browser = await launchChromium({ webgpu: true });
try {
  const { page, errors } = await pageWithErrors(browser);
  await page.setViewport({ width: 1000, height: Number(process.env.HEIGHT ?? 620) });
  await page.goto(url);
  if (!process.env.NO_READY) await page.waitForFunction(() => window.__demoReady === true, { timeout: 60000 });
  await new Promise((r) => setTimeout(r, wait));
  if (!process.env.NO_READY) console.log('stats:', await page.$eval('#stats', (e) => e.value));
  console.log('errors:', JSON.stringify(errors));
  await page.screenshot({ path: out });
} finally {
  await browser.close();
}
