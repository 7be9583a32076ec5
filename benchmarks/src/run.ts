/**
 * `pnpm bench [--preset NAME] [--suites A,B] [--backends …] [--scenes …] [--renderers …] [--variants …]
 * [--cost-rounds N] [--cost-batch K] [--seed N]`, or `pnpm bench --vpt DIR …` for only the side-by-side
 * suite against the original VPT (vpt-side/run-side.ts). The options are bench-cli.mjs's tables
 * (`pnpm bench --help`); bench.mjs checks them before building, this checks them again when run directly.
 * Runs the suites in headless Chromium and writes benchmarks/results/<stamp>/results.json
 * and report.html. Nothing here asserts a time: comparisons are ratios within one run.
 */
import { existsSync, mkdirSync, readFileSync, writeFileSync } from 'node:fs';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import { openVptPage, CHROMIUM_FLAGS, WEBGPU_FLAGS } from '@vpt/headless';
import { CliArgsError, cliUsage } from '@vpt/cli-options';
import { benchSettings, wantsSideBySide, type BenchSettings } from './bench-args.js';
import { BENCH_CLI } from './bench-cli.mjs';
import { ESTIMATOR_VARIANTS, FETCHED_SCENES, MCRT_VARIANTS, PRESETS, RENDERERS, type SceneSpec } from './configs.js';
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

const argv = process.argv.slice(2);
if (wantsSideBySide(argv)) {
  await runSide(argv);
  process.exit(0);
}
/** The parsed command line; prints the usage or the error and exits on --help or bad input. */
function settingsOrExit(): BenchSettings {
  let parsed: BenchSettings | null;
  try {
    parsed = benchSettings(argv, PRESETS);
  } catch (e) {
    if (!(e instanceof CliArgsError)) throw e;
    console.error(`pnpm bench: ${e.message} (--help lists the options)`);
    process.exit(2);
  }
  if (!parsed) {
    console.log(cliUsage(BENCH_CLI));
    process.exit(0);
  }
  return parsed;
}
const settings = settingsOrExit();
const { preset, suites, backends } = settings;
const keepVariant = (r: { label: string }) =>
  settings.variants.length === 0 || settings.variants.some((v) => r.label === `mcrt fixed: ${v}`);

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
    available.includes(r.renderer) &&
    (settings.renderers.length === 0 || settings.renderers.some((o) => r.label.startsWith(o)));
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
  // Not in the default list: `--suites denoise` (docs/benchmarks.md, "Denoiser").
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
