#!/usr/bin/env node
/**
 * MCRT single-scattering variants against VPT's MCS on the side-by-side suite's anchor scene
 * (docs/benchmarks.md, "Side by side with VPT"), in one page: per variant the cost of an
 * iteration, interleaved over rounds, as wall ms AND as CPU ms (user + system time of all of
 * Chromium's processes over the batch, from /proc: the work done, which a shared machine's
 * load barely changes), then iterations to HDR 30 / 35 dB against the variant's own
 * 512-iteration reference, one curve per seed. Linux only (reads /proc).
 *
 *   pnpm run build && node benchmarks/single-variants.mjs VARIANTS [ROUNDS=5] [CURVES=0] [BATCH=8] [VPT_DIR]
 *
 * VARIANTS: JSON object name → MCRT params merged over { scattering: 'single' }, or "VPT" for
 * VPT's MCS (extinction 100), e.g. '{"VPT":"VPT","auto":{},"old":{"lightSamples":1,"environmentSampling":"mis"}}'.
 * VPT_DIR is a clone of terier/vpt with its build/ (never stored in this repository).
 */
import os from 'node:os';
import fs from 'node:fs';
import path from 'node:path';
import { parseCliOrExit } from '@vpt/cli-options';

const args = parseCliOrExit({
  name: 'node benchmarks/single-variants.mjs',
  synopsis: 'VARIANTS [ROUNDS] [CURVES] [BATCH] [VPT_DIR]',
  summary: "MCRT single-scattering variants against VPT's MCS on the side-by-side anchor scene (needs pnpm run build).",
  positionals: [
    {
      key: 'variants',
      name: 'VARIANTS',
      type: 'json',
      required: true,
      description: 'JSON: name → MCRT params over { scattering: "single" }, or "VPT" for VPT\'s MCS',
    },
    { key: 'rounds', name: 'ROUNDS', type: 'integer', min: 1, default: 5, description: 'interleaved cost rounds' },
    {
      key: 'curves',
      name: 'CURVES',
      type: 'integer',
      min: 0,
      default: 0,
      description: 'error curves (seeds) per variant',
    },
    { key: 'batch', name: 'BATCH', type: 'integer', min: 1, default: 8, description: 'iterations per timed batch' },
    { key: 'vptDir', name: 'VPT_DIR', type: 'string', description: 'a clone of terier/vpt with its build/' },
  ],
});
const { variants, rounds, curves: curveIts, batch } = args;
const vptBuild = args.vptDir ? path.join(args.vptDir, 'build') : null;
if (!vptBuild) {
  // The side page loads VPT's modules even when no "VPT" variant runs.
  console.log('single-variants: skipped: no VPT_DIR (a clone of terier/vpt with its build/)');
  process.exit(0);
}
// After the arguments, so that --help works before a build.
const { openVptPage } = await import('../packages/headless/dist/index.js');
const { installSidePage } = await import('./dist/vpt-side/side-page.js');
const { anchorVolume, ANCHOR_ALBEDO, ANCHOR_CAMERA_Z, ANCHOR_EXTINCTION, ANCHOR_FOVY, VPT_SKY_ROWS } =
  await import('./dist/vpt-side/anchor-scene.js');
const { sideIterationsTo } = await import('./dist/vpt-side/side-metrics.js');
const { processTreeCpuMs } = await import('./dist/process-cpu-time.js');
const n = 128;
const dir = fs.mkdtempSync(path.join(os.tmpdir(), 'sv-'));
fs.writeFileSync(path.join(dir, 'a.raw'), anchorVolume(n));
const session = await openVptPage();
const root = session.browser.process()?.pid;
// CPU time (user + system) of the browser and all its descendants: the work, whatever the load.
const cpuMs = () => processTreeCpuMs(root);
const side = (fn, ...args) => session.page.evaluate((fn, args) => window.side[fn](...args), fn, args);
try {
  const vptBase = session.mount(vptBuild, '/vpt/');
  const vb = session.mount(dir);
  await session.page.evaluate(installSidePage);
  await side('init', vptBase, {
    volumeUrl: vb + 'a.raw',
    n,
    extinction: ANCHOR_EXTINCTION,
    albedo: [...ANCHOR_ALBEDO],
    cameraZ: ANCHOR_CAMERA_Z,
    fovy: ANCHOR_FOVY,
    skyRows: VPT_SKY_ROWS,
  });
  const keys = Object.keys(variants);
  for (const k of keys) {
    const v = variants[k];
    const cfg =
      v === 'VPT'
        ? { engine: 'vpt-ref', renderer: 'mcs', props: { extinction: ANCHOR_EXTINCTION } }
        : { engine: 'vpt', renderer: 'mcrt', params: { scattering: 'single', ...v } };
    await side('open', k, cfg, 128);
  }
  console.log(
    'load',
    os
      .loadavg()
      .map((x) => x.toFixed(2))
      .join(' / '),
  );
  const ms = Object.fromEntries(keys.map((k) => [k, []]));
  const cpu = Object.fromEntries(keys.map((k) => [k, []]));
  for (let r = 0; r < rounds; r++)
    for (const k of r % 2 ? [...keys].reverse() : keys) {
      const c0 = cpuMs();
      ms[k].push(...(await side('msPerIteration', k, batch, 1)));
      cpu[k].push((cpuMs() - c0) / batch);
    }
  for (const k of keys) {
    const s = [...cpu[k]].sort((a, b) => a - b);
    console.log(
      k.padEnd(14),
      'median CPU ms/it',
      s[s.length >> 1].toFixed(2),
      'all',
      cpu[k].map((x) => x.toFixed(1)).join(' '),
    );
  }
  for (const k of keys) {
    const s = [...ms[k]].sort((a, b) => a - b);
    console.log(
      k.padEnd(14),
      'median ms/it',
      s[s.length >> 1].toFixed(2),
      'min',
      s[0].toFixed(2),
      'all',
      ms[k].map((x) => x.toFixed(1)).join(' '),
    );
  }
  if (curveIts) {
    for (const k of keys) {
      await side('reference', k, k, 512);
      const its30 = [],
        its35 = [];
      for (let seed = 1; seed <= curveIts; seed++) {
        const pts = await side('curve', k, k, seed, 64, 1e9);
        its30.push(sideIterationsTo(pts, 512, 30));
        its35.push(sideIterationsTo(pts, 512, 35));
      }
      console.log(
        k.padEnd(14),
        'its to 30',
        its30.map((x) => x?.toFixed(1)).join(' '),
        ' 35',
        its35.map((x) => x?.toFixed(1)).join(' '),
      );
    }
  }
  console.log(
    'load',
    os
      .loadavg()
      .map((x) => x.toFixed(2))
      .join(' / '),
  );
} finally {
  await session.close();
}
