import { scenes } from '../configs.js';
import { median } from '../metrics.js';
import type { SuiteContext } from './types.js';
import { frameTimes } from './frame-time.js';

export interface ScalingRow {
  axis: 'volume-size' | 'empty-fraction';
  label: string;
  backend: string;
  x: number;
  nsPerPath: number;
}

/**
 * Cost per path (ns per pixel per iteration) against volume size, and against the
 * fraction of empty space (a sphere whose radius leaves that fraction of the box empty).
 */
export async function scaling(s: SuiteContext): Promise<ScalingRow[]> {
  const rows: ScalingRow[] = [];
  const size = s.preset.scalingFramebuffer ?? 128;
  const backend = s.backends[0];
  const per = async (axis: ScalingRow['axis'], x: number, spec: ReturnType<typeof scenes>['cloud']) => {
    for (const config of s.renderers) {
      s.log(`scaling: ${axis} ${x} ${config.label}`);
      const r = await frameTimes(s, config, backend, spec, size);
      rows.push({ axis, label: config.label, backend, x, nsPerPath: (median(r.samples) * 1e6) / (size * size) });
    }
  };
  for (const v of s.preset.scalingVolumeSizes) await per('volume-size', v, scenes(v).cloud);
  for (const f of s.preset.scalingEmptyFractions) {
    // A sphere of radius r fills 4/3 π r³ of the unit box: empty fraction f ⇒ r = (3(1−f)/4π)^(1/3), capped at the box.
    const radius = Math.min(0.5, Math.cbrt((3 * (1 - f)) / (4 * Math.PI)));
    const base = scenes(64).cloud;
    await per('empty-fraction', f, {
      ...base,
      volume: { kind: 'ball', size: 64, radius },
      densityScale: 20,
      transferFunction: {
        dimensions: '1d',
        points: [
          { value: 0, color: [1, 1, 1], opacity: 0 },
          { value: 1, color: [1, 1, 1], opacity: 1 },
        ],
      },
    });
  }
  return rows;
}
