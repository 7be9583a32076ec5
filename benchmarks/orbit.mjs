#!/usr/bin/env node
/**
 * An orbit in `<vpt-viewer>` (issue 26 item 4): a scripted 2-second orbit at 30 camera updates
 * per second on the bundled head, through the element's user-camera path (so adaptive
 * resolution lowers the render size as it does under a drag), on WebGL 2 and WebGPU, with MCRT
 * and EAM. Configurations: plain resets (temporal="off" denoise="off"), temporal reuse, the
 * denoiser alone, and both. Before every 4th update the image shown (after the denoiser where it
 * is on; upscaled by nearest neighbour to the element's size when adaptive resolution shrank it)
 * is compared with the converged image of that view: the RMSE (linear RGB), the render size
 * chosen and the samples behind the image are recorded, and the animation frames' intervals give
 * the frame time. Configurations are interleaved (A B C D E, then E D C B A); the load average
 * is printed. `defaults` is the element's own choice: temporal="on" denoise="auto". The references: a separate element per renderer, temporal and denoiser off, each
 * view refined to --ref-samples.
 *
 *   pnpm run build && node benchmarks/orbit.mjs [--size 64] [--rounds 2] [--renderers mcrt,eam] [--backends webgl2,webgpu] [--configs defaults,...]
 */
import fs from 'node:fs';
import http from 'node:http';
import os from 'node:os';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import { parseCliOrExit } from '@vpt/cli-options';

const root = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '..');
const args = parseCliOrExit({
  name: 'node benchmarks/orbit.mjs',
  synopsis:
    '[--size N] [--rounds N] [--renderers mcrt,eam] [--backends webgl2,webgpu] [--ref-samples N] [--configs LIST]',
  summary:
    'Per-frame RMSE against the converged view during a scripted orbit in <vpt-viewer>, with and without temporal reuse and denoising (needs pnpm run build).',
  options: {
    size: { type: 'integer', min: 8, max: 512, default: 64, description: "the element's side in CSS pixels (DPR 1)" },
    rounds: { type: 'integer', min: 1, default: 2, description: 'interleaved rounds of every configuration' },
    renderers: { type: 'list', choices: ['mcrt', 'eam'], default: ['mcrt', 'eam'], description: 'renderers' },
    backends: { type: 'list', choices: ['webgl2', 'webgpu'], default: ['webgl2', 'webgpu'], description: 'backends' },
    'ref-samples': {
      type: 'integer',
      min: 1,
      description: "samples per pixel of each view's converged image (default: MCRT 256, EAM 64)",
    },
    degrees: { type: 'number', min: 0, max: 360, default: 30, description: 'the orbit angle over the 2 seconds' },
    configs: {
      type: 'list',
      choices: ['temporal', 'denoise', 'temporal+denoise', 'defaults'],
      default: ['temporal', 'denoise', 'temporal+denoise', 'defaults'],
      description: 'configurations besides plain (always run: the ratios are against it)',
    },
  },
});
const { launchChromium } = await import(path.join(root, 'packages/headless/dist/index.js'));

const UPDATES = 60; // 2 s at 30 updates per second
const EVERY = 4; // measure before every 4th update
const HEAD = '/data/mri_head_volpack_brainsmall_128x128x84_uint8.json';
// 'defaults' is the element's own choice (temporal reuse on, denoise="auto": EAM stops the denoiser
// while the camera moves, MCRT keeps it); the ratios are against the first configuration, plain.
const ALL_CONFIGS = [
  { name: 'plain', temporal: 'off', denoise: 'off' },
  { name: 'temporal', temporal: 'on', denoise: 'off' },
  { name: 'denoise', temporal: 'off', denoise: 'on' },
  { name: 'temporal+denoise', temporal: 'on', denoise: 'on' },
  { name: 'defaults', temporal: 'on', denoise: 'auto' },
];
const CONFIGS = ALL_CONFIGS.filter((c) => c.name === 'plain' || args.configs.includes(c.name));

const server = http.createServer((req, res) => {
  const file = path.resolve(root, '.' + decodeURIComponent(new URL(req.url, 'http://x').pathname));
  if (!file.startsWith(root) || !fs.existsSync(file) || !fs.statSync(file).isFile())
    return void res.writeHead(404).end();
  const type = /\.m?js$/.test(file)
    ? 'text/javascript'
    : /\.html$/.test(file)
      ? 'text/html'
      : 'application/octet-stream';
  res.writeHead(200, { 'content-type': type, 'cache-control': 'max-age=3600' });
  res.end(fs.readFileSync(file));
});
await new Promise((r) => server.listen(0, '127.0.0.1', r));
const base = `http://127.0.0.1:${server.address().port}/`;
const browser = await launchChromium();

async function openPage() {
  const page = await browser.newPage();
  await page.setViewport({ width: args.size + 40, height: args.size + 40, deviceScaleFactor: 1 });
  await page.goto(new URL('tests/pages/viewer.html', base).href);
  await page.waitForFunction(() => window.__ready === true, { timeout: 120_000 });
  page.on('pageerror', (e) => console.error('page error:', e.message));
  return page;
}

// The page side: an element with these attributes, loaded and settled, its first refining frame shown.
const PAGE_HELPERS = `
window.makeViewer = async (attrs, size) => {
  const el = document.createElement('vpt-viewer');
  for (const [k, v] of Object.entries(attrs)) el.setAttribute(k, v);
  el.setAttribute('style', 'width:' + size + 'px;height:' + size + 'px');
  document.body.append(el);
  await new Promise((resolve, reject) => {
    el.addEventListener('vpt-error', (e) => reject(new Error(e.detail.message)), { once: true });
    el.addEventListener('vpt-load', resolve, { once: true });
    el.src = attrs.src;
  });
  await el.whenSettled();
  return el;
};
// The image shown against the reference (size² linear RGB): as shown (nearest upscale to the
// element's size) and at the render size (the reference box-averaged over each render pixel's
// footprint: a render pixel's estimate is the mean over its footprint, so this is the converged
// image at that size); the samples behind it (iterations since the reset; with temporal reuse the
// mean over pixels of the samples the resolve says each stands for).
window.measure = async (el, want, size) => {
  const iterations = el.context.stats.iterations;
  const hdr = await el.context.readHDR({ afterPost: el.denoised });
  const { width, height } = el.context.size;
  let sq = 0, n = 0;
  for (let y = 0; y < size; y++)
    for (let x = 0; x < size; x++) {
      const sx = Math.min(width - 1, Math.floor((x * width) / size)), sy = Math.min(height - 1, Math.floor((y * height) / size));
      for (let c = 0; c < 3; c++) { const d = hdr[4 * (sy * width + sx) + c] - want[4 * (y * size + x) + c]; sq += d * d; n++; }
    }
  const shown = Math.sqrt(sq / n);
  const cover = (i, n, j) => Math.max(0, Math.min((i + 1) * size / n, j + 1) - Math.max((i * size) / n, j));
  sq = 0; n = 0;
  for (let py = 0; py < height; py++)
    for (let px = 0; px < width; px++) {
      const acc = [0, 0, 0]; let wsum = 0;
      for (let y = Math.floor((py * size) / height); y < Math.min(size, Math.ceil(((py + 1) * size) / height)); y++)
        for (let x = Math.floor((px * size) / width); x < Math.min(size, Math.ceil(((px + 1) * size) / width)); x++) {
          const w = cover(px, width, x) * cover(py, height, y);
          for (let c = 0; c < 3; c++) acc[c] += w * want[4 * (y * size + x) + c];
          wsum += w;
        }
      for (let c = 0; c < 3; c++) { const d = hdr[4 * (py * width + px) + c] - acc[c] / wsum; sq += d * d; n++; }
    }
  const state = el.context.readTemporalState ? await el.context.readTemporalState() : null;
  let effective = el.context.stats.iterations;
  if (state) { let s = 0; for (let i = 1; i < state.length; i += 4) s += state[i]; effective = s / (state.length / 4); }
  const { msPerIteration, msPostPerFrame } = el.context.stats;
  return { rmse: shown, rmseAtSize: Math.sqrt(sq / n), width, height, samples: iterations, effective, msPerIteration, msPostPerFrame };
};
window.frames = (n) => new Promise((r) => { const f = () => (n-- <= 0 ? r() : requestAnimationFrame(f)); f(); });
window.orbitCamera = (c, angle) => {
  const x = c.position[0] - c.target[0], z = c.position[2] - c.target[2];
  return { ...c, position: [c.target[0] + x * Math.cos(angle) + z * Math.sin(angle), c.position[1], c.target[2] - x * Math.sin(angle) + z * Math.cos(angle)] };
};
`;

/** The converged image of each measured view (linear RGB, the element's size). */
async function references(renderer, refSamples) {
  const page = await openPage();
  await page.evaluate(PAGE_HELPERS);
  const out = await page.evaluate(
    async (renderer, src, size, refSamples, updates, every, degrees) => {
      const el = await window.makeViewer(
        {
          src,
          renderer,
          backend: 'webgl2',
          panels: 'none',
          temporal: 'off',
          denoise: 'off',
          'max-samples': String(refSamples),
          'hide-stats': '',
          'hide-progress': '',
        },
        size,
      );
      const start = el.camera;
      const refs = [];
      for (let k = every - 1; k < updates; k += every) {
        const cam = window.orbitCamera(start, ((degrees * Math.PI) / 180) * (k / updates));
        el.camera = cam;
        await el.updateComplete;
        await window.frames(2);
        if (!el.converged || el.samples < refSamples)
          await new Promise((r) => el.addEventListener('vpt-converged', r, { once: true }));
        refs.push(Array.from(await el.context.readHDR()));
      }
      el.remove();
      return { refs, start };
    },
    renderer,
    HEAD,
    args.size,
    refSamples,
    UPDATES,
    EVERY,
    args.degrees,
  );
  await page.close();
  return out;
}

/** One orbit in one configuration: per measured view the RMSE, render size and samples; the frame intervals. */
async function orbit(renderer, backend, config, ref) {
  const page = await openPage();
  await page.evaluate(PAGE_HELPERS);
  const r = await page.evaluate(
    async (renderer, backend, config, src, size, updates, every, degrees, ref) => {
      const el = await window.makeViewer(
        {
          src,
          renderer,
          backend,
          panels: 'none',
          temporal: config.temporal,
          denoise: config.denoise,
          'hide-stats': '',
          'hide-progress': '',
        },
        size,
      );
      el.camera = ref.start;
      await el.updateComplete;
      // Rest a second at the start view (temporal reuse's module loads, the loop learns its rate).
      await new Promise((r) => setTimeout(r, 1000));
      const frameTimes = [];
      let last = performance.now(),
        running = true;
      const tick = () => {
        const now = performance.now();
        frameTimes.push(now - last);
        last = now;
        if (running) requestAnimationFrame(tick);
      };
      requestAnimationFrame(tick);
      const rows = [];
      const t0 = performance.now();
      for (let k = 0; k < updates; k++) {
        const wait = t0 + (k * 1000) / 30 - performance.now();
        if (wait > 0) await new Promise((r) => setTimeout(r, wait));
        // Just before update k, the image of view k − 1 (measured at every 4th).
        if (k % every === 0 && k > 0)
          rows.push({ view: k - 1, ...(await window.measure(el, ref.refs[k / every - 1], size)) });
        el.onUserCamera(window.orbitCamera(ref.start, ((degrees * Math.PI) / 180) * (k / updates)));
      }
      await new Promise((r) => setTimeout(r, Math.max(0, t0 + (updates * 1000) / 30 - performance.now())));
      rows.push({ view: updates - 1, ...(await window.measure(el, ref.refs[ref.refs.length - 1], size)) });
      running = false;
      const seconds = (performance.now() - t0) / 1000;
      el.remove();
      return { rows, frameTimes: frameTimes.slice(1), seconds };
    },
    renderer,
    backend,
    config,
    HEAD,
    args.size,
    UPDATES,
    EVERY,
    args.degrees,
    ref,
  );
  await page.close();
  return r;
}

const mean = (a) => a.reduce((s, x) => s + x, 0) / a.length;
const median = (a) => [...a].sort((x, y) => x - y)[Math.floor(a.length / 2)];
const load0 = os.loadavg();
console.log(
  `orbit: ${UPDATES} updates at 30 per second (${args.degrees}° about the vertical axis), element ${args.size}² CSS px, DPR 1; load average ${load0.map((x) => x.toFixed(2)).join(' ')}`,
);
const results = [];
for (const renderer of args.renderers) {
  const refSamples = args['ref-samples'] ?? (renderer === 'mcrt' ? 256 : 64);
  const ref = await references(renderer, refSamples);
  for (const backend of args.backends) {
    const runs = Object.fromEntries(CONFIGS.map((c) => [c.name, []]));
    for (let round = 0; round < args.rounds; round++)
      for (const config of round % 2 ? [...CONFIGS].reverse() : CONFIGS)
        runs[config.name].push(await orbit(renderer, backend, config, ref));
    const load = os.loadavg();
    console.log(
      `\n${renderer} on ${backend} (reference ${refSamples} spp; load average now ${load.map((x) => x.toFixed(2)).join(' ')})`,
    );
    console.log(
      '| configuration | mean RMSE at render size | × plain | mean RMSE as shown | × plain | median frame (ms) | render side (median) | new samples (median) | samples per pixel with history (mean) |',
    );
    console.log('|---|---|---|---|---|---|---|---|---|');
    const all = (name, key) => runs[name].flatMap((r) => r.rows.map((x) => x[key]));
    const plainAt = mean(all('plain', 'rmseAtSize')),
      plainShown = mean(all('plain', 'rmse'));
    for (const c of CONFIGS) {
      const at = mean(all(c.name, 'rmseAtSize')),
        shown = mean(all(c.name, 'rmse'));
      const frame = median(runs[c.name].flatMap((r) => r.frameTimes));
      const side = median(all(c.name, 'width'));
      const samples = median(all(c.name, 'samples'));
      const effective = mean(all(c.name, 'effective'));
      console.log(
        `| ${c.name} | ${at.toFixed(4)} | ${(at / plainAt).toFixed(2)} | ${shown.toFixed(4)} | ${(shown / plainShown).toFixed(2)} | ${frame.toFixed(1)} | ${side} | ${samples} | ${effective.toFixed(1)} |`,
      );
      results.push({
        renderer,
        backend,
        config: c.name,
        rmseAtSize: at,
        rmseShown: shown,
        frameMs: frame,
        side,
        samples,
        effective,
        runs: runs[c.name],
      });
    }
    if (process.env.VPT_BENCH_DEBUG)
      for (const c of CONFIGS)
        console.log(
          c.name,
          runs[c.name]
            .map((r) =>
              r.rows
                .map(
                  (x) =>
                    `${x.rmseAtSize.toFixed(3)}/${x.rmse.toFixed(3)}@${x.width}:${x.samples}:${x.effective.toFixed(1)}:${x.msPerIteration.toFixed(1)}+${x.msPostPerFrame.toFixed(1)}ms`,
                )
                .join(' '),
            )
            .join(' | '),
        );
  }
}
const load1 = os.loadavg();
console.log(`\nload average at the end ${load1.map((x) => x.toFixed(2)).join(' ')}`);
if (process.env.VPT_BENCH_JSON) fs.writeFileSync(process.env.VPT_BENCH_JSON, JSON.stringify(results));
await browser.close();
server.close();
