import os from 'node:os';
import { RENDERERS, scenes } from '../configs.js';
import { timeToPsnr, type CurvePoint } from '../metrics.js';
import { TARGETS_DB, referenceKey } from './error-vs-time.js';
import { bench, type SuiteContext } from './types.js';

export interface DenoiseRow {
  scene: string;
  label: string;
  backend: string;
  size: number;
  referenceIterations: number;
  /** PSNR (HDR, against the converged reference) against wall-clock ms, the image rendered at every checkpoint; ms = mean of two runs. */
  plain: CurvePoint[];
  denoised: CurvePoint[];
  timeToDb: { plain: Record<string, number | null>; denoised: Record<string, number | null> };
  /**
   * The reference's samples through the denoiser against the plain reference: an upper bound on
   * what the filter leaves at convergence (it includes the noise removed; noiseRmse is the plain
   * image's own relative noise).
   */
  bias: { iterations: number; psnr: number; relativeRmse: number; noiseRmse: number | null };
  /** os.loadavg() before and after this row (1, 5, 15 min). */
  loadAverage: { before: number[]; after: number[] };
}

/** Checkpoints 1, 2, 3, 4, 6, 8, 12, 16, … up to `max` (×1.5 after 4). */
export function denoiseCheckpoints(max: number): number[] {
  const out: number[] = [];
  for (let n = 1; n <= max; n = n < 4 ? n + 1 : Math.ceil(n * 1.5)) out.push(n);
  return out;
}

/**
 * The denoise step's worth (docs/benchmarks.md, "Denoiser"): PSNR against wall-clock time of MCRT (multiple
 * scattering) with and without the denoiser on every scene (cloud, head, the fetched chest CT),
 * measured interleaved A/B/B/A so drift in the machine's speed affects both, and the bias the
 * denoiser leaves at the reference's sample count.
 */
export async function denoise(s: SuiteContext): Promise<DenoiseRow[]> {
  const rows: DenoiseRow[] = [];
  const size = s.preset.errorSize;
  const config = RENDERERS.find((r) => r.label === 'mcrt multiple')!;
  const refIterations = s.preset.referenceIterations.mcrt;
  const checkpoints = denoiseCheckpoints(s.preset.curveIterations);
  for (const [sceneName, spec] of Object.entries({ ...scenes(s.preset.cloudSize), ...s.fetchedScenes })) {
    if (s.preset.errorScenes && !s.preset.errorScenes.includes(sceneName)) continue;
    for (const backend of s.backends) {
      const before = os.loadavg();
      s.log(`denoise: ${sceneName} ${config.label} ${backend} at ${size}² (reference ${refIterations} it)`);
      const refKey = referenceKey(sceneName, config.label, size);
      await bench(s.page, 'reference', refKey, { ...config, backend: s.backends[0] }, spec, size, size, refIterations);
      const runs: Record<'plain' | 'denoised', CurvePoint[][]> = { plain: [], denoised: [] };
      for (const kind of ['plain', 'denoised', 'denoised', 'plain'] as const) {
        runs[kind].push(
          await bench<CurvePoint[]>(
            s.page,
            'denoiseCurve',
            { ...config, backend },
            spec,
            size,
            size,
            refKey,
            checkpoints,
            kind === 'denoised',
          ),
        );
      }
      // Same seed in both runs of a kind, so the errors agree; the times are averaged.
      const mean = (curves: CurvePoint[][]) => curves[0].map((p, i) => ({ ...p, ms: (p.ms + curves[1][i].ms) / 2 }));
      const plain = mean(runs.plain),
        denoised = mean(runs.denoised);
      const bias = await bench<DenoiseRow['bias']>(
        s.page,
        'denoiseBias',
        refKey,
        { ...config, backend },
        spec,
        size,
        size,
      );
      rows.push({
        scene: sceneName,
        label: config.label,
        backend,
        size,
        referenceIterations: refIterations,
        plain,
        denoised,
        timeToDb: {
          plain: Object.fromEntries(TARGETS_DB.map((d) => [d, timeToPsnr(plain, d)])),
          denoised: Object.fromEntries(TARGETS_DB.map((d) => [d, timeToPsnr(denoised, d)])),
        },
        bias,
        loadAverage: { before, after: os.loadavg() },
      });
    }
  }
  return rows;
}
