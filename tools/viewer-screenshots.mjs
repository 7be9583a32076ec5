// Screenshots of <vpt-viewer> and the gallery for docs/images/ (run after `pnpm run build`
// and `pnpm --filter @vpt/gallery run build`). Renders on SwiftShader, so it takes minutes.
// Usage: node tools/viewer-screenshots.mjs [name…]   (no names: all of them)
import { parseCliOrExit } from '@vpt/cli-options';

const HEAD = 'mri_head_volpack_brainsmall_128x128x84_uint8';

/** A gallery page (`page`: index or compare) rendered until every view has `samples` samples (the `max` it is given). */
const gallery = (page, query, samples, size, extra = {}) => ({
  url: `apps/gallery/dist/${page}.html?${query}&max=${samples}`,
  size,
  samples,
  ready:
    page === 'compare'
      ? (n) => window.__compareReady && window.compare.views.every((v) => v.samples >= n)
      : (n) => window.__galleryReady && window.gallery.viewer.samples >= n,
  ...extra,
});

/** README's page snippet (tools/newcomer.html) at a size, until `samples` samples. */
const newcomer = (query, samples, size) => ({
  url: `tools/newcomer.html?${query}`,
  size,
  samples,
  ready: (n) => window.viewer?.samples >= n,
});

const SHOTS = {
  // The gallery page as README's first command shows it.
  'gallery-head-eam': gallery('index', `dataset=${HEAD}&renderer=eam`, 16, [1280, 800]),
  'gallery-head-mcrt': gallery('index', `dataset=${HEAD}&renderer=mcrt&scale=0.6`, 64, [1280, 800]),
  'gallery-ct-head-iso': gallery(
    'index',
    'dataset=ct_head_invesalius_256x256x108_int16&renderer=iso&scale=0.75',
    32,
    [1280, 800],
  ),
  'gallery-compare': gallery('compare', `dataset=${HEAD}&scale=0.5`, 12, [1100, 1060]),
  // What a newcomer sees: README's page snippet as written (mcrt, 800x600), a 400x300 element at rest, a 320x240 one.
  'newcomer-readme-page': newcomer('renderer=mcrt&w=800&h=600', 4, [800, 600]),
  'newcomer-400x300': newcomer('w=400&h=300', 24, [400, 300]),
  'newcomer-320x240': newcomer('w=320&h=240&renderer=iso', 16, [320, 240]),
  // The element alone with every panel open and a 2D transfer function.
  'viewer-element-2d-tf': gallery('index', `dataset=${HEAD}&renderer=eam&tf=boundaries&density=60`, 12, [1280, 1180], {
    before: () => {
      const viewer = document.querySelector('#viewer');
      viewer.style.height = '1000px';
      viewer.shadowRoot.querySelectorAll('details').forEach((d) => {
        d.open = true;
      });
    },
    clip: '#viewer',
  }),
};

const { names: given } = parseCliOrExit({
  name: 'node tools/viewer-screenshots.mjs',
  synopsis: '[NAME…]',
  summary:
    'Screenshots of <vpt-viewer> and the gallery for docs/images/ (after pnpm run build and\n' +
    'pnpm --filter @vpt/gallery run build; minutes on SwiftShader).',
  positionals: [
    {
      key: 'names',
      name: 'NAME',
      type: 'string',
      variadic: true,
      choices: Object.keys(SHOTS),
      description: `the screenshots to take (default: all): ${Object.keys(SHOTS).join(', ')}`,
    },
  ],
});
const names = given.length ? given : Object.keys(SHOTS);
// After the arguments, so that --help works before a build.
const { launchChromium, pageWithErrors, REPO_ROOT, startStaticServer } = await import('./tool-browser.mjs');
const server = await startStaticServer(REPO_ROOT);
const browser = await launchChromium({ webgpu: true });
try {
  for (const name of names) {
    const s = SHOTS[name];
    if (!s) throw new Error(`unknown screenshot ${name} (${Object.keys(SHOTS).join(', ')})`);
    const { page, errors } = await pageWithErrors(browser);
    await page.setViewport({ width: s.size[0], height: s.size[1] });
    const t0 = Date.now();
    await page.goto(new URL(s.url, server.url).href);
    if (s.before) {
      await page.waitForFunction(() => window.__galleryReady || window.__compareReady, { timeout: 120_000 });
      await page.evaluate(s.before);
    }
    await page.waitForFunction(s.ready, { timeout: 900_000, polling: 500 }, s.samples);
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
