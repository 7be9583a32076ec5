/**
 * `node benchmarks/dist/estimator-table.js benchmarks/results/<run>/results.json`: the
 * estimator study (preset 'estimators') as a markdown table per scene: time to 30 and 35 dB
 * of MCRT's default `estimator: 'auto'` and of every fixed estimator, the best fixed one, and
 * auto's time over the best (the issue-14 goal: ≤ 1.10).
 */
import { readFileSync } from 'node:fs';
import type { ErrorCurveResult } from './suites/error-vs-time.js';

const AUTO = 'mcrt multiple';

export function estimatorTable(curves: readonly ErrorCurveResult[]): string {
  const lines: string[] = [];
  const scenes = [...new Set(curves.map((c) => c.scene))];
  const s = (ms: number | null | undefined) => (ms == null ? '—' : (ms / 1000).toFixed(2));
  for (const scene of scenes) {
    const rows = curves.filter((c) => c.scene === scene);
    const auto = rows.find((c) => c.label === AUTO);
    const fixed = rows.filter((c) => c.label !== AUTO);
    const choice = auto?.rendererStats;
    lines.push(
      `**${scene}** — auto chose ${choice ? `${choice.tracking}, ${choice.environmentSampling}, ${choice.majorantGrid}` : '?'}` +
        (choice
          ? ` (${choice.trackingReason}; ${choice.environmentSamplingReason}; ${choice.majorantGridReason})`
          : ''),
      '',
      '| estimator | 30 dB (s) | 35 dB (s) |',
      '|---|---|---|',
    );
    for (const c of [...(auto ? [auto] : []), ...fixed])
      lines.push(
        `| ${c.label === AUTO ? 'auto' : c.label.replace('mcrt fixed: ', '')} | ${s(c.timeToDb[30])} | ${s(c.timeToDb[35])} |`,
      );
    for (const db of [30, 35]) {
      const reached = fixed.filter((c) => c.timeToDb[db] != null);
      if (!auto || auto.timeToDb[db] == null || !reached.length) continue;
      const best = reached.reduce((a, b) => (a.timeToDb[db]! <= b.timeToDb[db]! ? a : b));
      lines.push(
        '',
        `${db} dB: best fixed = ${best.label.replace('mcrt fixed: ', '')} (${s(best.timeToDb[db])} s); auto / best = ${(auto.timeToDb[db]! / best.timeToDb[db]!).toFixed(2)}`,
      );
    }
    lines.push('');
  }
  return lines.join('\n');
}

if (process.argv[2]) {
  const results = JSON.parse(readFileSync(process.argv[2], 'utf8')) as { errorVsTime?: ErrorCurveResult[] };
  console.log(estimatorTable(results.errorVsTime ?? []));
}
