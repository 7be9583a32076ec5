import { scenes, type SceneSpec } from '../configs.js';
import { median, spread } from '../metrics.js';
import { bench, type SuiteContext } from './types.js';

export interface SpecializationRow {
  scene: string;
  scattering: 'single' | 'multiple';
  backend: string;
  size: number;
  specializedMs: number;
  genericMs: number;
  /** generic / specialised median ms per iteration: what specialisation saves, as a ratio measured in one run. */
  ratio: number;
  specializedSpread: { min: number; max: number };
  genericSpread: { min: number; max: number };
  /** First iteration after setScene (kernel compilation + one iteration), ms. */
  specializedFirstMs: number;
  genericFirstMs: number;
}

/**
 * What kernel specialisation saves (docs/benchmarks.md, "MCRT kernel specialization"): ms per iteration of the MCRT kernel compiled
 * for the scene against the generic kernel (`specialize: false`: environment map, light
 * loop, scattering order and majorant grid as runtime data) on the same scene. The two are
 * measured alternately, two rounds each, so drift in the machine's speed affects both.
 */
export async function specialization(s: SuiteContext): Promise<SpecializationRow[]> {
  const rows: SpecializationRow[] = [];
  const size = s.preset.specializationSize;
  const all = scenes(s.preset.cloudSize);
  const cases: [string, SceneSpec][] = [
    ['cloud (constant sky, one light)', all.cloud],
    ['cloud (constant sky only)', { ...all.cloud, lights: [] }],
    ['head (constant sky, one light)', all.head],
  ];
  for (const backend of s.backends) {
    for (const [sceneName, spec] of cases) {
      for (const scattering of ['single', 'multiple'] as const) {
        s.log(`specialization: ${sceneName} ${scattering} ${backend} at ${size}²`);
        const samples = { specialized: [] as number[], generic: [] as number[] };
        const first = { specialized: [] as number[], generic: [] as number[] };
        for (let round = 0; round < 2; round++) {
          const order = round === 0 ? (['specialized', 'generic'] as const) : (['generic', 'specialized'] as const);
          for (const kind of order) {
            const config = {
              label: `mcrt ${scattering} ${kind}`,
              renderer: 'mcrt',
              backend,
              params: { scattering, specialize: kind === 'specialized' },
            };
            const r = await bench<{ samples: number[]; firstMs: number }>(
              s.page,
              'frameTime',
              config,
              spec,
              size,
              size,
              s.preset.frameIterations,
              s.preset.frameRepeats,
            );
            samples[kind].push(...r.samples);
            first[kind].push(r.firstMs);
          }
        }
        const sm = median(samples.specialized),
          gm = median(samples.generic);
        rows.push({
          scene: sceneName,
          scattering,
          backend,
          size,
          specializedMs: sm,
          genericMs: gm,
          ratio: gm / sm,
          specializedSpread: spread(samples.specialized),
          genericSpread: spread(samples.generic),
          specializedFirstMs: median(first.specialized),
          genericFirstMs: median(first.generic),
        });
      }
    }
  }
  return rows;
}
