#!/usr/bin/env node
/**
 * Frame-time cost and GPU memory of a label volume (scene `labels`, docs/benchmarks.md "Label
 * volumes"): per renderer (EAM, MIP, ISO, MCRT, slice) ms per iteration of a uint8 blob with
 * and without a uint8 label volume of the same grid (a ball and a box, two visible labels),
 * interleaved (A B, then B A) in one page, as the median ratio to the label-free batch of the
 * same round; and the label textures' bytes (stats.gpuBytes.auxiliary difference is not used:
 * the grid differs; the label volume is N³ bytes and the table 4 KiB), with the load average.
 *
 *   pnpm run build && node benchmarks/label-cost.mjs [--size N] [--volume N] [--rounds N] [--batch N] [--backend webgl2|webgpu]
 */
import os from 'node:os';
import { parseCliOrExit } from '@vpt/cli-options';

const { size, volume, rounds, batch, backend } = parseCliOrExit({
  name: 'node benchmarks/label-cost.mjs',
  synopsis: '[--size N] [--volume N] [--rounds N] [--batch N] [--backend webgl2|webgpu]',
  summary: 'ms per iteration with a label volume against none, per renderer, interleaved (needs pnpm run build).',
  options: {
    size: { type: 'integer', min: 1, default: 96, description: 'image side in pixels' },
    volume: { type: 'integer', min: 4, default: 64, description: 'volume side in voxels' },
    rounds: { type: 'integer', min: 1, default: 4, description: 'interleaved rounds (one batch of each per round)' },
    batch: { type: 'integer', min: 1, default: 6, description: 'iterations per timed batch' },
    backend: { type: 'string', choices: ['webgl2', 'webgpu'], default: 'webgl2', description: 'the GPU backend' },
  },
});
// After the arguments, so that --help works before a build.
const { openVptPage } = await import('../packages/headless/dist/index.js');

const RENDERERS = {
  eam: {},
  mip: {},
  iso: { surfaces: [{ value: 0.4, color: [0.9, 0.8, 0.7] }] },
  mcrt: {},
  slice: {},
};
const load = () =>
  os
    .loadavg()
    .map((x) => x.toFixed(2))
    .join(' / ');

const session = await openVptPage();
try {
  console.log(
    `label-cost: ${backend}, ${size}² px, ${volume}³ uint8 + uint8 labels, ${rounds} rounds of ${batch} iterations; load ${load()}`,
  );
  for (const [renderer, params] of Object.entries(RENDERERS)) {
    const r = await session.page.evaluate(
      async (o) => {
        const { core } = window.vpt;
        const n = o.volume;
        const blob = core.createProceduralVolume('blob', n);
        const image = core.createVolume(
          [n, n, n],
          'uint8',
          Uint8Array.from(blob.data, (x) => Math.round(255 * Math.min(1, Math.max(0, x)))),
        );
        const ids = new Uint8Array(n * n * n);
        for (let z = 0; z < n; z++)
          for (let y = 0; y < n; y++)
            for (let x = 0; x < n; x++) {
              const q = ((x + 0.5) / n - 0.6) ** 2 + ((y + 0.5) / n - 0.45) ** 2 + ((z + 0.5) / n - 0.5) ** 2;
              ids[x + n * (y + n * z)] = q < 0.04 ? 1 : x < n / 3 && y > n / 2 ? 2 : 0;
            }
        const base = {
          volume: image,
          transferFunction: {
            dimensions: '1d',
            points: [
              { value: 0.2, color: [0.9, 0.85, 0.8], opacity: 0 },
              { value: 1, color: [0.9, 0.85, 0.8], opacity: 1 },
            ],
          },
          camera: { position: [0.9, 0.6, 1.3], target: [0, 0, 0], up: [0, 1, 0], fovy: 0.7 },
          lights: [{ type: 'directional', direction: [-0.5, 1, 0.4], irradiance: [2, 2, 2] }],
          environment: { type: 'constant', radiance: [0.4, 0.5, 0.7] },
          densityScale: 30,
          seed: 1,
        };
        const labelled = {
          ...base,
          labels: {
            volume: core.createVolume([n, n, n], 'uint8', ids),
            table: [
              { id: 1, color: [0.8, 0.2, 0.1], opacity: 1 },
              { id: 2, color: [0.2, 0.3, 0.9], opacity: 1 },
            ],
          },
        };
        const ctxs = [];
        for (const scene of [base, labelled]) {
          const ctx = await core.RenderContext.create({
            backend: o.backend,
            width: o.size,
            height: o.size,
            renderer: window.vpt.createRenderer(o.renderer, o.params),
          });
          ctx.setScene(scene);
          await ctx.renderIterations(2); // compile and warm up, untimed
          ctxs.push(ctx);
        }
        const ms = [[], []];
        for (let r = 0; r < o.rounds; r++)
          for (const k of r % 2 ? [1, 0] : [0, 1]) {
            const t0 = performance.now();
            await ctxs[k].renderIterations(o.batch); // ends with backend.finish()
            ms[k].push((performance.now() - t0) / o.batch);
          }
        ctxs.forEach((c) => c.dispose());
        return { ms };
      },
      { backend, size, volume, rounds, batch, renderer, params },
    );
    const median = (xs) => [...xs].sort((a, b) => a - b)[xs.length >> 1];
    const ratio = r.ms[1].map((m, i) => m / r.ms[0][i]);
    console.log(
      `${renderer.padEnd(5)} none ${median(r.ms[0]).toFixed(2)} ms/it; labels ${median(r.ms[1]).toFixed(2)} ms/it ×${median(ratio).toFixed(3)}; load ${load()}`,
    );
  }
} finally {
  await session.close();
}
