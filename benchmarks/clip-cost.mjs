#!/usr/bin/env node
/**
 * The frame-time cost of clipping (scene `clip`, docs/benchmarks.md "Clipping"): per renderer
 * (EAM, MIP, ISO, MCRT) ms per iteration of the procedural blob with two clip planes and a crop
 * box (about half the blob cut away), and with planes and a box that remove nothing (the clipping
 * code's own cost), against the same scene unclipped, interleaved (U C U N, then N U C U) in one
 * page, as median ratios to the neighbouring unclipped batch, with the load average.
 *
 *   pnpm run build && node benchmarks/clip-cost.mjs [--size N] [--rounds N] [--batch N] [--backend webgl2|webgpu]
 */
import os from 'node:os';
import { parseCliOrExit } from '@vpt/cli-options';

const { size, rounds, batch, backend } = parseCliOrExit({
  name: 'node benchmarks/clip-cost.mjs',
  synopsis: '[--size N] [--rounds N] [--batch N] [--backend webgl2|webgpu]',
  summary: 'ms per iteration with and without clipping, per renderer, interleaved (needs pnpm run build).',
  options: {
    size: { type: 'integer', min: 1, default: 128, description: 'image side in pixels' },
    rounds: { type: 'integer', min: 1, default: 6, description: 'interleaved rounds (one batch of each per round)' },
    batch: { type: 'integer', min: 1, default: 8, description: 'iterations per timed batch' },
    backend: { type: 'string', choices: ['webgl2', 'webgpu'], default: 'webgl2', description: 'the GPU backend' },
  },
});
// After the arguments, so that --help works before a build.
const { openVptPage } = await import('../packages/headless/dist/index.js');

// A cut that leaves about half of the blob: a plane through the centre, a tilted one and a crop box.
const CLIP = {
  planes: [
    { normal: [1, 0.3, 0.2], offset: 0 },
    { normal: [0, -1, 0.4], offset: 0.2 },
  ],
  box: { min: [-0.45, -0.4, -0.35], max: [0.4, 0.45, 0.4] },
};
// The same number of planes and a box that remove nothing: the clipping code's own cost.
const NOOP_CLIP = {
  planes: [
    { normal: [1, 0.3, 0.2], offset: 2 },
    { normal: [0, -1, 0.4], offset: 2 },
  ],
  box: { min: [-0.5, -0.5, -0.5], max: [0.5, 0.5, 0.5] },
};
const RENDERERS = {
  eam: {},
  mip: {},
  iso: { surfaces: [{ value: 0.4, color: [0.9, 0.8, 0.7] }] },
  mcrt: {},
};
const load = () =>
  os
    .loadavg()
    .map((x) => x.toFixed(2))
    .join(' / ');

const session = await openVptPage();
try {
  console.log(`clip-cost: ${backend}, ${size}² px, ${rounds} rounds of ${batch} iterations; load ${load()}`);
  for (const [renderer, params] of Object.entries(RENDERERS)) {
    const ms = await session.page.evaluate(
      async (o) => {
        const { core } = window.vpt;
        const base = {
          volume: core.createProceduralVolume('blob', 64),
          transferFunction: {
            dimensions: '1d',
            points: [
              { value: 0, color: [0.9, 0.8, 0.7], opacity: 0 },
              { value: 0.2, color: [0.9, 0.8, 0.7], opacity: 0 },
              { value: 1, color: [0.95, 0.95, 0.95], opacity: 1 },
            ],
          },
          camera: { position: [0.9, 0.6, 1.3], target: [0, 0, 0], up: [0, 1, 0], fovy: 0.7 },
          lights: [{ type: 'directional', direction: [-0.5, 1, 0.4], irradiance: [2, 2, 2] }],
          environment: { type: 'constant', radiance: [0.4, 0.5, 0.7] },
          densityScale: 30,
          seed: 1,
        };
        // One context per configuration, so each keeps its compiled variant and neither recompiles.
        const make = async (clip) => {
          const ctx = await core.RenderContext.create({
            backend: o.backend,
            width: o.size,
            height: o.size,
            renderer: window.vpt.createRenderer(o.renderer, o.params),
          });
          ctx.setScene(clip ? { ...base, clip } : base);
          await ctx.renderIterations(2); // compile and warm up, untimed
          return ctx;
        };
        const ctxs = { unclipped: await make(null), clipped: await make(o.clip), noop: await make(o.noop) };
        const out = { unclipped: [], clipped: [], noop: [] };
        const order = ['unclipped', 'clipped', 'unclipped', 'noop'];
        for (let r = 0; r < o.rounds; r++) {
          for (const k of r % 2 ? [...order].reverse() : order) {
            const t0 = performance.now();
            await ctxs[k].renderIterations(o.batch); // ends with backend.finish()
            out[k].push((performance.now() - t0) / o.batch);
          }
        }
        Object.values(ctxs).forEach((c) => c.dispose());
        return out;
      },
      { backend, size, rounds, batch, renderer, params, clip: CLIP, noop: NOOP_CLIP },
    );
    const median = (xs) => [...xs].sort((a, b) => a - b)[xs.length >> 1];
    // Each clipped batch against the unclipped batch next to it (two unclipped batches per round).
    const ratio = (k) => ms[k].map((c, i) => c / ms.unclipped[2 * i + (k === 'clipped' ? 0 : 1)]);
    const text = (k) => {
      const r = ratio(k);
      return `${k} ${median(ms[k]).toFixed(2)} ms/it, ratio ${median(r).toFixed(3)} (${Math.min(...r).toFixed(3)}–${Math.max(...r).toFixed(3)})`;
    };
    console.log(
      `${renderer.padEnd(5)} unclipped ${median(ms.unclipped).toFixed(2)} ms/it; ${text('clipped')}; ${text('noop')}; load ${load()}`,
    );
  }
} finally {
  await session.close();
}
