import { scenes } from '../configs.js';
import { timeToPsnr, type CurvePoint } from '../metrics.js';
import { bench, type SuiteContext } from './types.js';

export const TARGETS_DB = [25, 30, 35, 40];

export interface ErrorCurveResult {
  scene: string;
  label: string;
  backend: string;
  size: number;
  referenceIterations: number;
  points: CurvePoint[];
  timeToDb: Record<string, number | null>;
  timeToDbLdr: Record<string, number | null>;
}

/**
 * Error vs wall-clock time: each configuration renders progressively against a converged
 * reference made by the same renderer with an independent seed (so the curve measures
 * noise, not a bias between renderers).
 */
export async function errorVsTime(s: SuiteContext): Promise<ErrorCurveResult[]> {
  const out: ErrorCurveResult[] = [];
  const size = s.preset.errorSize;
  const all = [...s.renderers, ...s.mcrtVariants];
  for (const [sceneName, spec] of Object.entries(scenes(s.preset.cloudSize))) {
    for (const backend of s.backends) {
      for (const config of all) {
        if (sceneName === 'head' && s.mcrtVariants.includes(config)) continue; // variants on the procedural scene only
        const refIterations = s.preset.referenceIterations[config.renderer];
        const refKey = `${sceneName}|${config.label}|${backend}|${size}`;
        s.log(`error-vs-time: ${sceneName} ${config.label} ${backend} (reference ${refIterations} it)`);
        await bench(s.page, 'reference', refKey, { ...config, backend }, spec, size, size, refIterations);
        const points = await bench<CurvePoint[]>(s.page, 'errorCurve', { ...config, backend }, spec, size, size, refKey, s.preset.curveIterations, s.preset.curveBudgetMs, !!config.halves);
        out.push({
          scene: sceneName, label: config.label, backend, size, referenceIterations: refIterations, points,
          timeToDb: Object.fromEntries(TARGETS_DB.map((d) => [d, timeToPsnr(points, d)])),
          timeToDbLdr: Object.fromEntries(TARGETS_DB.map((d) => [d, timeToPsnr(points, d, 'psnrLdr')])),
        });
      }
    }
  }
  return out;
}
