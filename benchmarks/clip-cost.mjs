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
import { parseCliOrExit } from '@vpt/cli-options';
import { COST_OPTIONS, COST_SYNOPSIS, runInterleavedCost } from './src/interleaved-cost.mjs';

const options = parseCliOrExit({
  name: 'node benchmarks/clip-cost.mjs',
  synopsis: COST_SYNOPSIS,
  summary: 'ms per iteration with and without clipping, per renderer, interleaved (needs pnpm run build).',
  options: COST_OPTIONS,
});

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

await runInterleavedCost({
  name: 'clip-cost',
  options,
  baseline: 'unclipped',
  variants: [
    ['clipped', { clip: CLIP }],
    ['noop', { clip: NOOP_CLIP }],
  ],
});
