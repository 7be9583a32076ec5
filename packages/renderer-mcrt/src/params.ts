import { VptError, type ParamSpecs } from '@vpt/core';

/** Shadow-ray (transmittance) estimator. Free flights always use delta tracking. */
export type TrackingMode = 'delta' | 'ratio' | 'residual';
/** How light from the environment is gathered at a scattering event. */
export type EnvironmentSampling = 'mis' | 'light' | 'phase';

export interface McrtParams {
  /**
   * 'auto' (default): MCRT chooses the environment sampling, the shadow-ray tracking,
   * whether the majorant grid is walked and (single scattering) the light samples per event
   * per scene (estimator-choice.ts); any of those set here overrides its choice. 'fixed': the
   * unset ones take the fixed defaults (residual ratio tracking, majorant grid, MIS, 1 light
   * sample).
   */
  estimator?: 'auto' | 'fixed';
  /** 'single': one real scattering event per path (as in the seed paper); 'multiple' (default): up to `maxDepth`. */
  scattering?: 'single' | 'multiple';
  /** Multiple scattering: most real scattering events per path; -1 (default) = unlimited (Russian roulette ends paths). */
  maxDepth?: number;
  /** Real scattering events before Russian roulette may end a path (survival = max(throughput), capped at 1). Default 2. */
  rouletteDepth?: number;
  /** Henyey–Greenstein asymmetry g in [-0.9999, 0.9999]; g > 0 scatters forward. Default 0. */
  anisotropy?: number;
  /** Transmittance estimator for shadow rays. Chosen per scene with `estimator: 'auto'`; else default 'residual' (Novák et al. 2014). */
  tracking?: TrackingMode | 'auto';
  /** Traverse a coarse grid of per-cell extinction bounds instead of one global majorant. Chosen per scene with `estimator: 'auto'`; else default true. */
  majorantGrid?: boolean;
  /** Edge of a majorant-grid cell in voxels (default 8; at most 64 cells per axis). */
  majorantCellSize?: number;
  /**
   * Environment light: 'mis' = light sampling and phase sampling combined by multiple
   * importance sampling; 'light' = light sampling only; 'phase' = phase sampling only.
   * Chosen per scene with `estimator: 'auto'`; else default 'mis'.
   */
  environmentSampling?: EnvironmentSampling | 'auto';
  /**
   * Single scattering: in-scattering estimates at the scattering event, averaged (1 to
   * MAX_LIGHT_SAMPLES). Each is a light sample of every directional light and (light or MIS
   * sampling) of the environment, plus (phase or MIS sampling) a phase-sampled direction
   * toward the environment, each with its shadow ray; the camera ray's walk is shared. Chosen
   * per scene with `estimator: 'auto'`; else default 1. Multiple scattering takes one.
   */
  lightSamples?: number;
  /** MIS heuristic: 'power' (β = 2, default) or 'balance'. */
  misHeuristic?: 'power' | 'balance';
  /**
   * Debug outputs replacing the radiance: 'transmittance' = the shadow-ray estimator along each
   * camera ray through the box; 'fetches' = (medium lookups, majorant-grid cells visited, real
   * scattering events, 1) per path. Default 'none'.
   */
  debugOutput?: 'none' | 'transmittance' | 'fetches';
  /**
   * Compile a kernel specialised to the scene (default true). false = one generic kernel for
   * every scene, as a renderer without specialisation would have: the environment is always
   * an importance-sampled lat-long map (a constant sky becomes a constant map), the lights
   * are a loop over a runtime count, the scattering order is the runtime maxDepth and the
   * majorant grid is always traversed (one cell when `majorantGrid` is false). The images
   * agree in expectation; the benchmark `pnpm bench --suites specialization` measures the
   * difference in speed.
   */
  specialize?: boolean;
}

/** Every parameter filled in; 'auto' tracking / environment sampling resolve to the fixed defaults here (the renderer chooses per scene). */
export type ResolvedMcrtParams = Omit<Required<McrtParams>, 'tracking' | 'environmentSampling'> & {
  tracking: TrackingMode;
  environmentSampling: EnvironmentSampling;
};

/** The defaults; tracking, majorantGrid, environmentSampling and lightSamples are those of `estimator: 'fixed'`. */
export const MCRT_DEFAULTS: ResolvedMcrtParams = {
  estimator: 'auto',
  scattering: 'multiple',
  maxDepth: -1,
  rouletteDepth: 2,
  anisotropy: 0,
  tracking: 'residual',
  majorantGrid: true,
  majorantCellSize: 8,
  environmentSampling: 'mis',
  lightSamples: 1,
  misHeuristic: 'power',
  debugOutput: 'none',
  specialize: true,
};

/** The most light samples per scattering event (each count is its own kernel variant). */
export const MAX_LIGHT_SAMPLES = 16;

/** The largest |g| accepted: HG's peak (1+g)/(4π(1−g)²) stays far from float32 overflow. */
export const MAX_ANISOTROPY = 0.9999;

/** MCRT's parameters and their ranges (core's validateParams; resolveParams adds the rules across them). */
export const MCRT_PARAM_SPECS: ParamSpecs = {
  estimator: { kind: 'enum', values: ['auto', 'fixed'] },
  scattering: { kind: 'enum', values: ['single', 'multiple'] },
  maxDepth: { kind: 'number', integer: true, min: -1, max: 1 << 20 },
  rouletteDepth: { kind: 'number', integer: true, min: 1, max: 1 << 20 },
  anisotropy: { kind: 'number', min: -MAX_ANISOTROPY, max: MAX_ANISOTROPY },
  tracking: { kind: 'enum', values: ['auto', 'delta', 'ratio', 'residual'] },
  majorantGrid: { kind: 'boolean' },
  majorantCellSize: { kind: 'number', integer: true, min: 1, max: 4096, unit: 'voxels' },
  environmentSampling: { kind: 'enum', values: ['auto', 'mis', 'light', 'phase'] },
  lightSamples: { kind: 'number', integer: true, min: 1, max: MAX_LIGHT_SAMPLES },
  misHeuristic: { kind: 'enum', values: ['power', 'balance'] },
  debugOutput: { kind: 'enum', values: ['none', 'transmittance', 'fetches'] },
  specialize: { kind: 'boolean' },
};

const oneOf = <T extends string>(name: string, v: unknown, allowed: readonly T[]) => {
  if (!allowed.includes(v as T))
    throw new VptError('invalid-scene', `MCRT: ${name} must be one of ${allowed.join(', ')}, got ${JSON.stringify(v)}`);
};

/** Defaults filled in and every value checked; throws VptError('invalid-scene') naming the bad field. */
export function resolveParams(p: McrtParams): ResolvedMcrtParams {
  const r: ResolvedMcrtParams = { ...MCRT_DEFAULTS };
  for (const [k, v] of Object.entries(p)) if (v !== undefined && v !== 'auto') (r as Record<string, unknown>)[k] = v;
  oneOf('estimator', r.estimator, ['auto', 'fixed'] as const);
  oneOf('scattering', r.scattering, ['single', 'multiple'] as const);
  oneOf('tracking', r.tracking, ['delta', 'ratio', 'residual'] as const);
  oneOf('environmentSampling', r.environmentSampling, ['mis', 'light', 'phase'] as const);
  oneOf('misHeuristic', r.misHeuristic, ['power', 'balance'] as const);
  oneOf('debugOutput', r.debugOutput, ['none', 'transmittance', 'fetches'] as const);
  if (typeof r.specialize !== 'boolean')
    throw new VptError('invalid-scene', `MCRT: specialize must be a boolean, got ${JSON.stringify(r.specialize)}`);
  if (typeof r.majorantGrid !== 'boolean')
    throw new VptError('invalid-scene', `MCRT: majorantGrid must be a boolean, got ${JSON.stringify(r.majorantGrid)}`);
  if (!Number.isInteger(r.maxDepth) || r.maxDepth < -1 || r.maxDepth === 0)
    throw new VptError(
      'invalid-scene',
      `MCRT: maxDepth must be -1 (unlimited) or a positive integer, got ${r.maxDepth}`,
    );
  if (!Number.isInteger(r.lightSamples) || r.lightSamples < 1 || r.lightSamples > MAX_LIGHT_SAMPLES)
    throw new VptError(
      'invalid-scene',
      `MCRT: lightSamples must be an integer from 1 to ${MAX_LIGHT_SAMPLES}, got ${r.lightSamples}`,
    );
  if (!Number.isInteger(r.rouletteDepth) || r.rouletteDepth < 1)
    throw new VptError('invalid-scene', `MCRT: rouletteDepth must be a positive integer, got ${r.rouletteDepth}`);
  if (!Number.isFinite(r.anisotropy) || Math.abs(r.anisotropy) > MAX_ANISOTROPY)
    throw new VptError(
      'invalid-scene',
      `MCRT: anisotropy must be in [-${MAX_ANISOTROPY}, ${MAX_ANISOTROPY}], got ${r.anisotropy}`,
    );
  if (!Number.isInteger(r.majorantCellSize) || r.majorantCellSize < 1)
    throw new VptError(
      'invalid-scene',
      `MCRT: majorantCellSize must be a positive integer (voxels), got ${r.majorantCellSize}`,
    );
  return r;
}
