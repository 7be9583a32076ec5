#!/usr/bin/env node
/**
 * MCRT work per path with and without the majorant grid: medium lookups (each a trilinear
 * volume sample + TF lookup), majorant-grid cells visited, and ms per iteration, for each
 * shadow-ray estimator, on the bundled MRI head (apps/gallery/scenes/head-mcrt.json) and a
 * procedural blob. Uses the renderer's `debugOutput: 'fetches'` kernel variant, which
 * writes the per-path counters instead of radiance.
 *
 *   pnpm run build && node benchmarks/mcrt-fetches.mjs [--size 64] [--iterations 8] [--backend webgl2]
 *
 * Prints a table and one JSON line. Timings on SwiftShader are CPU-bound and noisy;
 * compare ratios from the same run.
 */
import fs from 'node:fs';
import { parseCliOrExit } from '@vpt/cli-options';

const { size, iterations, backend } = parseCliOrExit({
  name: 'node benchmarks/mcrt-fetches.mjs',
  synopsis: '[--size N] [--iterations N] [--backend webgl2|webgpu]',
  summary: 'MCRT medium lookups and majorant-grid cells per path, with and without the grid (needs pnpm run build).',
  options: {
    size: { type: 'integer', min: 1, default: 64, description: 'image side in pixels' },
    iterations: { type: 'integer', min: 1, default: 8, description: 'iterations per configuration' },
    backend: { type: 'string', choices: ['webgl2', 'webgpu'], default: 'webgl2', description: 'the GPU backend' },
  },
});
// After the arguments, so that --help works before a build.
const { openVptPage } = await import('../packages/headless/dist/index.js');

const head = JSON.parse(fs.readFileSync(new URL('../apps/gallery/scenes/head-mcrt.json', import.meta.url), 'utf8'));
const blob = {
  volume: { procedural: 'blob', size: 64 },
  transferFunction: {
    dimensions: '1d',
    points: [
      { value: 0, color: [0.9, 0.9, 0.9], opacity: 0 },
      { value: 0.3, color: [0.9, 0.9, 0.9], opacity: 0 },
      { value: 1, color: [0.9, 0.9, 0.9], opacity: 1 },
    ],
  },
  camera: { position: [0, 0.3, 1.8], target: [0, 0, 0], up: [0, 1, 0], fovy: 0.7 },
  lights: [{ type: 'directional', direction: [1, 1, 0.5], irradiance: [2, 2, 2] }],
  environment: { type: 'constant', radiance: [0.3, 0.35, 0.45] },
  densityScale: 60,
  rendererParams: { anisotropy: 0.3 },
};
const CONFIGS = [
  { tracking: 'residual', majorantGrid: true },
  { tracking: 'residual', majorantGrid: false },
  { tracking: 'ratio', majorantGrid: true },
  { tracking: 'ratio', majorantGrid: false },
  { tracking: 'delta', majorantGrid: true },
  { tracking: 'delta', majorantGrid: false },
];

const session = await openVptPage();
try {
  const rows = await session.page.evaluate(
    async (scenes, configs, size, iterations, backend) => {
      const { core, mcrt, buildScene } = window.vpt;
      const out = [];
      for (const [name, desc] of Object.entries(scenes)) {
        const scene = await buildScene({ ...desc, renderer: 'mcrt' }, location.origin + '/apps/gallery/scenes/');
        for (const cfg of configs) {
          const params = { ...(desc.rendererParams ?? {}), ...cfg };
          // Counters: mean over all pixels and iterations of (lookups, cells, depth).
          const r = new mcrt.McrtRenderer({ ...params, debugOutput: 'fetches' });
          const ctx = await core.RenderContext.create({ backend, width: size, height: size, renderer: r });
          ctx.setScene(scene);
          await ctx.renderIterations(iterations);
          const acc = await ctx.readHDR();
          let lookups = 0,
            cells = 0,
            depth = 0;
          for (let i = 0; i < acc.length; i += 4) {
            lookups += acc[i];
            cells += acc[i + 1];
            depth += acc[i + 2];
          }
          const n = acc.length / 4;
          // Time of the radiance kernel (warm-up compiles it).
          ctx.renderer.setParams({ debugOutput: 'none' });
          await ctx.renderIterations(1);
          await ctx.renderIterations(iterations);
          out.push({
            scene: name,
            ...cfg,
            lookupsPerPath: lookups / n,
            cellsPerPath: cells / n,
            scatteringPerPath: depth / n,
            msPerIteration: ctx.stats.msPerIteration,
          });
          ctx.dispose();
        }
      }
      return out;
    },
    { head, blob },
    CONFIGS,
    size,
    iterations,
    backend,
  );
  console.log(`MCRT work per path, ${size}x${size}, ${iterations} iterations, ${backend}`);
  console.log('scene  tracking  grid   lookups/path  cells/path  scatterings/path  ms/iteration');
  for (const r of rows)
    console.log(
      `${r.scene.padEnd(6)} ${r.tracking.padEnd(9)} ${String(r.majorantGrid).padEnd(6)} ${r.lookupsPerPath.toFixed(1).padStart(12)} ${r.cellsPerPath.toFixed(1).padStart(11)} ${r.scatteringPerPath.toFixed(2).padStart(17)} ${r.msPerIteration.toFixed(1).padStart(13)}`,
    );
  console.log(JSON.stringify({ size, iterations, backend, rows }));
} finally {
  await session.close();
}
