#!/usr/bin/env node
/**
 * openTimeSeries over one 4D file: reading the file once (TimeSeriesOptions.keepBytes, the
 * default) against reading it again per step (keepBytes: 0, the behaviour before), in Node
 * (in-thread decode), by file path as a File: a .nii.gz (inflated once vs inflated up to each
 * step) and an .nrrd with gzip encoding (both inflate up to each step; the read is saved).
 * Runs A B A B… interleaved and prints medians, the ratio and the load average.
 *
 *   node benchmarks/time-series-read.mjs [--size 64] [--steps 12] [--rounds 5]
 */
import os from 'node:os';
import path from 'node:path';
import { fileURLToPath, pathToFileURL } from 'node:url';
import zlib from 'node:zlib';
import { parseCliOrExit } from '@vpt/cli-options';

const {
  size: N,
  steps: T,
  rounds: ROUNDS,
} = parseCliOrExit({
  name: 'node benchmarks/time-series-read.mjs',
  synopsis: '[--size N] [--steps N] [--rounds N]',
  summary: 'openTimeSeries over one 4D file: read once vs read per step (needs pnpm run build).',
  options: {
    size: { type: 'integer', min: 1, default: 64, description: 'volume side in voxels' },
    steps: { type: 'integer', min: 1, default: 12, description: 'time steps' },
    rounds: { type: 'integer', min: 1, default: 5, description: 'A B rounds' },
  },
});

// The built package (pnpm --filter @vpt/loaders run build), as read-speed.mjs loads it.
const here = path.dirname(fileURLToPath(import.meta.url));
const { openTimeSeries } = await import(pathToFileURL(path.join(here, '../packages/loaders/dist/index.js')).href);

const count = N * N * N;
const voxels = new Float32Array(count * T);
for (let i = 0; i < voxels.length; i++) voxels[i] = Math.sin(i * 0.001) * 100 + (i % 97);
const payload = new Uint8Array(voxels.buffer);

function nifti() {
  const out = new Uint8Array(352 + payload.length);
  const v = new DataView(out.buffer);
  v.setInt32(0, 348, true);
  [4, N, N, N, T, 1, 1, 1].forEach((d, i) => v.setInt16(40 + 2 * i, d, true));
  v.setInt16(70, 16, true);
  v.setInt16(72, 32, true);
  for (let i = 0; i < 8; i++) v.setFloat32(76 + 4 * i, 1, true);
  v.setFloat32(108, 352, true);
  out.set([0x6e, 0x2b, 0x31, 0], 344);
  out.set(payload, 352);
  return new Uint8Array(zlib.gzipSync(out, { level: 1 }));
}
function nrrd() {
  const head = new globalThis.TextEncoder().encode(
    `NRRD0004\ntype: float\ndimension: 4\nsizes: ${N} ${N} ${N} ${T}\nkinds: domain domain domain time\nendian: little\nencoding: gzip\n\n`,
  );
  const gz = zlib.gzipSync(payload, { level: 1 });
  const out = new Uint8Array(head.length + gz.length);
  out.set(head);
  out.set(gz, head.length);
  return out;
}

async function allSteps(file, keepBytes) {
  const t0 = performance.now();
  const s = await openTimeSeries(file, { keepBytes });
  for (let t = 0; t < s.steps; t++) await s.loadStep(t);
  return performance.now() - t0;
}

const median = (a) => [...a].sort((x, y) => x - y)[Math.floor(a.length / 2)];
console.log(
  `load average before: ${os
    .loadavg()
    .map((x) => x.toFixed(1))
    .join(' ')}`,
);
for (const [name, bytes] of [
  [`series.nii.gz`, nifti()],
  [`series.nrrd`, nrrd()],
]) {
  const file = new File([bytes], name);
  const once = [],
    again = [];
  await allSteps(file, undefined); // warm-up (JIT, fflate import)
  for (let r = 0; r < ROUNDS; r++) {
    once.push(await allSteps(file, undefined));
    again.push(await allSteps(file, 0));
  }
  const a = median(once),
    b = median(again);
  console.log(
    `${name} (${N}³ float32 × ${T} steps, ${(bytes.length / 1e6).toFixed(1)} MB): read once ${a.toFixed(0)} ms, per step ${b.toFixed(0)} ms, ratio ${(b / a).toFixed(2)}`,
  );
}
console.log(
  `load average after: ${os
    .loadavg()
    .map((x) => x.toFixed(1))
    .join(' ')}`,
);
