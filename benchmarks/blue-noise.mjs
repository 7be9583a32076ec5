#!/usr/bin/env node
/**
 * Blue-noise sampling against the PCG stream (docs/benchmarks.md, "Blue-noise sampling"): per
 * renderer (EAM, MIP, ISO, MCRT single and multiple) on the VPT side-by-side anchor scene and
 * the bundled head, iterations and wall time to HDR 30 / 35 dB PSNR (and iterations to 40 dB) against one converged PCG
 * reference (independent seed), for `sampler: 'pcg'` and `'blue-noise'`, interleaved over
 * rounds (A B, B A, …; each round its own seed), on the benchmark page's own errorCurve (the
 * same clock and error as `pnpm bench`'s error suite, where MCRT's reference noise is
 * subtracted through its half accumulations). Load average printed per row.
 *
 *   pnpm run build && node benchmarks/blue-noise.mjs [--size N] [--rounds R] [--max N] [--reference N] [--renderers a,b] [--scenes a,b]
 */
import os from 'node:os';
import { fileURLToPath } from 'node:url';
import { parseCliOrExit } from '@vpt/cli-options';

const RENDERERS = ['eam', 'mip', 'iso', 'mcrt single', 'mcrt multiple'];
const SCENES = ['anchor', 'head'];
const opts = parseCliOrExit({
  name: 'node benchmarks/blue-noise.mjs',
  synopsis: '[--size N] [--rounds R] [--max N] [--reference N] [--renderers LIST] [--scenes LIST] [--backend B]',
  summary: "Iterations and time to 30/35 dB, sampler 'blue-noise' against 'pcg', per renderer (needs pnpm run build).",
  options: {
    size: { type: 'integer', min: 8, default: 64, description: 'image side in pixels' },
    rounds: { type: 'integer', min: 1, default: 2, description: 'interleaved rounds (A B, then B A, …)' },
    max: { type: 'integer', min: 2, default: 512, description: "a curve's last iteration" },
    reference: { type: 'integer', min: 2, default: 2048, description: "the PCG reference's iterations" },
    renderers: { type: 'list', choices: RENDERERS, default: RENDERERS, description: 'renderer configurations' },
    scenes: { type: 'list', choices: SCENES, default: SCENES, description: 'scenes' },
    backend: { type: 'string', choices: ['webgl2', 'webgpu'], default: 'webgl2', description: 'the GPU backend' },
  },
});
// After the arguments, so that --help works before a build.
const { openVptPage } = await import('../packages/headless/dist/index.js');
const { scenes } = await import('./dist/configs.js');
const { ANCHOR_SCENE } = await import('./dist/suites/skipping.js');
const { skyRadiance } = await import('./dist/vpt-side/anchor-scene.js');
const { timeToPsnr, median } = await import('./dist/metrics.js');

const CONFIGS = {
  eam: { renderer: 'eam' },
  mip: { renderer: 'mip' },
  iso: { renderer: 'iso' },
  'mcrt single': { renderer: 'mcrt', params: { scattering: 'single' }, halves: true },
  'mcrt multiple': { renderer: 'mcrt', params: { scattering: 'multiple' }, halves: true },
};
// The anchor scene of the skipping suite (VPT's volume and ramp TF); MCRT and ISO (which reflect
// light, so would be black under its black sky) get VPT's sky (radiance by height,
// vpt-side/anchor-scene.ts) as a lat-long map, as in the side-by-side suite.
const SKY_W = 16,
  SKY_H = 64;
const sky = [];
for (let j = 0; j < SKY_H; j++)
  for (let i = 0; i < SKY_W; i++) {
    const r = skyRadiance(Math.cos((Math.PI * (j + 0.5)) / SKY_H));
    sky.push(r, r, r);
  }
const SCENE_SPECS = {
  anchor: (label) =>
    label.startsWith('mcrt') || label === 'iso'
      ? { ...ANCHOR_SCENE, environment: { type: 'latlong', width: SKY_W, height: SKY_H, data: sky } }
      : ANCHOR_SCENE,
  head: () => scenes(128).head,
};

const load = () =>
  os
    .loadavg()
    .map((x) => x.toFixed(2))
    .join(' / ');
const ROOT = fileURLToPath(new URL('..', import.meta.url));
const session = await openVptPage({ root: ROOT });
const fmt = (x) => (x === null ? '—' : x.toFixed(x < 10 ? 1 : 0));
const fix = (x) => (x === null ? '—' : x.toFixed(1));
try {
  const dist = session.mount(fileURLToPath(new URL('./dist/', import.meta.url)));
  await session.page.evaluate(async (url) => (await import(url)).installBenchPage(), `${dist}page-code.js`);
  console.log(
    `blue-noise: ${opts.size}², ${opts.backend}, curves to ${opts.max} it, PCG reference ${opts.reference} it, ${opts.rounds} rounds; load ${load()}`,
  );
  const rows = [];
  for (const sceneName of opts.scenes)
    for (const label of opts.renderers) {
      const spec = SCENE_SPECS[sceneName](label);
      const base = { label, ...CONFIGS[label], backend: opts.backend };
      const cfg = (sampler) => ({ ...base, params: { ...(base.params ?? {}), sampler } });
      const refKey = `${sceneName}|${label}`;
      await session.page.evaluate(
        (k, c, s, w, n) => window.bench.reference(k, c, s, w, w, n),
        refKey,
        cfg('pcg'),
        spec,
        opts.size,
        opts.reference,
      );
      const res = { pcg: [], 'blue-noise': [] };
      for (let r = 0; r < opts.rounds; r++) {
        const order = r % 2 === 0 ? ['pcg', 'blue-noise'] : ['blue-noise', 'pcg'];
        for (const sampler of order) {
          const points = await session.page.evaluate(
            (c, s, w, k, n, est) => window.bench.errorCurve(c, s, w, w, k, n, 1e12, est),
            cfg(sampler),
            { ...spec, seed: 17 + 31 * r },
            opts.size,
            refKey,
            opts.max,
            false,
          );
          const its = points.map((p) => ({ ...p, ms: p.iterations }));
          res[sampler].push({
            it30: timeToPsnr(its, 30),
            it35: timeToPsnr(its, 35),
            it40: timeToPsnr(its, 40),
            ms30: timeToPsnr(points, 30),
            ms35: timeToPsnr(points, 35),
            finalDb: points[points.length - 1].psnr,
            msPerIt: points[points.length - 1].ms / points[points.length - 1].iterations,
          });
        }
      }
      const med = (s, k) => {
        const xs = res[s].map((x) => x[k]).filter((x) => x !== null);
        return xs.length === res[s].length ? median(xs) : null;
      };
      const row = { scene: sceneName, renderer: label, load: load() };
      for (const s of ['pcg', 'blue-noise'])
        for (const k of ['it30', 'it35', 'it40', 'ms30', 'ms35', 'finalDb', 'msPerIt']) row[`${s} ${k}`] = med(s, k);
      const ratio = (k) =>
        row[`pcg ${k}`] !== null && row[`blue-noise ${k}`] !== null ? row[`pcg ${k}`] / row[`blue-noise ${k}`] : null;
      console.log(
        `${sceneName.padEnd(6)} ${label.padEnd(13)} it→30 dB pcg ${fmt(row['pcg it30'])} bn ${fmt(row['blue-noise it30'])} (×${fmt(ratio('it30'))})` +
          `  it→35 dB pcg ${fmt(row['pcg it35'])} bn ${fmt(row['blue-noise it35'])} (×${fmt(ratio('it35'))})` +
          `  it→40 dB pcg ${fmt(row['pcg it40'])} bn ${fmt(row['blue-noise it40'])} (×${fmt(ratio('it40'))})` +
          `  ms→35 dB pcg ${fmt(row['pcg ms35'])} bn ${fmt(row['blue-noise ms35'])}` +
          `  ms/it pcg ${fix(row['pcg msPerIt'])} bn ${fix(row['blue-noise msPerIt'])}` +
          `  dB@${opts.max} pcg ${fix(row['pcg finalDb'])} bn ${fix(row['blue-noise finalDb'])}; load ${row.load}`,
      );
      rows.push({ ...row, rounds: res });
    }
  console.log(JSON.stringify(rows));
} finally {
  await session.close();
}
