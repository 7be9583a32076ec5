/**
 * Blue-noise sampling of a path's first dimensions (the `sampler: 'blue-noise'` renderer
 * parameter; shader chunk SAMPLE_DIMS of blue-noise.glsl.ts / .wgsl.ts). The method, the mask
 * and its CPU twin are in blue-noise-mask.ts, loaded lazily (loadBlueNoise: a chunk of its own
 * in a bundle, so the viewer's entry pays only for this file); RenderContext.create loads it
 * before the context exists, so every renderer path after that finds it synchronously.
 */
import { VptError } from '../errors.js';
import type { AuxiliaryTexture } from '../renderer.js';

/** The mask's side in pixels (a power of two: kernels wrap with `& (size − 1)`). */
export const BLUE_NOISE_SIZE = 64;

/** The renderer parameter's choices: the PCG stream everywhere, or blue noise for the first dimensions. */
export const SAMPLERS = ['pcg', 'blue-noise'] as const;
export type Sampler = (typeof SAMPLERS)[number];

/**
 * The dimensions that blue noise serves (the kernels' `rngDim(rng, d)`); every other draw is
 * the PCG stream. 0, 1: the pixel jitter (R2 pair); 2: the march's offset (EAM, MIP, ISO) or
 * the camera ray's first free flight (MCRT); 3, 4: the first light sample (R2 pair).
 */
export const SAMPLE_DIM = { jitterX: 0, jitterY: 1, offset: 2, lightU: 3, lightV: 4 } as const;

type BlueNoiseModule = typeof import('./blue-noise-mask.js');
let loaded: BlueNoiseModule | null = null;
let loading: Promise<BlueNoiseModule> | null = null;

/**
 * Load the blue-noise module (mask generator, CPU twin, shader bodies) once; RenderContext.create
 * and precompile() await it. Rejects with VptError('load-failed') when its chunk cannot be
 * fetched (a later call tries again).
 */
export function loadBlueNoise(): Promise<BlueNoiseModule> {
  loading ??= import('./blue-noise-mask.js').then(
    (m) => (loaded = m),
    (e: unknown) => {
      loading = null;
      throw new VptError('load-failed', `sampler 'blue-noise': its module could not be loaded (${String(e)})`, {
        cause: e,
      });
    },
  );
  return loading;
}

/** The loaded blue-noise module; VptError('load-failed') before loadBlueNoise() resolved. */
export function blueNoiseModule(): BlueNoiseModule {
  if (!loaded)
    throw new VptError(
      'load-failed',
      "sampler 'blue-noise': its module is not loaded (await loadBlueNoise(); RenderContext.create and precompile() do)",
    );
  return loaded;
}

/** Where the kernels' SAMPLE_DIMS wants the BLUE_NOISE body (a line the preprocessor cuts without BLUE_NOISE). */
export const BLUE_NOISE_PLACEHOLDER = '// VPT_BLUE_NOISE_CHUNK';

/** A preprocessed kernel with the blue-noise body in place of BLUE_NOISE_PLACEHOLDER (unchanged without it). */
export function withBlueNoise(source: string, lang: 'glsl' | 'wgsl'): string {
  return source.includes(BLUE_NOISE_PLACEHOLDER)
    ? source.replace(BLUE_NOISE_PLACEHOLDER, blueNoiseModule().BLUE_NOISE_DIMS[lang])
    : source;
}

/** The mask as the auxiliary texture `blueNoise` (r32float ranks) that SAMPLE_DIMS reads under BLUE_NOISE. */
export function blueNoiseTexture(): AuxiliaryTexture {
  return {
    name: 'blueNoise',
    dimension: '2d',
    key: `void-and-cluster-${BLUE_NOISE_SIZE}`,
    create: () => ({
      dimension: '2d',
      width: BLUE_NOISE_SIZE,
      height: BLUE_NOISE_SIZE,
      format: 'r32float',
      data: blueNoiseModule().blueNoiseMask(),
      label: 'blue-noise mask',
    }),
  };
}

/**
 * The `sampler` renderer parameter (EAM, MIP, ISO, MCRT descriptors): 'blue-noise' compiles the
 * kernels with BLUE_NOISE and binds the mask; the default is chosen per renderer by measurement
 * (docs/benchmarks.md, "Blue-noise sampling").
 */
export function samplerParam<D extends Sampler>(defaultSampler: D) {
  return { kind: 'enum', values: SAMPLERS, default: defaultSampler as Sampler } as const;
}
