// Screenshot a page served on 127.0.0.1 once it sets window.__demoReady (for docs and manual checks).
// Usage: node tools/screenshot.mjs <url> <out.png> [waitMs]   (NO_READY=1 for pages without __demoReady)
import { launchChromium, pageWithErrors } from './tool-browser.mjs';

const browser = await launchChromium({ webgpu: true });
try {
  const { page, errors } = await pageWithErrors(browser);
  await page.setViewport({ width: 1000, height: Number(process.env.HEIGHT ?? 620) });
  await page.goto(process.argv[2]);
  if (!process.env.NO_READY) await page.waitForFunction(() => window.__demoReady === true, { timeout: 60000 });
  await new Promise((r) => setTimeout(r, Number(process.argv[4] ?? 15000)));
  if (!process.env.NO_READY) console.log('stats:', await page.$eval('#stats', (e) => e.value));
  console.log('errors:', JSON.stringify(errors));
  await page.screenshot({ path: process.argv[3] });
} finally {
  await browser.close();
}
