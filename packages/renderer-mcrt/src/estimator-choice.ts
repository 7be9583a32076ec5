/**
 * `estimator: 'auto'`: the estimator choices MCRT makes per scene, from quantities the scene
 * already provides (the environment's radiance, the volume and the transfer function). Every
 * choice is unbiased; they differ only in cost and variance. The thresholds come from the
 * time-to-30/35 dB measurements in docs/benchmarks.md ("MCRT: estimator 'auto'"; the figures
 * behind each rule: docs/benchmarks.md#fig-estimator-choice).
 *
 *  - Environment: phase sampling alone for a constant environment (or a map whose texels are
 *    all within ENV_PEAK_RATIO_FOR_MIS of its mean: a constant one), MIS for any other map.
 *    Under a constant sky the phase function samples the light as well as uniform light
 *    sampling would, and light sampling adds a shadow ray per event; a map, even a smooth
 *    gradient sky, needs several times the iterations without light sampling.
 *    Directional lights are sampled by next-event estimation either way. Single scattering
 *    under a map with a near-isotropic phase function (peak ≤ PHASE_PEAK_FOR_LIGHT_ONLY × 1/4π,
 *    |g| ≤ 0.2) takes light sampling alone: there its weight Le·T·p/pdf stays within that peak
 *    of the mean, phase sampling cannot do much better, and two light samples beat one light +
 *    one phase sample at the same cost.
 *  - Light samples (single scattering with light sampling alone): SINGLE_SCATTERING_LIGHT_SAMPLES
 *    in-scattering estimates per scattering event: there the in-scattering estimate carries
 *    most of the variance and a light sample costs a fraction of the rest of an iteration.
 *    With phase or MIS sampling one (see chooseLightSamples).
 *  - Majorant grid: walked unless it lowers the bound too little (global majorant below
 *    GRID_GAIN_FOR_WALK times the mean cell majorant), where the DDA's cell steps cost more
 *    than the null collisions they save.
 *  - Shadow rays: residual ratio tracking for single scattering (every path ends in a shadow
 *    ray, and it needed fewer iterations than delta tracking there). For multiple scattering:
 *    residual where the cells' minorants are at least RESIDUAL_MINORANT_FRACTION of their
 *    majorants (Novák et al. 2014: the control then carries most of the optical depth in
 *    closed form; a homogeneous medium needs no tentative collision at all); else delta tracking where the environment is phase-sampled (shadow
 *    rays only toward directional lights) and the medium is dense (mean cell minorant at least
 *    DELTA_MINORANT_DEPTH per box length: most shadow rays are blocked, and delta tracking stops
 *    them at their first collision); else ratio tracking, which needs fewer iterations than
 *    delta tracking for some extra cost per iteration. Below that minorant fraction residual
 *    tracking needs no fewer iterations than ratio tracking and costs more: its per-step
 *    weights fall more slowly, so Russian roulette ends its walks later.
 *
 * The grid statistics are computed on the CPU from a strided subsample of the volume (at most
 * about 2²¹ voxels, so a large volume costs milliseconds): they steer a choice between unbiased
 * estimators, so approximate ranges suffice; the kernel's own grid is still the GPU-built one.
 */
import {
  scalarSceneOf,
  type MajorantGrid,
  normalizationRange,
  buildMajorantGrid,
  computeCellValueRanges,
  gridCells,
  rasterizeTransferFunction,
  TF_RESOLUTION,
  type Environment,
  type Scene,
  type Volume,
} from '@vpt/core';
// The CPU grid of what the kernel draws: the channels' sum, plus the labels' (label volumes' subpath).
import { sceneMajorantGrid } from '@vpt/core/labels';
import { extinctionCap } from './extinction-cap.js';
import type { EnvironmentSampling, TrackingMode } from './params.js';

export const ENV_PEAK_RATIO_FOR_MIS = 1.05;
/**
 * A lat-long map whose peak is more than this many times its mean (a small sun) is not lit
 * by phase sampling alone under `estimator: 'auto'`, even when `environmentSampling:
 * 'phase'` is set: it leaves fireflies after hundreds of iterations (means 0.89 and 1.91
 * for two seeds against 1.65 with MIS at 512), so MIS is used instead and the reason says
 * so. MIS has the same expectation, so only the noise changes. `estimator: 'fixed'` keeps 'phase'.
 */
export const ENV_PEAK_RATIO_PHASE_TO_MIS = 8;
export const GRID_GAIN_FOR_WALK = 3;
export const RESIDUAL_MINORANT_FRACTION = 0.5;
export const SINGLE_SCATTERING_LIGHT_SAMPLES = 3;
export const PHASE_PEAK_FOR_LIGHT_ONLY = 2;
export const DELTA_MINORANT_DEPTH = 1;
const MAX_SAMPLED_VOXELS = 1 << 21;

/** What the choice rules read from the volume and TF (all extinctions in the box's units). */
export interface GridStatistics {
  /** Largest cell majorant: the bound of a walk without the grid. */
  globalMajorant: number;
  /** Smallest cell minorant: the control of residual tracking without the grid. */
  globalMinorant: number;
  /** Mean cell majorant (cells of equal volume): the bound a ray meets on average with the grid. */
  meanMajorant: number;
  /** Σ minorant / Σ majorant over the cells: how much of the bound residual tracking takes in closed form. */
  minorantFraction: number;
}

const peakMemo = new WeakMap<Float32Array, number>();

/** The environment's peak luminance over its mean over the sphere (1 for a constant sky, 0 for a black one). */
export function environmentPeakRatio(env: Environment): number {
  if (env.type !== 'latlong') return env.radiance.some((x) => x > 0) ? 1 : 0;
  const { width: W, height: H, data } = env;
  const memo = peakMemo.get(data);
  if (memo !== undefined) return memo;
  let peak = 0,
    weighted = 0,
    weights = 0;
  for (let j = 0; j < H; j++) {
    const sinTheta = Math.sin((Math.PI * (j + 0.5)) / H);
    for (let i = 0; i < W; i++) {
      const k = 3 * (j * W + i);
      const lum = 0.2126 * data[k] + 0.7152 * data[k + 1] + 0.0722 * data[k + 2];
      if (lum > peak) peak = lum;
      weighted += lum * sinTheta;
      weights += sinTheta;
    }
  }
  const mean = weighted / Math.max(weights, 1e-30);
  const ratio = mean > 0 ? peak / mean : 0;
  peakMemo.set(data, ratio);
  return ratio;
}

/** The Henyey–Greenstein phase function's peak over the isotropic 1/4π: (1 + |g|) / (1 − |g|)². */
export function phasePeakRatio(g: number): number {
  const a = Math.abs(g);
  return (1 + a) / ((1 - a) * (1 - a));
}

/** Grid statistics from every `stride`-th voxel per axis (stride ≥ 1 so that at most ~2²¹ voxels are read). */
export function gridStatistics(given: Scene, cellSize: number): GridStatistics {
  const scene = scalarSceneOf(given) ?? given;
  if (scene.channels || scene.labels) return statisticsOf(sceneMajorantGrid(scene, cellSize), extinctionCap(scene));
  const v = scene.volume;
  const [nx, ny, nz] = v.dims;
  const stride = Math.max(1, Math.ceil(Math.cbrt((nx * ny * nz) / MAX_SAMPLED_VOXELS)));
  const sub: [number, number, number] = [Math.ceil(nx / stride), Math.ceil(ny / stride), Math.ceil(nz / stride)];
  const [lo, hi] = normalizationRange(v);
  const scale = 1 / (hi - lo);
  const values = new Float32Array(sub[0] * sub[1] * sub[2]);
  let o = 0;
  for (let z = 0; z < sub[2]; z++)
    for (let y = 0; y < sub[1]; y++)
      for (let x = 0; x < sub[0]; x++) {
        const value = (v.data[x * stride + nx * (y * stride + ny * z * stride)] - lo) * scale;
        values[o++] = Number.isFinite(value) ? Math.min(1, Math.max(0, value)) : 0;
      }
  const cells = gridCells(sub, Math.max(1, Math.round(cellSize / stride)));
  const grid = buildMajorantGrid(
    computeCellValueRanges(values, sub, cells),
    rasterizeTransferFunction(scene.transferFunction, TF_RESOLUTION),
    scene.densityScale,
  );
  return statisticsOf(grid, extinctionCap(scene));
}

/**
 * Mean and global bounds of a majorant grid, and how much of the majorant the minorant covers.
 * The kernel's bounds are capped at σ_max (extinction-cap.ts); so are the statistics that steer it.
 */
function statisticsOf(grid: MajorantGrid, cap: number): GridStatistics {
  let sumMaj = 0,
    sumMin = 0;
  const n = grid.data.length / 4;
  for (let c = 0; c < n; c++) {
    sumMaj += Math.min(grid.data[4 * c], cap);
    sumMin += Math.min(grid.data[4 * c + 1], cap);
  }
  return {
    globalMajorant: Math.min(grid.globalMajorant, cap),
    globalMinorant: Math.min(grid.globalMinorant, cap),
    meanMajorant: sumMaj / n,
    minorantFraction: sumMaj > 0 ? sumMin / sumMaj : 0,
  };
}

/** The choices, each with the reason it was made ('set' when a parameter fixed it). */
export interface EstimatorChoice {
  tracking: TrackingMode;
  environmentSampling: EnvironmentSampling;
  majorantGrid: boolean;
  lightSamples: number;
  reasons: { tracking: string; environmentSampling: string; majorantGrid: string; lightSamples: string };
}

/** What the caller fixed (a value) or left to the rules (undefined), and the scattering order. */
export interface EstimatorRequest {
  tracking?: TrackingMode;
  environmentSampling?: EnvironmentSampling;
  majorantGrid?: boolean;
  lightSamples?: number;
  /** Henyey–Greenstein g of the medium (0 when absent). */
  anisotropy?: number;
  /** Single scattering (every path ends with a shadow ray). */
  singleScattering?: boolean;
}

/**
 * Apply the rules to what the request leaves open. `stats` is called only when a rule needs
 * the grid statistics.
 */
export function chooseEstimator(scene: Scene, request: EstimatorRequest, stats: () => GridStatistics): EstimatorChoice {
  const reasons = { tracking: 'set', environmentSampling: 'set', majorantGrid: 'set' };
  let environmentSampling = request.environmentSampling;
  if (environmentSampling === 'phase' && scene.environment.type === 'latlong') {
    const ratio = environmentPeakRatio(scene.environment);
    if (ratio > ENV_PEAK_RATIO_PHASE_TO_MIS) {
      environmentSampling = 'mis';
      reasons.environmentSampling = `phase was set, but the map's peak/mean ${ratio.toFixed(1)} > ${ENV_PEAK_RATIO_PHASE_TO_MIS} leaves phase sampling with fireflies: MIS (estimator 'fixed' keeps phase)`;
    }
  }
  if (environmentSampling === undefined) {
    const ratio = environmentPeakRatio(scene.environment);
    environmentSampling = ratio > ENV_PEAK_RATIO_FOR_MIS ? 'mis' : 'phase';
    reasons.environmentSampling =
      scene.environment.type === 'constant'
        ? 'constant environment'
        : `map peak/mean ${ratio.toFixed(1)} ${ratio > ENV_PEAK_RATIO_FOR_MIS ? '>' : '≤'} ${ENV_PEAK_RATIO_FOR_MIS}`;
    if (environmentSampling === 'mis' && request.singleScattering) {
      const peak = phasePeakRatio(request.anisotropy ?? 0);
      if (peak <= PHASE_PEAK_FOR_LIGHT_ONLY) {
        environmentSampling = 'light';
        reasons.environmentSampling += `; single scattering, phase peak ${peak.toFixed(2)}× isotropic ≤ ${PHASE_PEAK_FOR_LIGHT_ONLY}: light sampling alone`;
      }
    }
  }
  let majorantGrid = request.majorantGrid;
  let tracking = request.tracking;
  if (majorantGrid === undefined || tracking === undefined) {
    const s = stats();
    if (majorantGrid === undefined) {
      const gain = s.meanMajorant > 0 ? s.globalMajorant / s.meanMajorant : 1;
      majorantGrid = gain >= GRID_GAIN_FOR_WALK;
      reasons.majorantGrid = `global/mean cell majorant ${gain.toFixed(2)} ${majorantGrid ? '≥' : '<'} ${GRID_GAIN_FOR_WALK}`;
    }
    if (tracking === undefined && request.singleScattering) {
      tracking = 'residual';
      reasons.tracking = 'single scattering: the shadow rays carry all the light';
    } else if (tracking === undefined) {
      // Multiple scattering, under any environment. Without the grid the one control is the
      // global minorant (0 in most real volumes, the majorant in a homogeneous one).
      const fraction = majorantGrid
        ? s.minorantFraction
        : s.globalMajorant > 0
          ? s.globalMinorant / s.globalMajorant
          : 0;
      // Σ min / Σ max × mean max = the mean cell minorant: an optical depth per box length the medium guarantees.
      const minorantDepth = s.minorantFraction * s.meanMajorant;
      const dense = environmentSampling === 'phase' && minorantDepth >= DELTA_MINORANT_DEPTH;
      tracking = fraction >= RESIDUAL_MINORANT_FRACTION ? 'residual' : dense ? 'delta' : 'ratio';
      reasons.tracking =
        `cell minorants ${(100 * fraction).toFixed(0)}% of majorants, mean minorant ${minorantDepth.toFixed(2)} per box length` +
        (environmentSampling === 'phase' ? ' (shadow rays only toward the lights)' : '');
    }
  }
  const samples = chooseLightSamples(request, environmentSampling);
  const lightSamples = samples.lightSamples;
  return {
    tracking,
    environmentSampling,
    majorantGrid,
    lightSamples,
    reasons: { ...reasons, lightSamples: samples.reason },
  };
}

/**
 * Light samples per scattering event: SINGLE_SCATTERING_LIGHT_SAMPLES for single scattering
 * with the environment sampled by light alone, where one sample is one shadow ray per light
 * and the in-scattering estimate carries most of a pixel's variance (the camera ray's walk is
 * shared by all of them); one otherwise (with phase or MIS sampling a sample adds a second,
 * phase-sampled shadow ray, and more samples took longer to a target; figures:
 * docs/benchmarks.md#fig-estimator-choice).
 */
export function chooseLightSamples(
  request: EstimatorRequest,
  environmentSampling: EnvironmentSampling,
): { lightSamples: number; reason: string } {
  if (request.lightSamples !== undefined) return { lightSamples: request.lightSamples, reason: 'set' };
  if (!request.singleScattering) return { lightSamples: 1, reason: 'multiple scattering: one per event' };
  if (environmentSampling !== 'light')
    return { lightSamples: 1, reason: `single scattering, ${environmentSampling} sampling: one per event` };
  return {
    lightSamples: SINGLE_SCATTERING_LIGHT_SAMPLES,
    reason: 'single scattering, light sampling: the shadow rays carry most of the variance, the camera ray is shared',
  };
}

/** Memo of gridStatistics by volume object, TF, density and cell size (a camera move recomputes nothing). */
export class GridStatisticsMemo {
  private key = '';
  private volume: Volume | null = null;
  private labels: Volume | undefined = undefined;
  private value: GridStatistics | null = null;
  get(scene: Scene, cellSize: number): GridStatistics {
    const key = `${cellSize}|${scene.densityScale}|${JSON.stringify(scene.channels ?? scene.transferFunction)}|${JSON.stringify(scene.labels?.table ?? null)}`;
    if (!this.value || this.volume !== scene.volume || this.labels !== scene.labels?.volume || this.key !== key) {
      this.labels = scene.labels?.volume;
      this.value = gridStatistics(scene, cellSize);
      this.volume = scene.volume;
      this.key = key;
    }
    return this.value;
  }
}
