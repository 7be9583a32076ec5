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
import { parseCliOrExit } from '@vpt/cli-options';
import { COST_OPTIONS, COST_SYNOPSIS, runInterleavedCost } from './src/interleaved-cost.mjs';

const options = parseCliOrExit({
  name: 'node benchmarks/slice-plane-cost.mjs',
  synopsis: COST_SYNOPSIS,
  summary: 'ms per iteration with and without a slice plane, per renderer, interleaved (needs pnpm run build).',
  options: COST_OPTIONS,
});

// Through the centre: the rays that meet it stop halfway. Through the last layer (behind the blob
// as seen from the camera): the rays run as far as without it, so this is the plane code's own cost.
const PLANE = { axis: 'z', index: 32 };
const BACK_PLANE = { axis: 'z', index: 0 };

await runInterleavedCost({
  name: 'slice-plane-cost',
  options,
  baseline: 'none',
  variants: [
    ['plane', { slicePlane: PLANE }],
    ['back', { slicePlane: BACK_PLANE }],
  ],
});
