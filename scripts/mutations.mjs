#!/usr/bin/env node
/**
 * `pnpm test:mutations`: put plausible one-line bugs into kernels, loaders, the viewer and the
 * CPU references, one at a time, and check that the tests meant to guard that code fail.
 * For each mutation: edit the file (the exact `find` string, which must occur exactly once,
 * becomes `replace`), rebuild the package when a browser test loads its dist/, run the named
 * test files (optionally only the tests whose names match `only`), restore the file. A
 * mutation is "caught" when the tests fail, "missed" when they pass.
 *
 * Safety: refuses to run on a tree with uncommitted changes to tracked files (so `git
 * checkout` always recovers), keeps the original text in memory and restores it after each
 * run, on failure, on Ctrl-C (SIGINT), SIGTERM and uncaught errors; then rebuilds every
 * package whose dist/ it changed. A stale `find` string (the code moved or was renamed) is
 * reported as "stale" and fails the run, so the table below is kept up to date.
 *
 * Not part of `pnpm test` (it rebuilds and reruns tests per mutation: minutes).
 * Options: --only a,b (run the named mutations), --list (print the table), --baseline (first
 * run every test selection unmutated; a selection that fails then makes "caught" meaningless).
 */
import { spawn, spawnSync } from 'node:child_process';
import fs from 'node:fs';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import { parseCliOrExit } from '@vpt/cli-options';

const root = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '..');

/**
 * The mutations. file: path from the repository root; find/replace: exact text; build: the
 * package whose dist/ the tests load (browser tests), none for unit tests that import src/;
 * tests: test files; only: a vitest -t pattern selecting the tests aimed at this code.
 */
export const MUTATIONS = [
  // MCRT kernels
  {
    name: 'ratio-roulette-no-rescale-glsl',
    why: 'ratio tracking Russian roulette survivors not rescaled to 0.1',
    file: 'packages/renderer-mcrt/src/kernels/tracking.glsl.ts',
    find: '        T = 0.1;\n      }\n    }\n#if TRACKING == 2',
    replace: '      }\n    }\n#if TRACKING == 2',
    build: '@vpt/renderer-mcrt',
    tests: ['tests/mcrt-transmittance.test.ts'],
    only: 'dense medium',
  },
  {
    name: 'ratio-roulette-no-rescale-wgsl',
    why: 'the same in WGSL',
    file: 'packages/renderer-mcrt/src/kernels/tracking.wgsl.ts',
    find: '        T = 0.1;\n      }\n    }\n#if TRACKING == 2',
    replace: '      }\n    }\n#if TRACKING == 2',
    build: '@vpt/renderer-mcrt',
    tests: ['tests/mcrt-transmittance.test.ts'],
    only: 'dense medium',
  },
  {
    name: 'majorant-upper-border-dropped-cpu',
    why: 'majorant grid cell range misses its upper border (+2 → +0)',
    file: 'packages/core/src/majorant/majorant-grid.ts',
    find: 'const hi = Math.floor(((c + 1) * N) / G - 0.5) + 2;',
    replace: 'const hi = Math.floor(((c + 1) * N) / G - 0.5) + 0;',
    tests: ['packages/renderer-mcrt/test/majorant-grid.test.ts'],
    only: 'true bound on smooth data|high side',
  },
  {
    name: 'majorant-upper-border-dropped-glsl',
    why: 'the same in the GPU build (GLSL)',
    file: 'packages/core/src/majorant/majorant-build.glsl.ts',
    find: 'int hi = floorDiv(2 * (c + 1) * n - g, 2 * g) + 2;',
    replace: 'int hi = floorDiv(2 * (c + 1) * n - g, 2 * g) + 0;',
    build: '@vpt/core',
    tests: ['tests/mcrt-majorant-gpu.test.ts'],
    only: 'true upper bound',
  },
  {
    name: 'majorant-upper-border-dropped-wgsl',
    why: 'the same in the GPU build (WGSL)',
    file: 'packages/core/src/majorant/majorant-build.wgsl.ts',
    find: 'let hi = floorDiv(2 * (c + 1) * n - g, 2 * g) + 2;',
    replace: 'let hi = floorDiv(2 * (c + 1) * n - g, 2 * g) + 0;',
    build: '@vpt/core',
    tests: ['tests/mcrt-majorant-gpu.test.ts'],
    only: 'true upper bound',
  },
  {
    name: 'mip-skip-bound-too-low-glsl',
    why: 'MIP skips cells whose largest value is underestimated (a bound that is not one)',
    file: 'packages/renderer-mip/src/kernels/mip.glsl.ts',
    find: 'return m > 0.0 ? m + 1e-5 : 0.0;',
    replace: 'return m > 0.0 ? m - 0.05 : 0.0;',
    build: '@vpt/renderer-mip',
    tests: ['tests/empty-space-skipping.test.ts'],
    only: 'webgl2.*MIP',
  },
  {
    name: 'hg-sign-flipped-glsl',
    why: 'HG phase of the light direction evaluated with −g',
    file: 'packages/renderer-mcrt/src/kernels/path.glsl.ts',
    find: 'float ph = hgPhase(u.phaseG, dot(w, l));',
    replace: 'float ph = hgPhase(-u.phaseG, dot(w, l));',
    build: '@vpt/renderer-mcrt',
    tests: ['tests/mcrt-single-scattering.test.ts'],
  },
  {
    name: 'mis-weight-dropped-glsl',
    why: 'environment hit by phase sampling not MIS-weighted',
    file: 'packages/renderer-mcrt/src/kernels/path.glsl.ts',
    find: 'return e.rgb * misWeight(phasePdf, e.a);',
    replace: 'return e.rgb;',
    build: '@vpt/renderer-mcrt',
    tests: ['tests/mcrt-unbiased.test.ts'],
    only: 'HDR environment',
  },
  {
    name: 'nan-not-zeroed-wgsl',
    why: 'non-finite radiance no longer zeroed before accumulation',
    file: 'packages/renderer-mcrt/src/kernels/path.wgsl.ts',
    find: 'o.out0 = vec4f(finiteOrZero(L), alpha);',
    replace: 'o.out0 = vec4f(L, alpha);',
    build: '@vpt/renderer-mcrt',
    tests: ['tests/mcrt-stiff.test.ts'],
    only: 'stiff media on webgpu',
  },
  // EAM
  {
    name: 'eam-fixed-offset-glsl',
    why: 'EAM march offset fixed at 0.5 instead of random',
    file: 'packages/renderer-eam/src/kernels/eam.glsl.ts',
    find: 'float offset = rngNext(rng);',
    replace: 'float offset = 0.5;',
    build: '@vpt/renderer-eam',
    tests: ['tests/eam.test.ts'],
    only: 'CPU twin',
  },
  {
    name: 'eam-fixed-offset-wgsl',
    why: 'the same in WGSL',
    file: 'packages/renderer-eam/src/kernels/eam.wgsl.ts',
    find: 'let offset = rngNext(&rng);',
    replace: 'let offset = 0.5;',
    build: '@vpt/renderer-eam',
    tests: ['tests/eam.test.ts'],
    only: 'CPU twin',
  },
  // Post
  {
    name: 'aces-typo-wgsl',
    why: 'ACES fit coefficient typo (2.43 → 2.34) in WGSL',
    file: 'packages/post/src/tone-mapping.wgsl.ts',
    find: '(x * (2.43 * x + 0.59) + 0.14)',
    replace: '(x * (2.34 * x + 0.59) + 0.14)',
    build: '@vpt/post',
    tests: ['tests/post.test.ts'],
  },
  // Loaders
  {
    name: 'nrrd-gzip-ignores-endianness',
    why: 'gzip-encoded NRRD data always read little-endian',
    file: 'packages/loaders/src/formats/nrrd.ts',
    find: "samples = readSamples(inflated, Math.max(0, from), count, source, endian === 'little');",
    replace: 'samples = readSamples(inflated, Math.max(0, from), count, source, true);',
    tests: ['packages/loaders/test/nrrd.test.ts'],
  },
  // Viewer
  {
    name: 'viewer-number-upper-bound-lost',
    why: 'number attributes no longer checked against their maximum',
    file: 'packages/viewer/src/attributes.ts',
    find: 'n < min || n > max ||',
    replace: 'n < min ||',
    tests: ['packages/viewer/test/attributes.test.ts'],
  },
  {
    name: 'viewer-number-upper-bound-lost-element',
    why: 'the same, seen through <vpt-viewer> attributes',
    file: 'packages/viewer/src/attributes.ts',
    find: 'n < min || n > max ||',
    replace: 'n < min ||',
    build: '@vpt/viewer',
    tests: ['tests/viewer-element.test.ts'],
    only: 'above their maximum',
  },
  // CPU twins shared by the references of many tests
  {
    name: 'cpu-twin-trilinear-not-cell-centred',
    why: 'CPU sampler uses corner-aligned voxels (drops the −0.5)',
    file: 'packages/core/src/reference/cpu-reference.ts',
    find: '* this.dims[a] - 0.5);',
    replace: '* this.dims[a]);',
    tests: ['packages/core/test/cpu-reference.test.ts'],
  },
  {
    name: 'cpu-twin-camera-y-up',
    why: 'CPU camera ray with film y up instead of down',
    file: 'packages/core/src/reference/cpu-reference.ts',
    find: 'sy = (1 - 2 * fy) * t;',
    replace: 'sy = (2 * fy - 1) * t;',
    tests: ['packages/core/test/cpu-reference.test.ts'],
  },
  {
    name: 'cpu-twin-box-direction-sign-lost',
    why: 'CPU box intersection ignores the sign of the direction',
    file: 'packages/core/src/reference/cpu-reference.ts',
    find: 'const inv = (d[a] < 0 ? -1 : 1) / Math.max(Math.abs(d[a]), 1e-20);',
    replace: 'const inv = 1 / Math.max(Math.abs(d[a]), 1e-20);',
    tests: ['packages/core/test/cpu-reference.test.ts'],
  },
  // Denoiser
  {
    name: 'denoise-no-luminance-weight-glsl',
    why: 'the à-trous weight loses its luminance edge-stopping term (a plain guided blur)',
    file: 'packages/post/src/denoise.glsl.ts',
    find: 'float w = h * wl * wz * wn * wa;',
    replace: 'float w = h * wz * wn * wa;',
    build: '@vpt/post',
    tests: ['tests/denoise.test.ts'],
    only: 'CPU twin',
  },
  {
    name: 'guide-moments-count-stuck-glsl',
    why: 'the guide integrate pass records n = 1 forever, so the denoiser never sees the variance of the mean fall',
    file: 'packages/core/src/shaders/guides.glsl.ts',
    find: 'vpt_out2 = vec4(a2.xy + (f2.xy - a2.xy) * w, f2.z, 0.0);',
    replace: 'vpt_out2 = vec4(a2.xy + (f2.xy - a2.xy) * w, 1.0, 0.0);',
    build: '@vpt/core',
    tests: ['tests/denoise.test.ts'],
    only: 'converged EAM',
  },
  // Slice renderer
  {
    name: 'slice-window-after-range-clamp-glsl',
    why: 'the slice window applied to the value-range-clamped normalized value instead of the data',
    file: 'packages/renderer-slice/src/kernels/slice.glsl.ts',
    find: 'float n = sliceTexel(p) * u.valueScale + u.valueOffset;',
    replace: 'float n = volumeValue(sliceTexel(p));',
    build: '@vpt/renderer-slice',
    tests: ['tests/slice.test.ts'],
    only: 'webgl2.*int16',
  },
  {
    name: 'slice-nearest-rounds-wgsl',
    why: 'nearest sampling rounds the voxel coordinate (the neighbouring voxel at every centre)',
    file: 'packages/renderer-slice/src/kernels/slice.wgsl.ts',
    find: 'vec3i(floor(tc * vec3f(dims)))',
    replace: 'vec3i(round(tc * vec3f(dims)))',
    build: '@vpt/renderer-slice',
    tests: ['tests/slice.test.ts'],
    only: 'webgpu.*fit with the image',
  },
  {
    name: 'slice-axial-image-axes-swapped',
    why: 'a z slice shows y along the columns and x down the rows (a transposed image)',
    file: 'packages/renderer-slice/src/plane.ts',
    find: '{ 0: [1, 2], 1: [0, 2], 2: [0, 1] }',
    replace: '{ 0: [1, 2], 1: [0, 2], 2: [1, 0] }',
    tests: ['packages/renderer-slice/test/plane.test.ts'],
  },
];

const args = parseCliOrExit({
  name: 'pnpm test:mutations',
  synopsis: '[--only A,B] [--list] [--baseline]',
  summary:
    'Put plausible one-line bugs into the code one at a time and check that the related tests fail\n' +
    '(minutes; refuses a tree with uncommitted changes, always restores).',
  options: {
    only: { type: 'list', valueName: 'A,B', description: 'run only the named mutations (--list shows the names)' },
    list: { type: 'boolean', description: 'print the table of mutations and stop' },
    baseline: { type: 'boolean', description: 'first run every test selection unmutated' },
  },
});

if (args.list) {
  for (const m of MUTATIONS)
    console.log(`${m.name.padEnd(38)} ${m.file}  →  ${m.tests.join(' ')}${m.only ? ` -t "${m.only}"` : ''}`);
  process.exit(0);
}

const sh = (cmd, cmdArgs, opts = {}) => spawnSync(cmd, cmdArgs, { cwd: root, encoding: 'utf8', ...opts });

// 1. A clean tree: whatever happens, `git checkout -- .` gets the code back.
const dirty = sh('git', ['status', '--porcelain', '--untracked-files=no']).stdout.trim();
if (dirty) {
  console.error(
    `mutations: refusing to run on a tree with uncommitted changes (commit or stash them first):\n${dirty}`,
  );
  process.exit(2);
}

const only = args.only;
const selected = only ? MUTATIONS.filter((m) => only.includes(m.name)) : MUTATIONS;
if (only && selected.length !== only.length) {
  console.error(`mutations: unknown name in --only (known: ${MUTATIONS.map((m) => m.name).join(', ')})`);
  process.exit(2);
}

// 2. Restore on every way out.
let pending = null; // { file, text } while a mutation is applied
let child = null; // the build or test run in progress
const staleDist = new Set(); // packages whose dist/ was built from mutated source
function restore() {
  if (!pending) return;
  fs.writeFileSync(path.join(root, pending.file), pending.text);
  console.log(`  restored ${pending.file}`);
  pending = null;
}
for (const sig of ['SIGINT', 'SIGTERM', 'SIGHUP']) {
  process.on(sig, () => {
    child?.kill('SIGTERM');
    restore();
    console.error(
      `\nmutations: interrupted (${sig}); source restored.${staleDist.size ? ` Rebuild ${[...staleDist].join(', ')} (pnpm run build) before browser tests.` : ''}`,
    );
    process.exit(130);
  });
}
process.on('uncaughtException', (e) => {
  restore();
  console.error(e);
  process.exit(1);
});
process.on('exit', restore);

/** Run a command asynchronously, so a signal reaches the handlers above while it runs. */
function run(cmd, cmdArgs) {
  return new Promise((resolve) => {
    let stdout = '',
      stderr = '';
    child = spawn(cmd, cmdArgs, { cwd: root });
    child.stdout.on('data', (d) => {
      stdout += d;
    });
    child.stderr.on('data', (d) => {
      stderr += d;
    });
    child.on('close', (status, signal) => {
      child = null;
      if (signal) {
        restore();
        console.error(`mutations: ${cmd} ended by ${signal}; stopping.`);
        process.exit(130);
      }
      resolve({ status, stdout, stderr });
    });
  });
}

async function build(pkg) {
  const r = await run('pnpm', ['--filter', pkg, 'run', 'build']);
  return r.status === 0;
}

async function runTests(m) {
  const r = await run('pnpm', ['exec', 'vitest', 'run', ...m.tests, ...(m.only ? ['-t', m.only] : [])]);
  const out = `${r.stdout}\n${r.stderr}`;
  // Strip colour codes (ESC [ … m) for the summary lines.
  // eslint-disable-next-line no-control-regex -- matching the escape character is the point
  const plain = out.replace(/\x1b\[[0-9;]*m/g, '');
  const summary = (plain.match(/Tests\s+[^\n]+/) ?? ['(no summary)'])[0].trim();
  return {
    passed: r.status === 0,
    summary,
    noTests: /No test files found|No test found/.test(plain) || /Tests\s+\d+ skipped/.test(summary),
  };
}

const results = [];
const started = Date.now();

if (args.baseline) {
  console.log('baseline: every test selection unmutated');
  for (const key of new Set(selected.map((m) => JSON.stringify([m.tests, m.only ?? null])))) {
    const [tests, o] = JSON.parse(key);
    const r = await runTests({ tests, only: o ?? undefined });
    console.log(`  ${r.passed ? 'pass' : 'FAIL'}  ${tests.join(' ')}${o ? ` -t "${o}"` : ''}  (${r.summary})`);
    if (!r.passed) {
      console.error('mutations: a selection fails without any mutation; fix that first.');
      process.exit(1);
    }
  }
}

for (const m of selected) {
  const t0 = Date.now();
  const abs = path.join(root, m.file);
  let result,
    detail = '';
  if (!fs.existsSync(abs)) {
    result = 'stale';
    detail = 'file not found';
  } else {
    const text = fs.readFileSync(abs, 'utf8');
    const count = text.split(m.find).length - 1;
    if (count !== 1) {
      result = 'stale';
      detail = `find string occurs ${count} times`;
    } else {
      // Packages left built from an earlier mutation: rebuild before this run uses them.
      for (const pkg of [...staleDist])
        if (pkg !== m.build) {
          await build(pkg);
          staleDist.delete(pkg);
        }
      pending = { file: m.file, text };
      fs.writeFileSync(abs, text.replace(m.find, m.replace));
      try {
        if (m.build) {
          staleDist.add(m.build);
          if (!(await build(m.build))) {
            result = 'caught';
            detail = 'build fails';
          }
        }
        if (!result) {
          const r = await runTests(m);
          result = r.noTests ? 'no-tests' : r.passed ? 'MISSED' : 'caught';
          detail = r.summary;
        }
      } finally {
        restore();
      }
    }
  }
  const s = ((Date.now() - t0) / 1000).toFixed(0);
  results.push({ name: m.name, file: m.file, result, detail, s });
  console.log(`${result.padEnd(8)} ${m.name.padEnd(38)} ${s.padStart(4)} s  ${m.why}  [${detail}]`);
}

for (const pkg of staleDist) await build(pkg);
staleDist.clear();

const caught = results.filter((r) => r.result === 'caught').length;
console.log(`\nmutations: ${caught} of ${results.length} caught in ${((Date.now() - started) / 60000).toFixed(1)} min`);
const bad = results.filter((r) => r.result !== 'caught');
for (const r of bad) console.log(`  ${r.result}: ${r.name} (${r.file}) ${r.detail}`);
process.exit(bad.length ? 1 : 0);
