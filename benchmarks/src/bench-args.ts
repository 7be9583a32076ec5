/**
 * `pnpm bench`'s command line (the option table is bench-cli.mjs) → what run.ts runs: a copy
 * of the chosen preset with the flags applied (the PRESETS table itself is never changed,
 * so one process can read it again), the suites, backends and filters.
 */
import { parseCli } from '@vpt/cli-options';
import { BENCH_CLI } from './bench-cli.mjs';
import type { Backend, Preset } from './configs.js';

export interface BenchSettings {
  preset: Preset;
  suites: string[];
  backends: Backend[];
  /** Renderer-label prefixes (empty: all). */
  renderers: string[];
  /** Estimator labels after "mcrt fixed: " (empty: all). */
  variants: string[];
}

/** Whether argv asks for the side-by-side suite (`--vpt DIR`), which has its own options (SIDE_CLI). */
export function wantsSideBySide(argv: readonly string[]): boolean {
  return argv.some((a) => a === '--vpt' || a.startsWith('--vpt='));
}

/** Parse `pnpm bench`'s arguments; null for --help. Throws CliArgsError on bad input. */
export function benchSettings(argv: readonly string[], presets: Record<string, Preset>): BenchSettings | null {
  const parsed = parseCli(BENCH_CLI, argv);
  if (parsed.help) return null;
  const v = parsed.values;
  const chosen = presets[v.preset];
  // bench-cli.mjs lists the names (so the launcher checks them before building); a test keeps the lists equal.
  if (!chosen) throw new Error(`preset "${v.preset}" is in bench-cli.mjs but not in configs.ts`);
  const preset = structuredClone(chosen);
  if (v.scenes) preset.errorScenes = v.scenes;
  if (v['cost-rounds'] !== undefined) preset.costRounds = v['cost-rounds'];
  if (v['cost-batch'] !== undefined) preset.costBatch = v['cost-batch'];
  if (v.seed !== undefined) preset.curveSeed = v.seed;
  return {
    preset,
    suites: v.suites,
    backends: v.backends,
    renderers: v.renderers ?? [],
    // Labels contain commas, hence '|'.
    variants: v.variants ? v.variants.split('|').map((s) => s.trim()) : [],
  };
}
