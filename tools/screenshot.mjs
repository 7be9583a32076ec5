// Screenshot a page served on 127.0.0.1 once it sets window.__demoReady (for docs and manual checks).
// Usage: node tools/screenshot.mjs <url> <out.png> [waitMs]   (NO_READY=1 for pages without __demoReady)
import puppeteer from 'puppeteer-core';
const browser = await puppeteer.launch({
  executablePath: '/usr/bin/chromium',
  headless: true,
  args: [
    '--no-sandbox',
    '--disable-background-networking',
    '--disable-component-update',
    '--disable-sync',
    '--no-first-run',
    '--disable-quic',
    '--use-angle=swiftshader',
    '--enable-unsafe-swiftshader',
    '--enable-unsafe-webgpu',
    '--enable-features=Vulkan',
    '--use-vulkan=swiftshader',
    '--use-webgpu-adapter=swiftshader',
  ],
});
const page = await browser.newPage();
const errors = [];
page.on('console', (m) => {
  if (m.type() === 'error') errors.push(m.text());
});
page.on('pageerror', (e) => errors.push(e.message));
await page.setViewport({ width: 1000, height: Number(process.env.HEIGHT ?? 620) });
await page.goto(process.argv[2]);
if (!process.env.NO_READY) await page.waitForFunction('window.__demoReady === true', { timeout: 60000 });
await new Promise((r) => setTimeout(r, Number(process.argv[4] ?? 15000)));
if (!process.env.NO_READY) console.log('stats:', await page.$eval('#stats', (e) => e.value));
console.log('errors:', JSON.stringify(errors));
await page.screenshot({ path: process.argv[3] });
await browser.close();
