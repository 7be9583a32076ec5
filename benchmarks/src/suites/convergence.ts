import { scenes } from '../configs.js';
import type { CurvePoint } from '../metrics.js';
import { errorCurve, referenceKey, renderReference } from './error-vs-time.js';
import type { SuiteContext } from './types.js';

export interface ConvergenceResult {
  label: string;
  backend: string;
  size: number;
  points: CurvePoint[];
}

/** The paper's Figure 5: PSNR against iteration count at several resolutions (first backend). */
export async function convergence(s: SuiteContext): Promise<ConvergenceResult[]> {
  const out: ConvergenceResult[] = [];
  const spec = scenes(s.preset.cloudSize).cloud;
  const backend = s.backends[0];
  for (const size of s.preset.convergenceSizes) {
    for (const config of s.renderers) {
      const refKey = referenceKey('cloud', config.label, size); // shared with error-vs-time where the sizes match
      s.log(`convergence: ${config.label} ${backend} ${size}²`);
      await renderReference(s, refKey, config, backend, spec, size, s.preset.referenceIterations[config.renderer]);
      const points = await errorCurve(s, config, backend, spec, size, refKey, false);
      out.push({ label: config.label, backend, size, points });
    }
  }
  return out;
}
