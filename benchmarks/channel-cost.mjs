#!/usr/bin/env node
/**
 * Memory per channel and frame-time cost per added channel (scene `channels`, docs/benchmarks.md
 * "Multichannel volumes"): per renderer (EAM, MIP, ISO, MCRT) ms per iteration of a uint8 volume
 * with 1, 2, 3 and 4 drawn channels (the same blob shifted per channel) against the scalar scene
 * of channel 0, interleaved (S 1 2 3 4, then reversed) in one page, as median ratios to the
 * scalar batch of the same round; and the volume texture's bytes (stats.gpuBytes.volume) per
 * channel count, with the load average.
 *
 *   pnpm run build && node benchmarks/channel-cost.mjs [--size N] [--volume N] [--rounds N] [--batch N] [--backend webgl2|webgpu]
 */
import os from 'node:os';
import { parseCliOrExit } from '@vpt/cli-options';

const { size, volume, rounds, batch, backend } = parseCliOrExit({
  name: 'node benchmarks/channel-cost.mjs',
  synopsis: '[--size N] [--volume N] [--rounds N] [--batch N] [--backend webgl2|webgpu]',
  summary:
    'ms per iteration and volume bytes with 1–4 channels against the scalar path, per renderer, interleaved (needs pnpm run build).',
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
};
const load = () =>
  os
    .loadavg()
    .map((x) => x.toFixed(2))
    .join(' / ');

const session = await openVptPage();
try {
  console.log(
    `channel-cost: ${backend}, ${size}² px, ${volume}³ uint8, ${rounds} rounds of ${batch} iterations; load ${load()}`,
  );
  for (const [renderer, params] of Object.entries(RENDERERS)) {
    const r = await session.page.evaluate(
      async (o) => {
        const { core } = window.vpt;
        const n = o.volume;
        const blob = core.createProceduralVolume('blob', n);
        const f = blob.data;
        // Channel k: the blob shifted by k voxels along x, as uint8.
        const field = (k) => {
          const d = new Uint8Array(n * n * n);
          for (let i = 0; i < d.length; i++) {
            const x = i % n;
            const j = i - x + ((x + k * 3) % n);
            d[i] = Math.round(255 * Math.min(1, Math.max(0, f[j])));
          }
          return d;
        };
        const parts = [0, 1, 2, 3].map((k) => core.createVolume([n, n, n], 'uint8', field(k)));
        const tf = (c) => ({
          dimensions: '1d',
          points: [
            { value: 0, color: c, opacity: 0 },
            { value: 0.2, color: c, opacity: 0 },
            { value: 1, color: c, opacity: 1 },
          ],
        });
        const colours = [
          [0.9, 0.3, 0.2],
          [0.2, 0.9, 0.3],
          [0.3, 0.4, 0.95],
          [0.9, 0.9, 0.2],
        ];
        const base = {
          transferFunction: tf(colours[0]),
          camera: { position: [0.9, 0.6, 1.3], target: [0, 0, 0], up: [0, 1, 0], fovy: 0.7 },
          lights: [{ type: 'directional', direction: [-0.5, 1, 0.4], irradiance: [2, 2, 2] }],
          environment: { type: 'constant', radiance: [0.4, 0.5, 0.7] },
          densityScale: 30,
          seed: 1,
        };
        const sceneOf = (count) =>
          count === 0
            ? { ...base, volume: parts[0] }
            : {
                ...base,
                volume: core.interleaveChannels(parts.slice(0, count)),
                channels: colours.slice(0, count).map((c) => ({ transferFunction: tf(c) })),
              };
        const keys = [0, 1, 2, 3, 4];
        const ctxs = {};
        const bytes = {};
        for (const k of keys) {
          const ctx = await core.RenderContext.create({
            backend: o.backend,
            width: o.size,
            height: o.size,
            renderer: window.vpt.createRenderer(o.renderer, o.params),
          });
          ctx.setScene(sceneOf(k));
          await ctx.renderIterations(2); // compile and warm up, untimed
          ctxs[k] = ctx;
          bytes[k] = ctx.stats.gpuBytes.volume;
        }
        const ms = Object.fromEntries(keys.map((k) => [k, []]));
        for (let r = 0; r < o.rounds; r++) {
          for (const k of r % 2 ? [...keys].reverse() : keys) {
            const t0 = performance.now();
            await ctxs[k].renderIterations(o.batch); // ends with backend.finish()
            ms[k].push((performance.now() - t0) / o.batch);
          }
        }
        Object.values(ctxs).forEach((c) => c.dispose());
        return { ms, bytes };
      },
      { backend, size, volume, rounds, batch, renderer, params },
    );
    const median = (xs) => [...xs].sort((a, b) => a - b)[xs.length >> 1];
    const parts = [1, 2, 3, 4].map((k) => {
      const ratio = r.ms[k].map((m, i) => m / r.ms[0][i]);
      return `${k} ch ${median(r.ms[k]).toFixed(2)} ms/it ×${median(ratio).toFixed(3)} (${(r.bytes[k] / 2 ** 20).toFixed(2)} MiB)`;
    });
    console.log(
      `${renderer.padEnd(5)} scalar ${median(r.ms[0]).toFixed(2)} ms/it (${(r.bytes[0] / 2 ** 20).toFixed(2)} MiB); ${parts.join('; ')}; load ${load()}`,
    );
  }
} finally {
  await session.close();
}
