// Screenshots of <vpt-viewer> and the gallery for docs/images/ (run after `pnpm run build`
// and `pnpm --filter @vpt/gallery run build`). Renders on SwiftShader, so it takes minutes.
// Usage: node tools/viewer-screenshots.mjs [name…]   (no names: all of them)
import { launchChromium, startStaticServer } from '../packages/headless/dist/index.js';

const SHOTS = {
  // The gallery page as README's first command shows it.
  'gallery-head-eam': {
    url: 'apps/gallery/dist/index.html?dataset=mri_head_volpack_brainsmall_128x128x84_uint8&renderer=eam&max=16',
    size: [1280, 800],
    ready: 'window.__galleryReady && window.gallery.viewer.samples >= 16',
  },
  'gallery-head-mcrt': {
    url: 'apps/gallery/dist/index.html?dataset=mri_head_volpack_brainsmall_128x128x84_uint8&renderer=mcrt&max=64&scale=0.6',
    size: [1280, 800],
    ready: 'window.__galleryReady && window.gallery.viewer.samples >= 64',
  },
  'gallery-ct-head-iso': {
    url: 'apps/gallery/dist/index.html?dataset=ct_head_invesalius_256x256x108_int16&renderer=iso&max=32&scale=0.75',
    size: [1280, 800],
    ready: 'window.__galleryReady && window.gallery.viewer.samples >= 32',
  },
  'gallery-compare': {
    url: 'apps/gallery/dist/compare.html?dataset=mri_head_volpack_brainsmall_128x128x84_uint8&max=12&scale=0.5',
    size: [1100, 1060],
    ready: 'window.__compareReady && window.compare.views.every((v) => v.samples >= 12)',
  },
  // What a newcomer sees: README's page snippet as written (mcrt, 800x600), a 400x300 element at rest, a 320x240 one.
  'newcomer-readme-page': {
    url: 'tools/newcomer.html?renderer=mcrt&w=800&h=600',
    size: [800, 600],
    ready: 'window.viewer?.samples >= 4',
  },
  'newcomer-400x300': {
    url: 'tools/newcomer.html?w=400&h=300',
    size: [400, 300],
    ready: 'window.viewer?.samples >= 24',
  },
  'newcomer-320x240': {
    url: 'tools/newcomer.html?w=320&h=240&renderer=iso',
    size: [320, 240],
    ready: 'window.viewer?.samples >= 16',
  },
  // The element alone with every panel open and a 2D transfer function.
  'viewer-element-2d-tf': {
    url: 'apps/gallery/dist/index.html?dataset=mri_head_volpack_brainsmall_128x128x84_uint8&renderer=eam&tf=boundaries&density=60&max=12',
    size: [1280, 1180],
    ready: 'window.__galleryReady && window.gallery.viewer.samples >= 12',
    before: `document.querySelector('#viewer').style.height = '1000px'; document.querySelector('#viewer').shadowRoot.querySelectorAll('details').forEach((d) => { d.open = true; });`,
    clip: '#viewer',
  },
};

const names = process.argv.slice(2).length ? process.argv.slice(2) : Object.keys(SHOTS);
const server = await startStaticServer(new URL('..', import.meta.url).pathname);
const browser = await launchChromium({ webgpu: true });
try {
  for (const name of names) {
    const s = SHOTS[name];
    if (!s) throw new Error(`unknown screenshot ${name} (${Object.keys(SHOTS).join(', ')})`);
    const page = await browser.newPage();
    const errors = [];
    page.on('console', (m) => {
      if (m.type() === 'error') errors.push(m.text());
    });
    page.on('pageerror', (e) => errors.push(e.message));
    await page.setViewport({ width: s.size[0], height: s.size[1] });
    const t0 = Date.now();
    await page.goto(new URL(s.url, server.url).href);
    if (s.before) {
      await page.waitForFunction('window.__galleryReady || window.__compareReady', { timeout: 120_000 });
      await page.evaluate(s.before);
    }
    await page.waitForFunction(s.ready, { timeout: 900_000, polling: 500 });
    await new Promise((r) => setTimeout(r, 500));
    const out = `docs/images/${name}.png`;
    if (s.clip) await (await page.$(s.clip)).screenshot({ path: out });
    else await page.screenshot({ path: out });
    console.log(
      `${out}  ${((Date.now() - t0) / 1000).toFixed(0)} s${errors.length ? `  console errors: ${JSON.stringify(errors)}` : ''}`,
    );
    await page.close();
  }
} finally {
  await browser.close();
  await server.close();
}
