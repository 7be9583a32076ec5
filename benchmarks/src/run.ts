/**
 * `pnpm bench --vpt DIR [--quick]`: only the side-by-side suite against the original VPT (vpt-side/run-side.ts).
 * `pnpm bench [--preset quick|full] [--suites error,frame,convergence,scaling,specialization,compact,skipping] [--backends webgl2,webgpu]`
 *   [--scenes a,b] [--renderers prefix,…] and, for `--preset estimators`, [--variants "delta, phase, grid|…"]
 *   [--cost-rounds N] [--cost-batch K] (the round-robin cost measurement's rounds and iterations per batch)
 *   [--seed N] (the error curves' seed: runs with different seeds are independent; estimator-table.js combines them).
 * Runs the suites in headless Chromium and writes benchmarks/results/<stamp>/results.json
 * and report.html. Nothing here asserts a time: comparisons are ratios within one run.
 */
import { existsSync, mkdirSync, readFileSync, writeFileSync } from 'node:fs';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import { openVptPage, CHROMIUM_FLAGS, WEBGPU_FLAGS } from '@vpt/headless';
import {
  ESTIMATOR_VARIANTS,
  FETCHED_SCENES,
  MCRT_VARIANTS,
  PRESETS,
  RENDERERS,
  type Backend,
  type SceneSpec,
} from './configs.js';
import { machineRecord } from './environment.js';
import { htmlReport, type Results } from './report.js';
import { convergence } from './suites/convergence.js';
import { errorVsTime } from './suites/error-vs-time.js';
import { frameTime } from './suites/frame-time.js';
import { scaling } from './suites/scaling.js';
import { specialization } from './suites/specialization.js';
import { compact } from './suites/compact.js';
import { skipping } from './suites/skipping.js';
import { denoise } from './suites/denoise.js';
import type { SuiteContext } from './suites/types.js';
import { runSide } from './vpt-side/run-side.js';

if (process.argv.includes('--vpt')) {
  await runSide(process.argv);
  process.exit(0);
}

function arg(name: string, fallback: string): string {
  const i = process.argv.indexOf(`--${name}`);
  return i > 0 && process.argv[i + 1] ? process.argv[i + 1] : fallback;
}

const preset = PRESETS[arg('preset', 'quick')];
if (!preset) throw new Error(`unknown preset (use ${Object.keys(PRESETS).join(', ')})`);
const suites = arg('suites', 'error,frame,convergence,scaling,specialization,compact').split(',');
const backends = arg('backends', 'webgl2,webgpu').split(',') as Backend[];
const only = arg('renderers', '');
const sceneFilter = arg('scenes', '');
if (sceneFilter) preset.errorScenes = sceneFilter.split(',');
// Estimator study: only these fixed estimators, '|'-separated (their labels contain commas), e.g. "delta, phase, grid|residual, phase, grid".
const variantFilter = arg('variants', '');
const costRounds = arg('cost-rounds', '');
if (costRounds) preset.costRounds = Number(costRounds);
const costBatch = arg('cost-batch', '');
if (costBatch) preset.costBatch = Number(costBatch);
const curveSeed = arg('seed', '');
if (curveSeed) preset.curveSeed = Number(curveSeed);
const keepVariant = (r: { label: string }) =>
  !variantFilter || variantFilter.split('|').some((v) => r.label === `mcrt fixed: ${v}`);

/** FETCHED_SCENES whose raw file `pnpm data:fetch` has put in data/fetched/, with their sidecar's geometry. */
function fetchedScenes(): { present: Record<string, SceneSpec>; absent: string[] } {
  const dir = fileURLToPath(new URL('../../data/fetched/', import.meta.url));
  const present: Record<string, SceneSpec> = {},
    absent: string[] = [];
  for (const [name, f] of Object.entries(FETCHED_SCENES)) {
    const sidecarPath = path.join(dir, f.sidecar);
    const sidecar = existsSync(sidecarPath) ? JSON.parse(readFileSync(sidecarPath, 'utf8')) : null;
    if (!sidecar || !existsSync(path.join(dir, sidecar.file))) {
      absent.push(`${name} (not fetched: pnpm data:fetch)`);
      continue;
    }
    present[name] = {
      ...f.scene,
      volume: {
        kind: 'raw',
        url: `/data/fetched/${sidecar.file}`,
        dims: sidecar.dims,
        type: sidecar.voxel_type,
        valueRange: sidecar.value_range,
        spacing: sidecar.spacing ?? [1, 1, 1],
      },
    };
  }
  return { present, absent };
}

const started = Date.now();
const log = (line: string) => console.log(`[${((Date.now() - started) / 1000).toFixed(0).padStart(5)} s] ${line}`);
const session = await openVptPage();
try {
  // page-code.js is an ES module of this build: the page imports it from the mounted dist/.
  const dist = session.mount(fileURLToPath(new URL('.', import.meta.url)));
  await session.page.evaluate(async (url: string) => {
    const pageCode = (await import(url)) as typeof import('./page-code.js');
    pageCode.installBenchPage();
  }, `${dist}page-code.js`);
  const available = await session.page.evaluate(() =>
    (window as unknown as { bench: { available(): string[] } }).bench.available(),
  );
  const keep = (r: { renderer: string; label: string }) =>
    available.includes(r.renderer) && (!only || only.split(',').some((o) => r.label.startsWith(o)));
  const skipped = [...RENDERERS, ...MCRT_VARIANTS]
    .filter((r) => !available.includes(r.renderer))
    .map((r) => `${r.label} (package not in this build)`);
  const results: Results = {
    machine: machineRecord(await session.browser.version(), [...CHROMIUM_FLAGS, ...WEBGPU_FLAGS]),
    backends: Object.fromEntries(
      await Promise.all(
        backends.map(async (b) => [
          b,
          await session.page.evaluate(
            (b) => (window as unknown as { bench: { backendInfo(b: string): Promise<unknown> } }).bench.backendInfo(b),
            b,
          ),
        ]),
      ),
    ),
    preset: preset.name,
    skipped,
  };
  const fetched = fetchedScenes();
  results.skipped.push(...fetched.absent);
  const ctx: SuiteContext = {
    page: session.page,
    preset,
    backends,
    renderers: RENDERERS.filter(keep).filter((r) => !preset.rendererLabels || preset.rendererLabels.includes(r.label)),
    mcrtVariants: (preset.estimatorStudy ? ESTIMATOR_VARIANTS.filter(keepVariant) : MCRT_VARIANTS).filter(keep),
    fetchedScenes: fetched.present,
    log,
  };
  if (suites.includes('frame')) results.frameTime = await frameTime(ctx);
  if (suites.includes('error')) results.errorVsTime = await errorVsTime(ctx);
  if (suites.includes('convergence')) results.convergence = await convergence(ctx);
  if (suites.includes('scaling')) results.scaling = await scaling(ctx);
  if (suites.includes('specialization') && available.includes('mcrt'))
    results.specialization = await specialization(ctx);
  if (suites.includes('compact')) results.compact = await compact(ctx);
  if (suites.includes('skipping')) results.skipping = await skipping(ctx);
  // Not in the default list: `--suites denoise` (issue 14's denoiser figures).
  if (suites.includes('denoise') && available.includes('mcrt')) results.denoise = await denoise(ctx);

  const dir = path.join(
    fileURLToPath(new URL('..', import.meta.url)),
    'results',
    new Date().toISOString().replace(/[:.]/g, '-'),
  );
  mkdirSync(dir, { recursive: true });
  writeFileSync(path.join(dir, 'results.json'), JSON.stringify(results, null, 2));
  writeFileSync(path.join(dir, 'report.html'), htmlReport(results));
  log(`wrote ${path.join(dir, 'report.html')}`);
} finally {
  await session.close();
}
