import { environmentEmits, normalize, VptError, type Scene, type Vec3 } from '@vpt/core';
import type { ResolvedMcrtParams } from './params.js';

/** Directional lights one kernel variant handles (uniform arrays of this length). */
export const MAX_LIGHTS = 8;

/**
 * The compile-time feature set of a scene + parameters: one kernel variant per distinct set,
 * containing only the code it needs (core's shaders/preprocess.ts). Flags that cannot matter are set to a
 * canonical value so they do not multiply variants.
 */
export interface McrtFeatures {
  /** The environment is a lat-long map (textures envMap/envMarginal/envConditional bound). */
  ENV_MAP: boolean;
  /** The environment emits light (a non-black constant or map): it is sampled at scattering events. */
  ENV_LIGHT: boolean;
  /** Directional lights with non-zero irradiance. */
  LIGHT_COUNT: number;
  SINGLE_SCATTERING: boolean;
  /** In-scattering estimates per scattering event (single scattering; 1 otherwise). */
  LIGHT_SAMPLES: number;
  /** Majorant grid + DDA (texture majorantGrid) instead of one global majorant. */
  MAJORANT_GRID: boolean;
  /** Shadow-ray estimator: 0 delta, 1 ratio, 2 residual ratio tracking. */
  TRACKING: number;
  /** Environment at scattering events: 0 phase sampling only, 1 light sampling only, 2 both with MIS. */
  ENV_SAMPLING: number;
  /** MIS with the power heuristic (else balance). */
  MIS_POWER: boolean;
  /** 0 radiance, 1 shadow-ray transmittance of the camera ray, 2 work counters. */
  DEBUG_OUTPUT: number;
  /** The unspecialised kernel (`specialize: false`): scene features are runtime data (see McrtParams.specialize). */
  GENERIC: boolean;
  /** `sampler: 'blue-noise'`: the path's first dimensions from core's SAMPLE_DIMS (texture blueNoise bound). */
  BLUE_NOISE: boolean;
}

export interface ActiveLight {
  direction: Vec3;
  irradiance: Vec3;
}

/** The scene's directional lights that emit, directions normalized (toward the light). */
export function activeLights(scene: Scene): ActiveLight[] {
  const lights = (scene.lights ?? []).filter((l) => l.irradiance.some((x) => x > 0));
  if (lights.length > MAX_LIGHTS) {
    throw new VptError(
      'limit-exceeded',
      `MCRT handles at most ${MAX_LIGHTS} directional lights, the scene has ${lights.length}`,
    );
  }
  return lights.map((l) => ({ direction: normalize(l.direction), irradiance: l.irradiance }));
}

export function computeFeatures(scene: Scene, p: ResolvedMcrtParams): McrtFeatures {
  if (!p.specialize) return genericFeatures(p);
  const envLight = environmentEmits(scene.environment);
  const envMap = scene.environment.type === 'latlong' && envLight;
  const envSampling = !envLight ? 0 : p.environmentSampling === 'phase' ? 0 : p.environmentSampling === 'light' ? 1 : 2;
  return {
    ENV_MAP: envMap,
    ENV_LIGHT: envLight,
    LIGHT_COUNT: activeLights(scene).length,
    SINGLE_SCATTERING: p.scattering === 'single',
    LIGHT_SAMPLES: p.scattering === 'single' ? p.lightSamples : 1,
    MAJORANT_GRID: p.majorantGrid,
    TRACKING: p.tracking === 'delta' ? 0 : p.tracking === 'ratio' ? 1 : 2,
    ENV_SAMPLING: envSampling,
    MIS_POWER: envSampling === 2 && p.misHeuristic === 'power',
    DEBUG_OUTPUT: p.debugOutput === 'transmittance' ? 1 : p.debugOutput === 'fetches' ? 2 : 0,
    GENERIC: false,
    BLUE_NOISE: p.sampler === 'blue-noise',
  };
}

/**
 * The one feature set of `specialize: false`, whatever the scene: every scene feature on
 * (environment map and light, MAX_LIGHTS lights cut short by a runtime count, multiple
 * scattering, majorant grid). The estimator choices (tracking, environment sampling, MIS
 * heuristic, light samples, debug output) stay compiled in, as they are in the specialised
 * kernels; the light samples apply where the runtime maxDepth is 1 (single scattering).
 */
function genericFeatures(p: ResolvedMcrtParams): McrtFeatures {
  const envSampling = p.environmentSampling === 'phase' ? 0 : p.environmentSampling === 'light' ? 1 : 2;
  return {
    ENV_MAP: true,
    ENV_LIGHT: true,
    LIGHT_COUNT: MAX_LIGHTS,
    SINGLE_SCATTERING: false,
    LIGHT_SAMPLES: p.scattering === 'single' ? p.lightSamples : 1,
    MAJORANT_GRID: true,
    TRACKING: p.tracking === 'delta' ? 0 : p.tracking === 'ratio' ? 1 : 2,
    ENV_SAMPLING: envSampling,
    MIS_POWER: envSampling === 2 && p.misHeuristic === 'power',
    DEBUG_OUTPUT: p.debugOutput === 'transmittance' ? 1 : p.debugOutput === 'fetches' ? 2 : 0,
    GENERIC: true,
    BLUE_NOISE: p.sampler === 'blue-noise',
  };
}

export const featureKey = (f: McrtFeatures) => JSON.stringify(f);
