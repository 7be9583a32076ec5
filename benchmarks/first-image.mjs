#!/usr/bin/env node
/**
 * Time to the first image (docs/benchmarks.md, "First image"): per renderer and backend, the
 * headless page's `setupMs` for the gallery's head scene (apps/gallery/scenes/head-<name>.json)
 * at one iteration: context creation, volume fetch and upload, kernel compilation, one
 * iteration, the render and post passes, GPU finished. Each sample runs in a fresh Chromium, so
 * no shader cache of an earlier sample helps it.
 *
 * With --baseline DIR (another checkout, built: its packages/<name>/dist) every sample is taken
 * with both builds, interleaved (A B, then B A), and the two LDR images are compared byte for
 * byte. Prints one line per sample with the load average, then medians and ratios as JSON.
 *
 *   pnpm run build && node benchmarks/first-image.mjs [--rounds N] [--renderers eam,mcrt] [--backends webgl2,webgpu] [--size N] [--baseline DIR]
 */
import crypto from 'node:crypto';
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import { parseCliOrExit } from '@vpt/cli-options';

const args = parseCliOrExit({
  name: 'node benchmarks/first-image.mjs',
  synopsis: '[--rounds N] [--renderers LIST] [--backends LIST] [--size N] [--baseline DIR]',
  summary: 'Time to the first image per renderer and backend, in fresh browsers (needs pnpm run build).',
  options: {
    rounds: { type: 'integer', min: 1, default: 3, description: 'samples per renderer, backend and build' },
    renderers: { type: 'list', description: 'renderer names (default: every catalog renderer with a head scene)' },
    backends: {
      type: 'list',
      choices: ['webgl2', 'webgpu'],
      default: ['webgl2', 'webgpu'],
      description: 'GPU backends',
    },
    size: { type: 'integer', min: 1, default: 256, description: 'image side in pixels' },
    baseline: { type: 'string', description: 'another built checkout to interleave with (its packages/*/dist)' },
  },
});
// After the arguments, so that --help works before a build.
const headless = await import('../packages/headless/dist/index.js');
const { RENDERER_CATALOG, rendererNames } = await import('../packages/core/dist/index.js');

const root = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '..');
const sceneFile = (name) => path.join(root, 'apps/gallery/scenes', `head-${name}.json`);
const renderers = (args.renderers ?? rendererNames()).filter((name) => {
  if (!rendererNames().includes(name)) throw new Error(`first-image: unknown renderer ${name}`);
  return fs.existsSync(sceneFile(name));
});

// The baseline's page packages: core, post, loaders and every catalog renderer.
let baselineDirs = null;
if (args.baseline) {
  const folders = ['core', 'post', 'loaders', ...RENDERER_CATALOG.map((e) => e.packageName.replace(/^@vpt\//, ''))];
  baselineDirs = Object.fromEntries(folders.map((f) => [f, path.resolve(args.baseline, 'packages', f)]));
  for (const [f, dir] of Object.entries(baselineDirs))
    if (!fs.existsSync(path.join(dir, 'dist'))) throw new Error(`first-image: ${dir}/dist missing (build ${f} there)`);
}

const load = () =>
  os
    .loadavg()
    .map((x) => x.toFixed(2))
    .join(' / ');
const median = (xs) => {
  const s = [...xs].sort((a, b) => a - b);
  return s.length % 2 ? s[(s.length - 1) / 2] : (s[s.length / 2 - 1] + s[s.length / 2]) / 2;
};

async function sample(name, backend, build) {
  const { description, baseDir } = headless.readSceneFile(sceneFile(name));
  const result = await headless.renderScene(description, {
    baseDir,
    sceneRoot: root,
    backend,
    iterations: 1,
    width: args.size,
    height: args.size,
    ...(build === 'baseline' ? { packageDirs: baselineDirs } : {}),
  });
  const image = result.ldr ?? result.hdr;
  return { ms: result.timings.setupMs, sha: crypto.createHash('sha256').update(image).digest('hex').slice(0, 16) };
}

const builds = baselineDirs ? ['baseline', 'current'] : ['current'];
const times = {};
const mismatches = [];
console.log(
  `first-image: ${args.size}² px, ${args.rounds} rounds, ${renderers.join(', ')} on ${args.backends.join(', ')}; load ${load()}`,
);
for (let round = 0; round < args.rounds; round++) {
  for (const name of renderers) {
    for (const backend of args.backends) {
      // A B, then B A: drift of the machine's load falls on both builds alike.
      const order = round % 2 ? [...builds].reverse() : builds;
      const shas = {};
      for (const build of order) {
        const { ms, sha } = await sample(name, backend, build);
        shas[build] = sha;
        (times[`${name}|${backend}|${build}`] ??= []).push(ms);
        console.log(
          `round ${round + 1} ${name.padEnd(6)} ${backend.padEnd(7)} ${build.padEnd(8)} ${ms.toFixed(0).padStart(6)} ms  image ${sha}  load ${load()}`,
        );
      }
      if (baselineDirs && shas.baseline !== shas.current) mismatches.push(`${name} ${backend} round ${round + 1}`);
    }
  }
}

const rows = [];
for (const name of renderers) {
  for (const backend of args.backends) {
    const row = { renderer: name, backend };
    for (const build of builds) row[`${build}Ms`] = Math.round(median(times[`${name}|${backend}|${build}`]));
    if (baselineDirs) {
      const a = times[`${name}|${backend}|baseline`];
      const b = times[`${name}|${backend}|current`];
      row.ratio = +median(b.map((x, i) => x / a[i])).toFixed(3);
    }
    rows.push(row);
  }
}
for (const r of rows) console.log(JSON.stringify(r));
console.log(JSON.stringify({ load: load(), rows, imagesDiffer: mismatches }));
if (mismatches.length) {
  console.error(`first-image: the builds' images differ: ${mismatches.join('; ')}`);
  process.exit(1);
}
