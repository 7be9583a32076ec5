#!/usr/bin/env node
/**
 * Temporal reuse's error apart from adaptive resolution and timing (docs/benchmarks.md, "Orbit: a
 * sharper and decorrelated history"): on the bundled head at a fixed size, per renderer and
 * history filter, (1) the history alone after one orbit step: a context whose history neither
 * fades nor decays (so it weighs its 64 samples against the one new one, taken back out exactly
 * from the blend) against the new view's converged image, next to the image of the old view
 * taken as it is; (2) the first frame after that step (the default options); (3) the orbit
 * benchmark's pace: --steps steps of --degrees each from a converged view, 2 samples per step,
 * against the last view's converged image, next to 2 samples from a reset. RMSE in linear RGB.
 *
 *   pnpm run build && node benchmarks/temporal-reprojection.mjs [--size 64] [--backend webgl2] [--renderers eam,mcrt] [--degrees 0.5] [--steps 12]
 */
import fs from 'node:fs';
import os from 'node:os';
import { fileURLToPath } from 'node:url';
import { parseCliOrExit } from '@vpt/cli-options';

const opts = parseCliOrExit({
  name: 'node benchmarks/temporal-reprojection.mjs',
  synopsis: '[--size N] [--backend B] [--renderers LIST] [--degrees X] [--steps N]',
  summary:
    "Temporal reuse's reprojection error (history alone), first frame and a paced orbit against converged views, per history filter (needs pnpm run build).",
  options: {
    size: { type: 'integer', min: 8, max: 512, default: 64, description: 'image side in pixels' },
    backend: { type: 'string', choices: ['webgl2', 'webgpu'], default: 'webgl2', description: 'the GPU backend' },
    renderers: { type: 'list', choices: ['eam', 'mcrt'], default: ['eam', 'mcrt'], description: 'renderers' },
    degrees: {
      type: 'number',
      min: 0,
      max: 90,
      default: 0.5,
      description: 'one orbit step (the orbit benchmark: 30° / 60)',
    },
    steps: { type: 'integer', min: 1, max: 1000, default: 12, description: 'steps of the paced orbit' },
  },
});
// After the arguments, so that --help works before a build.
const { openVptPage } = await import('../packages/headless/dist/index.js');
const ROOT = fileURLToPath(new URL('..', import.meta.url));
const headDesc = (renderer) => {
  const d = JSON.parse(
    fs.readFileSync(new URL(`../apps/gallery/scenes/head-${renderer}.json`, import.meta.url), 'utf8'),
  );
  d.volume = { sidecar: '/data/mri_head_volpack_brainsmall_128x128x84_uint8.json' };
  return d;
};
// The RGB RMSE of two RGBA images (metrics.ts).
const { rgbRmse: rmse } = await import('./dist/metrics.js');
const load = () =>
  os
    .loadavg()
    .map((x) => x.toFixed(2))
    .join(' ');
const FILTERS = ['bilinear', 'catmull-rom'];
const session = await openVptPage({ root: ROOT });
try {
  console.log(
    `temporal-reprojection: head ${opts.size}², ${opts.backend}, one step ${opts.degrees}°, paced orbit ${opts.steps} steps × 2 samples; load average ${load()}`,
  );
  console.log(
    '| renderer | filter | old view as is | history alone | reset, 1 sample | first frame | reset, 2 samples | paced orbit |',
  );
  console.log('|---|---|---|---|---|---|---|---|');
  for (const renderer of opts.renderers) {
    const r = await session.page.evaluate(
      async (d, S, backend, refIt, step, steps, filters) => {
        const { core } = window.vpt;
        const make = (temporal) =>
          core.RenderContext.create({
            backend,
            width: S,
            height: S,
            renderer: window.vpt.createRenderer(d.renderer, d.rendererParams),
            temporal,
          });
        const sceneA = await window.vpt.buildScene({ ...d, seed: 3 }, location.origin + '/');
        const c = sceneA.camera;
        const orbit = (a) => {
          const [x, z] = [c.position[0] - c.target[0], c.position[2] - c.target[2]];
          const p = [
            c.target[0] + x * Math.cos(a) + z * Math.sin(a),
            c.position[1],
            c.target[2] - x * Math.sin(a) + z * Math.cos(a),
          ];
          return { ...sceneA, camera: { ...c, position: p } };
        };
        const plain = await make(false);
        const render = async (scene, n, start = 0) => {
          plain.setSampleStart(start);
          plain.setScene(scene);
          await plain.renderIterations(n);
          return Array.from(await plain.readHDR());
        };
        const sceneB = orbit(step);
        const last = orbit(step * steps);
        const out = {
          refB: await render({ ...sceneB, seed: 11 }, refIt),
          // The moved context's new sample: sample 64 on, after the first view's 64 (TemporalReuse.sampleBase).
          curB: await render(sceneB, 1, 64),
          plain1: await render(sceneB, 1),
          refLast: await render({ ...last, seed: 11 }, refIt),
          plain2: await render(last, 2),
          filters: {},
        };
        plain.dispose();
        for (const historyFilter of filters) {
          const f = {};
          const frozen = await make({ historyFilter, maxHistory: 1024, fadeSamples: 1e6, viewDecay: 1e6 });
          frozen.setScene(sceneA);
          await frozen.renderIterations(64);
          f.oldView = Array.from(await frozen.readHDR());
          frozen.setScene(sceneB);
          frozen.iterate(1);
          f.blend = Array.from(await frozen.readHDR());
          f.state = Array.from(await frozen.readTemporalState());
          frozen.dispose();
          const ctx = await make({ historyFilter });
          ctx.setScene(sceneA);
          await ctx.renderIterations(64);
          ctx.setScene(sceneB);
          ctx.iterate(1);
          f.first = Array.from(await ctx.readHDR());
          ctx.setScene(sceneA);
          await ctx.renderIterations(64);
          for (let k = 1; k <= steps; k++) {
            ctx.setScene(orbit(step * k));
            ctx.iterate(2);
          }
          f.paced = Array.from(await ctx.readHDR());
          ctx.dispose();
          out.filters[historyFilter] = f;
        }
        return out;
      },
      headDesc(renderer),
      opts.size,
      opts.backend,
      renderer === 'mcrt' ? 256 : 128,
      (opts.degrees * Math.PI) / 180,
      opts.steps,
      FILTERS,
    );
    for (const filter of FILTERS) {
      const f = r.filters[filter];
      // The history alone where a pixel took one: blend = (cur + w·h)/(1 + w), so h = (blend·(1 + w) − cur)/w
      // (cur is the same sample, so this is exact); a pixel that took none counts no error.
      const hist = f.blend.map((v, i) => {
        const w = f.state[4 * Math.floor(i / 4) + 1] - 1;
        return w > 0.05 ? (v * (1 + w) - r.curB[i]) / w : r.refB[i];
      });
      console.log(
        `| ${renderer} | ${filter} | ${rmse(f.oldView, r.refB).toFixed(4)} | ${rmse(hist, r.refB).toFixed(4)} | ${rmse(r.plain1, r.refB).toFixed(4)} | ${rmse(f.first, r.refB).toFixed(4)} | ${rmse(r.plain2, r.refLast).toFixed(4)} | ${rmse(f.paced, r.refLast).toFixed(4)} (×${(rmse(f.paced, r.refLast) / rmse(r.plain2, r.refLast)).toFixed(2)}) |`,
      );
    }
  }
  console.log(`load average at the end ${load()}`);
} finally {
  await session.close();
}
