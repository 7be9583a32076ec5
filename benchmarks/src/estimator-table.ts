/**
 * `node benchmarks/dist/estimator-table.js benchmarks/results/<run>/results.json [<run2>/results.json …]`:
 * the estimator study (preset 'estimators') as a markdown table per scene. For MCRT's default
 * `estimator: 'auto'` and every fixed estimator: iterations to 30 and 35 dB (from the curve:
 * the variance side, independent of the machine's load), ms per iteration measured
 * round-robin across the configurations (the cost side), and their product, the time to
 * 30 / 35 dB; then the best fixed estimator and auto's time over it (the target:
 * docs/benchmarks.md#fig-estimator-table).
 * Several runs (`pnpm bench … --seed N`, one seed each) are combined: iteration figures are
 * averaged over the runs (they are proportional to the estimator's variance), cost samples pooled.
 */
import { readFileSync } from 'node:fs';
import { pathToFileURL } from 'node:url';
import { parseCliOrExit } from '@vpt/cli-options';
import { median, timeToPsnr } from './metrics.js';
import type { ErrorCurveResult } from './suites/error-vs-time.js';

const AUTO = 'mcrt multiple';
const TARGETS = [30, 35];

/** Iterations to `db` (interpolated in log iterations like time), or null. */
export const iterationsTo = (c: ErrorCurveResult, db: number) =>
  timeToPsnr(
    c.points.map((p) => ({ ...p, ms: p.iterations })),
    db,
  );

/**
 * Iterations to `db` extrapolated from the curve's last point (the most samples) by the 1/n
 * law of an unbiased estimator's MSE: n · 10^((db − psnr(n))/10). Less noisy than the
 * crossing, which rests on the few iterations around it, and defined where the budget ended
 * before the target (35 dB on slow scenes). The variance side of the comparison.
 */
export function iterationsFromLast(c: ErrorCurveResult, db: number): number | null {
  const last = c.points[c.points.length - 1];
  if (!last || last.iterations < 8 || !Number.isFinite(last.psnr)) return null;
  return last.iterations * 10 ** ((db - last.psnr) / 10);
}

/**
 * The same extrapolation with the curve's own error estimate at its last point (from its even
 * and odd half-accumulations) in place of the error against the reference: independent of the
 * reference's noise and of the curve's realization against it.
 */
export function iterationsFromHalves(c: ErrorCurveResult, db: number): number | null {
  const last = c.points[c.points.length - 1];
  if (!last || last.iterations < 8 || !last.estimatedRmse || !(last.rmse > 0)) return null;
  const psnr = last.psnr + 20 * Math.log10(last.rmse / last.estimatedRmse);
  return last.iterations * 10 ** ((db - psnr) / 10);
}

/**
 * The fixed variant whose curve is auto's, point for point: auto compiled to that estimator
 * and drew the same random numbers, so both are one computation, and their cost samples are
 * pooled (their difference measures only the timing noise of the run).
 */
function twinOf(auto: ErrorCurveResult, fixed: readonly ErrorCurveResult[]): ErrorCurveResult | undefined {
  return fixed.find(
    (c) => c.points.length === auto.points.length && c.points.every((p, i) => p.psnr === auto.points[i].psnr),
  );
}

/** One configuration on one scene over every run: its curves (one per run) and its pooled cost samples. */
interface Variant {
  name: string;
  curves: ErrorCurveResult[];
  /** Wall ms per iteration, one per batch. */
  costs: number[];
  /** The GPU process's CPU ms per iteration, one per batch (10 ms ticks: only their mean is meaningful). */
  cpu: number[];
}

/** Mean over the runs of a per-curve figure (null if any run lacks it). */
function meanOver(v: Variant, figure: (c: ErrorCurveResult) => number | null): number | null {
  const xs = v.curves.map(figure);
  return xs.some((x) => x === null) ? null : (xs as number[]).reduce((a, b) => a + b, 0) / xs.length;
}

const FIGURES = {
  crossing: iterationsTo,
  'last point': iterationsFromLast,
  halves: iterationsFromHalves,
} as const;

/** `runs`: the errorVsTime arrays of one or more runs (seeds) of the estimator study. */
export function estimatorTable(runs: readonly (readonly ErrorCurveResult[])[]): string {
  const lines: string[] = [];
  const f = (x: number | null | undefined, d = 2) => (x == null || !Number.isFinite(x) ? '—' : x.toFixed(d));
  const name = (c: ErrorCurveResult) => (c.label === AUTO ? 'auto' : c.label.replace('mcrt fixed: ', ''));
  const scenes = [...new Set(runs.flat().map((c) => c.scene))];
  for (const scene of scenes) {
    const variants = new Map<string, Variant>();
    const notes: string[] = [];
    for (const run of runs) {
      const rows = run.filter((c) => c.scene === scene);
      const auto = rows.find((c) => c.label === AUTO);
      const twin =
        auto &&
        twinOf(
          auto,
          rows.filter((c) => c !== auto),
        );
      for (const c of rows) {
        const v = variants.get(c.label) ?? { name: name(c), curves: [], costs: [], cpu: [] };
        variants.set(c.label, v);
        v.curves.push(c);
        // Auto and its twin are one computation: both get the pooled samples.
        const pooled =
          twin && (c === auto || c === twin)
            ? [...(auto.interleavedMsPerIteration ?? []), ...(twin.interleavedMsPerIteration ?? [])]
            : (c.interleavedMsPerIteration ?? []);
        v.costs.push(...pooled);
        const pooledCpu =
          twin && (c === auto || c === twin)
            ? [
                ...(auto.interleavedGpuProcessCpuMsPerIteration ?? []),
                ...(twin.interleavedGpuProcessCpuMsPerIteration ?? []),
              ]
            : (c.interleavedGpuProcessCpuMsPerIteration ?? []);
        v.cpu.push(...pooledCpu);
      }
      if (auto && twin?.interleavedMsPerIteration && auto.interleavedMsPerIteration)
        notes.push(
          `auto = ${name(twin)} (the same computation): cost medians ${f(median(auto.interleavedMsPerIteration), 1)} and ${f(median(twin.interleavedMsPerIteration), 1)} ms`,
        );
    }
    const all = [...variants.values()];
    const auto = variants.get(AUTO);
    const fixed = all.filter((v) => v !== auto);
    const ch = auto?.curves[0].rendererStats;
    lines.push(
      `**${scene}** — ${runs.filter((r) => r.some((c) => c.scene === scene)).length} run(s); auto chose ${ch?.tracking ? `${ch.tracking}, ${ch.environmentSampling}, ${ch.majorantGrid} (${ch.trackingReason}; ${ch.environmentSamplingReason}; ${ch.majorantGridReason})` : '?'}`,
      '',
      ...(notes.length ? [notes.join('; '), ''] : []),
      '| estimator | ms / it, median (quartiles; samples) | GPU process CPU ms / it, mean | iterations to 30 / 35 dB: crossing | from the last point (n there) | from the halves’ estimate |',
      '|---|---|---|---|---|---|',
    );
    const ms = (v: Variant) => (v.costs.length ? median(v.costs) : null);
    const cpuMs = (v: Variant) => (v.cpu.length ? v.cpu.reduce((a, b) => a + b, 0) / v.cpu.length : null);
    for (const v of all) {
      const sorted = [...v.costs].sort((a, b) => a - b);
      const q = (p: number) => sorted[Math.floor(p * (sorted.length - 1))];
      const lasts = v.curves.map((c) => c.points[c.points.length - 1]?.iterations ?? '—').join(', ');
      const it = (fig: (c: ErrorCurveResult, db: number) => number | null) =>
        TARGETS.map((db) =>
          f(
            meanOver(v, (c) => fig(c, db)),
            1,
          ),
        ).join(' / ');
      lines.push(
        `| ${v.name} | ${f(ms(v), 1)} (${f(q(0.25), 1)}–${f(q(0.75), 1)}; ${v.costs.length}) | ${f(cpuMs(v), 1)} | ${it(iterationsTo)} | ${it(iterationsFromLast)} (${lasts}) | ${it(iterationsFromHalves)} |`,
      );
    }
    lines.push('');
    const COSTS = { 'wall median': ms, 'GPU-process CPU mean': cpuMs };
    for (const [basis, cost] of Object.entries(COSTS))
      for (const [how, fig] of Object.entries(FIGURES))
        for (const db of TARGETS) {
          const time = (v: Variant) => {
            const n = meanOver(v, (c) => fig(c, db));
            const m = cost(v);
            return n === null || m === null ? null : n * m;
          };
          const reached = fixed.filter((v) => time(v) !== null);
          const a = auto ? time(auto) : null;
          if (a === null || !reached.length) continue;
          const best = reached.reduce((x, y) => (time(x)! <= time(y)! ? x : y));
          const others = reached
            .filter((v) => v !== best)
            .map((v) => `${v.name} ${f(time(v)! / time(best)!)}`)
            .join(', ');
          lines.push(
            `- ${db} dB, ${basis} cost, iterations by ${how}: best fixed ${best.name} (${f(time(best)! / 1000)} s); auto / best = ${f(a / time(best)!)}; others / best: ${others}`,
          );
        }
    lines.push('');
  }
  return lines.join('\n');
}

// Run as a script (not when imported, e.g. by its test).
if (process.argv[1] && import.meta.url === pathToFileURL(process.argv[1]).href) {
  const { files } = parseCliOrExit({
    name: 'node benchmarks/dist/estimator-table.js',
    synopsis: 'RESULTS.json [RESULTS.json …]',
    summary: 'The estimator study (pnpm bench --preset estimators) as a markdown table per scene; runs combined.',
    positionals: [
      {
        key: 'files',
        name: 'RESULTS.json',
        type: 'string',
        variadic: true,
        required: true,
        description: "runs' results.json (one seed each)",
      },
    ],
  });
  const runs = files.map(
    (p) => (JSON.parse(readFileSync(p, 'utf8')) as { errorVsTime?: ErrorCurveResult[] }).errorVsTime ?? [],
  );
  console.log(estimatorTable(runs));
}
