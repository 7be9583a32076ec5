/**
 * MCRT described as data (core's RendererDescriptor): its parameters, defaults, uniforms and
 * viewer look, and the rules across parameters. Side-effect free and kernel free, so user
 * interfaces import it alone (`@vpt/renderer-mcrt/descriptor`).
 */
import { defineRenderer, SAMPLER_PARAM, VptError, type ParamsOf } from '@vpt/core';

/** Shadow-ray (transmittance) estimator. Free flights always use delta tracking. */
export type TrackingMode = 'delta' | 'ratio' | 'residual';
/** How light from the environment is gathered at a scattering event. */
export type EnvironmentSampling = 'mis' | 'light' | 'phase';

/** The most light samples per scattering event (each count is its own kernel variant). */
export const MAX_LIGHT_SAMPLES = 16;

/** The largest |g| accepted: HG's peak (1+g)/(4π(1−g)²) stays far from float32 overflow. */
export const MAX_ANISOTROPY = 0.9999;

/** The shadow-ray tracking with `estimator: 'fixed'` (Novák et al. 2014's residual ratio tracking). */
export const FIXED_TRACKING: TrackingMode = 'residual';
/** The environment sampling with `estimator: 'fixed'`. */
export const FIXED_ENVIRONMENT_SAMPLING: EnvironmentSampling = 'mis';

export const MCRT_DESCRIPTOR = defineRenderer({
  name: 'mcrt',
  label: 'Path tracing (MCRT)',
  owner: 'MCRT',
  params: {
    /**
     * 'auto' (default): MCRT chooses the environment sampling, the shadow-ray tracking,
     * whether the majorant grid is walked and (single scattering) the light samples per event
     * per scene (estimator-choice.ts); any of those set here overrides its choice. 'fixed': the
     * unset ones take the fixed defaults (residual ratio tracking, majorant grid, MIS, 1 light
     * sample).
     */
    estimator: { kind: 'enum', values: ['auto', 'fixed'], default: 'auto' },
    /** 'single': one real scattering event per path (as in the seed paper); 'multiple' (default): up to `maxDepth`. */
    scattering: {
      kind: 'enum',
      values: ['single', 'multiple'],
      uiValues: ['multiple', 'single'],
      default: 'multiple',
      ui: { label: 'Scattering' },
    },
    /** Henyey–Greenstein asymmetry g in [-MAX_ANISOTROPY, MAX_ANISOTROPY]; g > 0 scatters forward. Default 0. */
    anisotropy: {
      kind: 'number',
      min: -MAX_ANISOTROPY,
      max: MAX_ANISOTROPY,
      default: 0,
      ui: { label: 'Anisotropy g', step: 0.05 },
      uniform: { name: 'phaseG', type: 'f32' },
    },
    /** Multiple scattering: most real scattering events per path; -1 (default) = unlimited (Russian roulette ends paths). */
    maxDepth: {
      kind: 'number',
      integer: true,
      min: -1,
      max: 1 << 20,
      default: -1,
      defaultText: 'unlimited',
      ui: { label: 'Max bounces', max: 256, step: 1 },
      // Single scattering is a depth of one.
      uniform: { type: 'i32', pack: (depth, p) => (p.scattering === 'single' ? 1 : depth) },
    },
    /** Real scattering events before Russian roulette may end a path (survival = max(throughput), capped at 1). Default 2. */
    rouletteDepth: { kind: 'number', integer: true, min: 1, max: 1 << 20, default: 2, uniform: { type: 'i32' } },
    /** Transmittance estimator for shadow rays. Chosen per scene with `estimator: 'auto'`; else FIXED_TRACKING. */
    tracking: {
      kind: 'enum',
      values: ['auto', 'delta', 'ratio', 'residual'],
      uiValues: ['auto', 'residual', 'ratio', 'delta'],
      default: 'auto',
      ui: { label: 'Shadow tracking' },
    },
    /**
     * Environment light: 'mis' = light sampling and phase sampling combined by multiple
     * importance sampling; 'light' = light sampling only; 'phase' = phase sampling only.
     * Chosen per scene with `estimator: 'auto'`; else FIXED_ENVIRONMENT_SAMPLING.
     */
    environmentSampling: {
      kind: 'enum',
      values: ['auto', 'mis', 'light', 'phase'],
      default: 'auto',
      ui: { label: 'Environment sampling' },
    },
    /** Traverse a coarse grid of per-cell extinction bounds instead of one global majorant. Chosen per scene with `estimator: 'auto'`; else default true. */
    majorantGrid: { kind: 'boolean', default: true, ui: { label: 'Majorant grid' } },
    /** Edge of a majorant-grid cell in voxels (default 8; at most 64 cells per axis). */
    majorantCellSize: { kind: 'number', integer: true, min: 1, max: 4096, unit: 'voxels', default: 8 },
    /**
     * Single scattering: in-scattering estimates at the scattering event, averaged (1 to
     * MAX_LIGHT_SAMPLES). Each is a light sample of every directional light and (light or MIS
     * sampling) of the environment, plus (phase or MIS sampling) a phase-sampled direction
     * toward the environment, each with its shadow ray; the camera ray's walk is shared. Chosen
     * per scene with `estimator: 'auto'`; else default 1. Multiple scattering takes one.
     */
    lightSamples: { kind: 'number', integer: true, min: 1, max: MAX_LIGHT_SAMPLES, default: 1 },
    /** MIS heuristic: 'power' (β = 2, default) or 'balance'. */
    misHeuristic: { kind: 'enum', values: ['power', 'balance'], default: 'power' },
    /**
     * Debug outputs replacing the radiance: 'transmittance' = the shadow-ray estimator along each
     * camera ray through the box; 'fetches' = (medium lookups, majorant-grid cells visited, real
     * scattering events, 1) per path. Default 'none'.
     */
    debugOutput: { kind: 'enum', values: ['none', 'transmittance', 'fetches'], default: 'none' },
    /**
     * Compile a kernel specialised to the scene (default true). false = one generic kernel for
     * every scene, as a renderer without specialisation would have: the environment is always
     * an importance-sampled lat-long map (a constant sky becomes a constant map), the lights
     * are a loop over a runtime count, the scattering order is the runtime maxDepth and the
     * majorant grid is always traversed (one cell when `majorantGrid` is false). The images
     * agree in expectation; the benchmark `pnpm bench --suites specialization` measures the
     * difference in speed.
     */
    specialize: { kind: 'boolean', default: true },
    /**
     * 'blue-noise': the pixel jitter, the camera ray's first free flight and the first environment
     * light sample are a rank-1 sequence rotated per pixel by a blue-noise mask (core's
     * shaders/blue-noise.ts); the rest of the path keeps the PCG stream. 'pcg': the PCG stream
     * throughout. Default: by measured iterations to 30/35 dB (docs/benchmarks.md, "Blue-noise sampling").
     */
    sampler: SAMPLER_PARAM,
  },
  check: (p) => void resolveMcrtParams(p),
  writesGuides: true,
  needs: { transferFunction: true, lights: true, environment: true },
  look: { densityScale: 150, environment: [0.08, 0.09, 0.12], keyLight: [4, 3.7, 3.2], transferFunction: 'albedo' },
});

export type McrtParams = ParamsOf<typeof MCRT_DESCRIPTOR>;

/** Every parameter filled in; 'auto' tracking / environment sampling resolve to the fixed defaults here (the renderer chooses per scene). */
export type ResolvedMcrtParams = Omit<Required<McrtParams>, 'tracking' | 'environmentSampling'> & {
  tracking: TrackingMode;
  environmentSampling: EnvironmentSampling;
};

/** The defaults; tracking, majorantGrid, environmentSampling and lightSamples are those of `estimator: 'fixed'`. */
export const MCRT_DEFAULTS: ResolvedMcrtParams = {
  ...(Object.fromEntries(
    Object.entries(MCRT_DESCRIPTOR.params).map(([k, p]) => [k, p.default]),
  ) as unknown as ResolvedMcrtParams),
  tracking: FIXED_TRACKING,
  environmentSampling: FIXED_ENVIRONMENT_SAMPLING,
};

const oneOf = <T extends string>(name: string, v: unknown, allowed: readonly T[]) => {
  if (!allowed.includes(v as T))
    throw new VptError('invalid-scene', `MCRT: ${name} must be one of ${allowed.join(', ')}, got ${JSON.stringify(v)}`);
};

/** Defaults filled in and every value checked, with the rules across parameters; throws VptError('invalid-scene') naming the bad field. */
export function resolveMcrtParams(p: McrtParams): ResolvedMcrtParams {
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

/** The package's descriptor under the name every renderer package uses (the generated loaders read it). */
export { MCRT_DESCRIPTOR as descriptor };
