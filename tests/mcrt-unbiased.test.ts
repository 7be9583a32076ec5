import { describe, expect, it } from 'vitest';
import { zSummary } from './helpers/mcrt-stats.js';
import { usePage } from './helpers/session.js';

/**
 * Estimators that must agree in expectation: delta, ratio and residual ratio tracking for
 * shadow rays, with the majorant grid and with one global majorant; and the three ways of
 * gathering an HDR environment (phase sampling, light sampling, MIS with the power or the
 * balance heuristic). Multiple scattering in a heterogeneous medium with coloured albedo,
 * a directional light and an environment. Each configuration's per-pixel mean is compared
 * with the reference configuration's: z = Δmean / √(se₁² + se₂²), se measured from the frames.
 * Pass: per channel |Σz|/√n < 4 (no aggregate bias; 9 comparisons × 3 channels, so 4σ keeps
 * false alarms below 0.2 %) and max |z| < 5.5 over ~370 channel values per comparison.
 */
const page = usePage({ mcrt: true });

const W = 16,
  H = 16,
  N = 64;

type Run = { mean: number[]; se: number[]; nonFinite: boolean };

function compareRuns(a: Run, b: Run) {
  const z: number[] = [];
  let identical = 0;
  for (let i = 0; i < a.mean.length; i += 4) {
    // Pixels that see only the environment are exact in both runs (no noise, z undefined).
    if (a.se[i] === 0 && b.se[i] === 0 && a.mean[i] === b.mean[i]) {
      identical++;
      continue;
    }
    for (let c = 0; c < 3; c++) z.push((a.mean[i + c] - b.mean[i + c]) / Math.hypot(a.se[i + c], b.se[i + c]));
  }
  return { ...zSummary(z, 3), identical };
}

async function render(
  params: Record<string, unknown>,
  sceneKind: 'tracking' | 'environment',
  seed: number,
): Promise<Run> {
  return page.run(
    async ({ core, mt, t }, W, H, N, params, sceneKind, seed) => {
      const environment =
        sceneKind === 'environment'
          ? {
              type: 'latlong',
              width: 8,
              height: 4,
              data: new Float32Array(8 * 4 * 3).map(
                (_, i) => [0.05, 0.3, 1, 5][(i * 5 + (i >> 2)) % 4] * [1, 0.8, 0.6][i % 3],
              ),
            }
          : { type: 'constant', radiance: [0.4, 0.5, 0.7] };
      const scene = {
        volume: core.createProceduralVolume('blob', 20),
        transferFunction: t.tf1d(
          [0.05, [0.9, 0.9, 0.9], 0],
          [0.4, [0.95, 0.7, 0.4], 0.7],
          [0.6, [0.7, 0.9, 0.95], 0.15],
          [1, [0.99, 0.99, 0.99], 1],
        ),
        camera: { position: [0.3, 0.9, 1.8], target: [0, 0, 0], up: [0, 1, 0], fovy: 0.6 },
        lights:
          sceneKind === 'tracking'
            ? [{ type: 'directional', direction: [-0.4, 1, 0.3], irradiance: [2, 1.8, 1.5] }]
            : [],
        environment,
        densityScale: 25,
        seed,
      };
      return mt.run({
        backend: 'webgl2',
        width: W,
        height: H,
        iterations: N,
        params: { anisotropy: 0.5, majorantCellSize: 4, ...params },
        scene,
      });
    },
    W,
    H,
    N,
    params,
    sceneKind,
    seed,
  );
}

describe('MCRT estimators converge to the same image (webgl2)', () => {
  it('delta, ratio and residual ratio tracking, with and without the majorant grid', async () => {
    const ref = await render({ tracking: 'residual', majorantGrid: true }, 'tracking', 1);
    expect(ref.nonFinite).toBe(false);
    const lines: string[] = [];
    let seed = 2; // independent runs: a shared seed would correlate them and hide a bias
    for (const tracking of ['delta', 'ratio', 'residual']) {
      for (const majorantGrid of [true, false]) {
        if (tracking === 'residual' && majorantGrid) continue;
        const r = await render({ tracking, majorantGrid }, 'tracking', seed++);
        expect(r.nonFinite).toBe(false);
        const s = compareRuns(r, ref);
        lines.push(`${tracking} grid=${majorantGrid}: ${JSON.stringify(s)}`);
        expect(Math.abs(s.meanScaled), lines.join('\n')).toBeLessThan(4);
        expect(s.maxAbs, lines.join('\n')).toBeLessThan(5.5);
      }
    }
    // A bright, non-trivial image (the comparisons have something to compare).
    expect(Math.max(...ref.mean)).toBeGreaterThan(0.3);
  });

  it('phase sampling, light sampling and MIS (power, balance) of an HDR environment', async () => {
    const ref = await render({ environmentSampling: 'mis', misHeuristic: 'power' }, 'environment', 11);
    expect(ref.nonFinite).toBe(false);
    const lines: string[] = [];
    let seed = 12;
    for (const [environmentSampling, misHeuristic] of [
      ['mis', 'balance'],
      ['light', 'power'],
      ['phase', 'power'],
    ]) {
      const r = await render({ environmentSampling, misHeuristic }, 'environment', seed++);
      expect(r.nonFinite).toBe(false);
      const s = compareRuns(r, ref);
      lines.push(`${environmentSampling}/${misHeuristic}: ${JSON.stringify(s)}`);
      expect(Math.abs(s.meanScaled), lines.join('\n')).toBeLessThan(4);
      expect(s.maxAbs, lines.join('\n')).toBeLessThan(5.5);
    }
  });
});
