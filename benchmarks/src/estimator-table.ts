/**
 * `node benchmarks/dist/estimator-table.js benchmarks/results/<run>/results.json`: the
 * estimator study (preset 'estimators') as a markdown table per scene. For MCRT's default
 * `estimator: 'auto'` and every fixed estimator: iterations to 30 and 35 dB (from the curve:
 * the variance side, independent of the machine's load), ms per iteration measured
 * round-robin across the configurations (the cost side), and their product, the time to
 * 30 / 35 dB; then the best fixed estimator and auto's time over it (issue 14's goal ≤ 1.10).
 */
import { readFileSync } from 'node:fs';
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

/** Iterations to `db` × the interleaved ms per iteration (the curve's own when there is none). */
export function timeTo(c: ErrorCurveResult, db: number): number | null {
  const n = iterationsTo(c, db);
  if (n === null) return null;
  const last = c.points[c.points.length - 1];
  const ms = c.interleavedMsPerIteration?.length ? median(c.interleavedMsPerIteration) : last.ms / last.iterations;
  return n * ms;
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

export function estimatorTable(curves: readonly ErrorCurveResult[]): string {
  const lines: string[] = [];
  const f = (x: number | null | undefined, d = 2) => (x == null ? '—' : x.toFixed(d));
  const name = (c: ErrorCurveResult) => (c.label === AUTO ? 'auto' : c.label.replace('mcrt fixed: ', ''));
  for (const scene of [...new Set(curves.map((c) => c.scene))]) {
    const rows = curves.filter((c) => c.scene === scene);
    const auto = rows.find((c) => c.label === AUTO);
    const fixed = rows.filter((c) => c.label !== AUTO);
    const twin = auto && twinOf(auto, fixed);
    let note = '';
    if (auto && twin && auto.interleavedMsPerIteration && twin.interleavedMsPerIteration) {
      const pooled = [...auto.interleavedMsPerIteration, ...twin.interleavedMsPerIteration];
      note = `(auto = ${name(twin)}, the same computation: cost medians ${f(median(auto.interleavedMsPerIteration), 1)} and ${f(median(twin.interleavedMsPerIteration), 1)} ms pooled to ${f(median(pooled), 1)})`;
      auto.interleavedMsPerIteration = twin.interleavedMsPerIteration = pooled;
    }
    const ch = auto?.rendererStats;
    lines.push(
      `**${scene}** — auto chose ${ch?.tracking ? `${ch.tracking}, ${ch.environmentSampling}, ${ch.majorantGrid} (${ch.trackingReason}; ${ch.environmentSamplingReason}; ${ch.majorantGridReason})` : '?'}`,
      '',
      ...(note ? [note, ''] : []),
      '| estimator | ms / it | iterations to 30 / 35 dB | time to 30 / 35 dB (s) |',
      '|---|---|---|---|',
    );
    for (const c of [...(auto ? [auto] : []), ...fixed]) {
      const ms = c.interleavedMsPerIteration?.length ? median(c.interleavedMsPerIteration) : null;
      lines.push(
        `| ${name(c)} | ${f(ms, 1)} | ${TARGETS.map((db) => f(iterationsTo(c, db), 1)).join(' / ')} | ${TARGETS.map((db) => f((timeTo(c, db) ?? NaN) / 1000)).join(' / ')} |`,
      );
    }
    lines.push('');
    for (const db of TARGETS) {
      const reached = fixed.filter((c) => timeTo(c, db) !== null);
      const a = auto ? timeTo(auto, db) : null;
      if (a === null || !reached.length) continue;
      const best = reached.reduce((x, y) => (timeTo(x, db)! <= timeTo(y, db)! ? x : y));
      lines.push(`- ${db} dB: best fixed ${name(best)}; auto / best = ${(a / timeTo(best, db)!).toFixed(2)}`);
    }
    lines.push('');
  }
  return lines.join('\n');
}

if (process.argv[2]) {
  const results = JSON.parse(readFileSync(process.argv[2], 'utf8')) as { errorVsTime?: ErrorCurveResult[] };
  console.log(estimatorTable(results.errorVsTime ?? []));
}
