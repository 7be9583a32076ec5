#!/usr/bin/env node
/**
 * OME-Zarr streaming against one raw file, over a throttled connection (issue 13 item 5):
 * time from setting `<vpt-viewer src>` to the first image and to the full-resolution
 * image, and the bytes fetched. Chromium's own network emulation (CDP
 * Network.emulateNetworkConditions, default 20 Mbit/s down and up, 20 ms latency) throttles
 * the page; runs alternate raw / zarr (interleaved A/B), each in a fresh page; medians with
 * min–max are printed with the machine's load average.
 *
 *   pnpm run build && node benchmarks/zarr-streaming.mjs [--sidecar data/…json] [--runs 5] [--mbit 20] [--latency 20]
 *
 * Default volume: the fetched cells3d nuclei (pnpm data:fetch) when present, else the
 * bundled head. The OME-Zarr copy: NGFF v0.4, zstd, 64³ chunks, 2× levels down to a side
 * ≤ 32 (scripts/raw-to-ome-zarr.mjs). "First image" is the first refining frame after the
 * first `vpt-load`; "full resolution" the first refining frame after the last level's.
 */
import fs from 'node:fs';
import http from 'node:http';
import os from 'node:os';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import { parseCliOrExit } from '@vpt/cli-options';
import { convertRawToOmeZarr } from '../scripts/raw-to-ome-zarr.mjs';

const root = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '..');
const args = parseCliOrExit({
  name: 'node benchmarks/zarr-streaming.mjs',
  synopsis: '[--sidecar data/….json] [--runs N] [--mbit X] [--latency MS]',
  summary: 'OME-Zarr streaming against one raw file over a throttled connection (needs pnpm run build).',
  options: {
    sidecar: {
      type: 'string',
      valueName: 'FILE',
      description: "the raw volume's JSON sidecar (default: the fetched cells3d nuclei, else the bundled head)",
    },
    runs: { type: 'integer', min: 1, default: 5, description: 'runs of each (raw / zarr alternate)' },
    mbit: { type: 'number', min: 0.01, default: 20, description: 'throttled bandwidth, Mbit/s down and up' },
    latency: { type: 'number', min: 0, default: 20, description: 'added latency in ms' },
  },
});
const { launchChromium } = await import(path.join(root, 'packages/headless/dist/index.js'));

const cells = path.join(root, 'data/fetched/micro_cells3d_nuclei_256x256x60_uint16.json');
const sidecarPath = path.resolve(
  args.sidecar ??
    (fs.existsSync(cells) ? cells : path.join(root, 'data/mri_head_volpack_brainsmall_128x128x84_uint8.json')),
);
const { runs, mbit, latency } = args;

// ——— the data: the raw file with its sidecar, and a multiscale OME-Zarr copy ———
const work = fs.mkdtempSync(path.join(os.tmpdir(), 'vpt-zarr-bench-'));
const sidecar = JSON.parse(fs.readFileSync(sidecarPath, 'utf8'));
const rawName = sidecar.file ?? path.basename(sidecarPath).replace(/\.json$/, '.raw');
fs.copyFileSync(sidecarPath, path.join(work, 'volume.json'));
fs.copyFileSync(path.join(path.dirname(sidecarPath), rawName), path.join(work, rawName));
fs.writeFileSync(path.join(work, 'volume.json'), JSON.stringify({ ...sidecar, file: rawName }));
let levels = 1;
for (let side = Math.max(...sidecar.dims); side > 32; side = Math.ceil(side / 2)) levels++;
await convertRawToOmeZarr(path.join(work, 'volume.json'), path.join(work, 'volume.ome.zarr'), {
  version: '0.4',
  codec: 'zstd',
  levels,
  chunk: 64,
});

// ——— a data server on its own origin (CORS, Range), counting body bytes ———
let bytesSent = 0;
const dataServer = http.createServer((req, res) => {
  res.setHeader('access-control-allow-origin', '*');
  res.setHeader('access-control-allow-headers', 'range');
  res.setHeader('cache-control', 'no-store');
  if (req.method === 'OPTIONS') return void res.writeHead(204).end();
  const file = path.resolve(work, '.' + decodeURIComponent(new URL(req.url, 'http://x').pathname));
  if (!file.startsWith(work) || !fs.existsSync(file) || !fs.statSync(file).isFile())
    return void res.writeHead(404).end();
  const body = fs.readFileSync(file);
  res.writeHead(200, { 'content-length': body.length, 'content-type': 'application/octet-stream' });
  res.end(body);
  bytesSent += body.length;
});
await new Promise((r) => dataServer.listen(0, '127.0.0.1', r));
const dataUrl = `http://127.0.0.1:${dataServer.address().port}/`;

// The page and the packages from a server that lets the browser cache them (as a deployed
// site would): after the warm-up, code comes from the cache and only the data crosses the
// throttled link, for raw and zarr alike.
const pageServer = http.createServer((req, res) => {
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
await new Promise((r) => pageServer.listen(0, '127.0.0.1', r));
pageServer.url = `http://127.0.0.1:${pageServer.address().port}/`;
const browser = await launchChromium();

async function measure(src) {
  const page = await browser.newPage();
  await page.setViewport({ width: 200, height: 200, deviceScaleFactor: 1 });
  await page.goto(new URL('tests/pages/viewer.html', pageServer.url).href);
  await page.waitForFunction(() => window.__ready === true, { timeout: 60_000 });
  const cdp = await page.createCDPSession();
  await cdp.send('Network.enable');
  await cdp.send('Network.emulateNetworkConditions', {
    offline: false,
    latency,
    downloadThroughput: (mbit * 1e6) / 8,
    uploadThroughput: (mbit * 1e6) / 8,
  });
  const before = bytesSent;
  const result = await page.evaluate(async (s) => {
    const el = document.createElement('vpt-viewer');
    for (const [k, v] of Object.entries({ renderer: 'mip', backend: 'webgl2', panels: 'none', 'max-samples': '4' }))
      el.setAttribute(k, v);
    el.setAttribute('style', 'width:64px;height:64px');
    document.body.append(el);
    await el.updateComplete;
    const t = { first: null, full: null, levels: [], loadedAt: [] };
    let loads = 0,
      finalLoaded = false,
      t0 = 0;
    const done = new Promise((resolve, reject) => {
      el.addEventListener('vpt-error', (e) => reject(new Error(e.detail.message)));
      el.addEventListener('vpt-load', (e) => {
        loads++;
        t.levels.push(e.detail.level?.index ?? 0);
        t.loadedAt.push(Math.round(performance.now() - t0));
        finalLoaded = !e.detail.level || e.detail.level.final;
      });
      el.addEventListener('vpt-progress', (e) => {
        if (e.detail.phase !== 'refining' || loads === 0) return;
        const now = performance.now() - t0;
        if (t.first === null) t.first = now;
        if (finalLoaded && t.full === null) {
          t.full = now;
          resolve();
        }
      });
    });
    t0 = performance.now();
    el.src = s;
    await done;
    el.remove();
    return t;
  }, src);
  await page.close();
  return { ...result, bytes: bytesSent - before };
}

const cases = { raw: `${dataUrl}volume.json`, zarr: `${dataUrl}volume.ome.zarr` };
const samples = { raw: [], zarr: [] };
await measure(cases.raw); // warm-up: compile the kernels, fill the browser's code caches
await measure(cases.zarr);
const load0 = os.loadavg();
for (let i = 0; i < runs; i++)
  for (const name of i % 2 ? ['zarr', 'raw'] : ['raw', 'zarr']) samples[name].push(await measure(cases[name]));
const load1 = os.loadavg();

const median = (a) => [...a].sort((x, y) => x - y)[Math.floor(a.length / 2)];
const range = (a) => `${Math.round(Math.min(...a))}–${Math.round(Math.max(...a))}`;
console.log(
  `volume ${path.basename(sidecarPath)} [${sidecar.dims.join('×')}] ${sidecar.voxel_type}; OME-Zarr v0.4 zstd, ${levels} levels; ` +
    `${mbit} Mbit/s, ${latency} ms latency (CDP); ${runs} interleaved runs each; load average ${load0.map((x) => x.toFixed(2)).join(' ')} → ${load1.map((x) => x.toFixed(2)).join(' ')}`,
);
console.log('| source | first image (ms) | full resolution (ms) | bytes fetched | levels shown |');
console.log('|---|---|---|---|---|');
for (const name of ['raw', 'zarr']) {
  const s = samples[name];
  console.log(
    `| ${name} | ${Math.round(median(s.map((r) => r.first)))} (${range(s.map((r) => r.first))}) | ${Math.round(median(s.map((r) => r.full)))} (${range(s.map((r) => r.full))}) | ${median(s.map((r) => r.bytes))} | ${s[0].levels.join(' → ')} |`,
  );
}
const ratio = (k) => median(samples.zarr.map((r) => r[k])) / median(samples.raw.map((r) => r[k]));
console.log(
  `zarr / raw: first image ${ratio('first').toFixed(2)}, full resolution ${ratio('full').toFixed(2)}, bytes ${ratio('bytes').toFixed(2)}`,
);

await browser.close();
pageServer.close();
dataServer.close();
fs.rmSync(work, { recursive: true, force: true });
if (process.env.VPT_BENCH_DEBUG) for (const name of ['raw', 'zarr']) console.log(name, JSON.stringify(samples[name]));
