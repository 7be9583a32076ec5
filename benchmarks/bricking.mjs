#!/usr/bin/env node
/**
 * Bricked volumes (issue 13 item 3, core/src/bricking): on the bundled MRI head (128 × 128 × 84
 * uint8) with the CLI's EAM and MCRT scene files,
 *  - ms per iteration bricked ('force', every brick resident) against unbricked, measured
 *    alternately (A B B A … per round) in one run, as a ratio of medians;
 *  - GPU bytes of the volume against the budget, unbricked, bricked with room for everything,
 *    and bricked under a budget of half the plain volume (how many level-0 bricks fit);
 *  - bricks uploaded and frames until the cache is complete at the default 16 uploads per frame.
 *
 *   pnpm run build && node benchmarks/bricking.mjs [--size 64] [--iterations 8] [--rounds 3] [--backend webgl2] [--brick 32]
 *
 * Prints one JSON line (with the load average). Timings on SwiftShader are CPU-bound and
 * noisy; compare the ratios of one run.
 */
import fs from 'node:fs';
import os from 'node:os';
import { parseCliOrExit } from '@vpt/cli-options';

const {
  size,
  iterations,
  rounds,
  backend,
  brick: brickSize,
} = parseCliOrExit({
  name: 'node benchmarks/bricking.mjs',
  synopsis: '[--size N] [--iterations N] [--rounds N] [--backend webgl2|webgpu] [--brick N]',
  summary:
    'Bricked against unbricked volumes on the bundled MRI head: ms per iteration, GPU bytes, cache fill (needs pnpm run build).',
  options: {
    size: { type: 'integer', min: 1, default: 64, description: 'image side in pixels' },
    iterations: { type: 'integer', min: 1, default: 8, description: 'iterations per timed batch' },
    rounds: { type: 'integer', min: 1, default: 3, description: 'A B B A rounds' },
    backend: { type: 'string', choices: ['webgl2', 'webgpu'], default: 'webgl2', description: 'the GPU backend' },
    brick: { type: 'integer', min: 2, default: 32, description: 'brick side in voxels' },
  },
});
// After the arguments, so that --help works before a build.
const { openVptPage } = await import('../packages/headless/dist/index.js');
const scenes = Object.fromEntries(
  ['eam', 'mcrt'].map((r) => [
    r,
    JSON.parse(fs.readFileSync(new URL(`../apps/gallery/scenes/head-${r}.json`, import.meta.url), 'utf8')),
  ]),
);

const loadBefore = os.loadavg();
const session = await openVptPage();
try {
  const result = await session.page.evaluate(
    async (scenes, size, iterations, rounds, backend, brickSize) => {
      const { core, buildScene } = window.vpt;
      const plainBytes = 128 * 128 * 84;
      const make = async (name, desc, bricking, maxGpuBytes) => {
        const scene = await buildScene({ ...desc, renderer: name }, location.origin + '/apps/gallery/scenes/');
        const renderer = window.vpt.createRenderer(name, desc.rendererParams ?? {});
        const ctx = await core.RenderContext.create({
          backend,
          width: size,
          height: size,
          renderer,
          bricking,
          brickSize,
          ...(maxGpuBytes ? { maxGpuBytes } : {}),
        });
        ctx.setScene(scene);
        const t0 = performance.now();
        let frames = 0;
        while (ctx.stats.bricking && !ctx.stats.bricking.complete && frames < 10000) {
          ctx.iterate(1);
          frames++;
          await new Promise((r) => setTimeout(r, 0));
        }
        const settleMs = performance.now() - t0;
        return { ctx, frames, settleMs };
      };
      const timing = {};
      for (const name of Object.keys(scenes)) {
        const ms = { plain: [], bricked: [] };
        const ctxs = { plain: await make(name, scenes[name], 'off'), bricked: await make(name, scenes[name], 'force') };
        await ctxs.plain.ctx.renderIterations(2); // compile
        await ctxs.bricked.ctx.renderIterations(2);
        for (let r = 0; r < rounds; r++) {
          for (const k of r % 2 ? ['bricked', 'plain', 'plain', 'bricked'] : ['plain', 'bricked', 'bricked', 'plain']) {
            await ctxs[k].ctx.renderIterations(iterations);
            ms[k].push(ctxs[k].ctx.stats.msPerIteration);
          }
        }
        const median = (a) => [...a].sort((x, y) => x - y)[Math.floor(a.length / 2)];
        timing[name] = {
          plainMs: median(ms.plain),
          brickedMs: median(ms.bricked),
          ratio: median(ms.bricked) / median(ms.plain),
          plainSamples: ms.plain,
          brickedSamples: ms.bricked,
          bricking: ctxs.bricked.ctx.stats.bricking,
          framesToComplete: ctxs.bricked.frames,
          msToComplete: ctxs.bricked.settleMs,
          volumeBytes: { plain: ctxs.plain.ctx.stats.gpuBytes.volume, bricked: ctxs.bricked.ctx.stats.gpuBytes.volume },
        };
        ctxs.plain.ctx.dispose();
        ctxs.bricked.ctx.dispose();
      }
      // Under a budget: half the plain volume's bytes for the bricks, beside what the context
      // counts for the render targets (frame, 2 × accumulation, HDR; no post chain here) and the TF.
      const eam = window.vpt.createRenderer('eam', {});
      const targets = size * size * 16 * (eam.frameFormats.length + 2 * eam.accumulationFormats.length + 1);
      const half = await make('eam', scenes.eam, 'auto', targets + 256 * 256 * 16 + plainBytes / 2);
      const underBudget = {
        budgetForVolume: plainBytes / 2,
        volumeBytes: half.ctx.stats.gpuBytes.volume,
        total: half.ctx.stats.gpuBytes.total,
        maxGpuBytes: half.ctx.maxGpuBytes,
        bricking: half.ctx.stats.bricking,
        framesToComplete: half.frames,
      };
      half.ctx.dispose();
      return { timing, underBudget, plainBytes };
    },
    scenes,
    size,
    iterations,
    rounds,
    backend,
    brickSize,
  );
  console.log(
    JSON.stringify({
      backend,
      size,
      iterations,
      rounds,
      brickSize,
      loadAverage: [loadBefore, os.loadavg()],
      ...result,
    }),
  );
} finally {
  await session.close();
}
