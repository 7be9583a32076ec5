#!/usr/bin/env node
/**
 * The denoiser's error at low sample counts and its bias at convergence (docs/benchmarks.md,
 * "Denoiser: SVGF filter"): a scene file (default the gallery's MCRT head) at N² with the chain
 * `[{ "type": "denoise", …params }, { "type": "srgb" }]`, RMSE (linear HDR, RGB) of the plain and
 * the denoised estimate at --low iterations against a --reference-iteration plain reference, over
 * --seeds seeds; and at the reference's own count, how far the denoiser moves the image against
 * the estimate's own noise (RMSE from the half accumulations, RenderContext.estimateError).
 *
 *   pnpm run build && node benchmarks/denoise-error.mjs [--scene FILE] [--size N] [--low N] [--reference N] [--seeds N] [--params JSON]
 */
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import { parseCliOrExit } from '@vpt/cli-options';

const ROOT = fileURLToPath(new URL('..', import.meta.url));
const opts = parseCliOrExit({
  name: 'node benchmarks/denoise-error.mjs',
  synopsis: '[--scene FILE] [--size N] [--low N] [--reference N] [--seeds N] [--params JSON] [--backend B]',
  summary:
    "RMSE of plain vs denoised at a low sample count, and the denoiser's bias at convergence (needs pnpm run build).",
  options: {
    scene: {
      type: 'string',
      valueName: 'FILE',
      default: 'apps/gallery/scenes/head-mcrt.json',
      description: 'a scene file whose volume is a sidecar in data/ (relative to the repository root)',
    },
    size: { type: 'integer', min: 1, default: 64, description: 'image side in pixels' },
    low: { type: 'integer', min: 2, default: 4, description: 'the low sample count (iterations)' },
    reference: { type: 'integer', min: 2, default: 512, description: "the reference's iterations" },
    seeds: { type: 'integer', min: 1, default: 4, description: 'seeds of the low-count estimate' },
    params: { type: 'json', default: {}, description: 'denoise step parameters, e.g. {"iterations":4}' },
    backend: { type: 'string', choices: ['webgl2', 'webgpu'], default: 'webgl2', description: 'the GPU backend' },
  },
});
// After the arguments, so that --help works before a build.
const { openVptPage } = await import('../packages/headless/dist/index.js');

const desc = JSON.parse(fs.readFileSync(path.resolve(ROOT, opts.scene), 'utf8'));
if (!desc.volume?.sidecar) throw new Error(`${opts.scene}: the volume must be a sidecar`);
// The page serves the repository root: the sidecar as a URL path from it.
const sidecar = path.resolve(ROOT, path.dirname(opts.scene), desc.volume.sidecar);
desc.volume = { sidecar: '/' + path.relative(ROOT, sidecar).split(path.sep).join('/') };
const load = () =>
  os
    .loadavg()
    .map((x) => x.toFixed(2))
    .join(' / ');
// The RGB RMSE of two RGBA images (metrics.ts).
const { rgbRmse: rmse } = await import('./dist/metrics.js');

const session = await openVptPage({ root: ROOT });
try {
  console.log(
    `denoise-error: ${opts.scene} at ${opts.size}², ${opts.low} vs ${opts.reference} iterations, ${opts.seeds} seeds, ${opts.backend}; load ${load()}`,
  );
  const runs = [[1000, opts.reference], ...Array.from({ length: opts.seeds }, (_, i) => [i + 1, opts.low])];
  const images = await session.page.evaluate(
    async (d, o, runs) => {
      const { core, post } = window.vpt;
      const ctx = await core.RenderContext.create({
        backend: o.backend,
        width: o.size,
        height: o.size,
        renderer: window.vpt.createRenderer(d.renderer, d.rendererParams),
        post: post.postChainFromJSON([{ type: 'denoise', ...o.params }, { type: 'srgb' }]),
      });
      const out = [];
      for (const [seed, n] of runs) {
        ctx.setScene(await window.vpt.buildScene({ ...d, seed }, location.origin + '/'));
        await ctx.renderIterations(n);
        out.push({
          plain: Array.from(await ctx.readHDR()),
          denoised: Array.from(await ctx.readHDR({ afterPost: true })),
          noise: (await ctx.estimateError())?.rmse ?? null,
        });
      }
      ctx.dispose();
      return out;
    },
    desc,
    opts,
    runs,
  );
  const [ref, ...lows] = images;
  const finite = images.every((im) => im.denoised.every(Number.isFinite));
  const ratios = [];
  lows.forEach((low, i) => {
    const p = rmse(low.plain, ref.plain),
      dn = rmse(low.denoised, ref.plain);
    ratios.push(dn / p);
    console.log(
      `seed ${i + 1}: ${opts.low} it RMSE plain ${p.toFixed(4)}, denoised ${dn.toFixed(4)} (x${(dn / p).toFixed(3)})`,
    );
  });
  const mean = (xs) => xs.reduce((a, b) => a + b, 0) / xs.length;
  const meanPlain = mean(lows.map((l) => rmse(l.plain, ref.plain))),
    meanDen = mean(lows.map((l) => rmse(l.denoised, ref.plain)));
  console.log(
    `mean: plain ${meanPlain.toFixed(4)}, denoised ${meanDen.toFixed(4)} (x${(meanDen / meanPlain).toFixed(3)}; worst seed x${Math.max(...ratios).toFixed(3)})`,
  );
  const noise = ref.noise === null ? 'n/a (no half accumulations)' : ref.noise.toFixed(5);
  console.log(
    `bias at ${opts.reference} it: denoised moves the image by RMSE ${rmse(ref.denoised, ref.plain).toFixed(5)}; the plain estimate's own noise ${noise}`,
  );
  console.log(`all denoised values finite: ${finite}; load ${load()}`);
} finally {
  await session.close();
}
