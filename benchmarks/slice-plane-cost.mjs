#!/usr/bin/env node
/**
 * The frame-time cost of "slice in 3D" (a scene's `slicePlane`, docs/benchmarks.md "Slice in 3D"):
 * per renderer (EAM, MIP, ISO, MCRT) ms per iteration of the procedural blob with an axial slice
 * plane through its centre (grey), and with one through the box's last layer, behind the blob
 * (the plane code's own cost where the rays run their full length), against the same scene
 * without it, interleaved (U P U B, then B U P U) in one page, as median ratios to the
 * neighbouring batch without it, with the load average.
 *
 *   pnpm run build && node benchmarks/slice-plane-cost.mjs [--size N] [--rounds N] [--batch N] [--backend webgl2|webgpu]
 */
import os from 'node:os';
import { parseCliOrExit } from '@vpt/cli-options';

const { size, rounds, batch, backend } = parseCliOrExit({
  name: 'node benchmarks/slice-plane-cost.mjs',
  synopsis: '[--size N] [--rounds N] [--batch N] [--backend webgl2|webgpu]',
  summary: 'ms per iteration with and without a slice plane, per renderer, interleaved (needs pnpm run build).',
  options: {
    size: { type: 'integer', min: 1, default: 128, description: 'image side in pixels' },
    rounds: { type: 'integer', min: 1, default: 6, description: 'interleaved rounds (one batch of each per round)' },
    batch: { type: 'integer', min: 1, default: 8, description: 'iterations per timed batch' },
    backend: { type: 'string', choices: ['webgl2', 'webgpu'], default: 'webgl2', description: 'the GPU backend' },
  },
});
// After the arguments, so that --help works before a build.
const { openVptPage } = await import('../packages/headless/dist/index.js');

// Through the centre: the rays that meet it stop halfway. Through the last layer (behind the blob
// as seen from the camera): the rays run as far as without it, so this is the plane code's own cost.
const PLANE = { axis: 'z', index: 32 };
const BACK_PLANE = { axis: 'z', index: 0 };
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
  console.log(`slice-plane-cost: ${backend}, ${size}² px, ${rounds} rounds of ${batch} iterations; load ${load()}`);
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
        const make = async (slicePlane) => {
          const ctx = await core.RenderContext.create({
            backend: o.backend,
            width: o.size,
            height: o.size,
            renderer: window.vpt.createRenderer(o.renderer, o.params),
          });
          ctx.setScene(slicePlane ? { ...base, slicePlane } : base);
          await ctx.renderIterations(2); // compile and warm up, untimed
          return ctx;
        };
        const ctxs = { none: await make(null), plane: await make(o.plane), back: await make(o.back) };
        const out = { none: [], plane: [], back: [] };
        const order = ['none', 'plane', 'none', 'back'];
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
      { backend, size, rounds, batch, renderer, params, plane: PLANE, back: BACK_PLANE },
    );
    const median = (xs) => [...xs].sort((a, b) => a - b)[xs.length >> 1];
    // Each batch with a plane against the batch without one next to it (two per round).
    const ratio = (k) => ms[k].map((c, i) => c / ms.none[2 * i + (k === 'plane' ? 0 : 1)]);
    const text = (k) => {
      const r = ratio(k);
      return `${k} ${median(ms[k]).toFixed(2)} ms/it, ratio ${median(r).toFixed(3)} (${Math.min(...r).toFixed(3)}–${Math.max(...r).toFixed(3)})`;
    };
    console.log(
      `${renderer.padEnd(5)} none ${median(ms.none).toFixed(2)} ms/it; ${text('plane')}; ${text('back')}; load ${load()}`,
    );
  }
} finally {
  await session.close();
}
