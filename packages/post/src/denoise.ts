import { UniformLayout, VptError, type PostStep, type UniformValues } from '@vpt/core';
import * as glsl from './denoise.glsl.js';
import * as wgsl from './denoise.wgsl.js';

/** Parameters of the denoise step; omitted ones take DENOISE_DEFAULTS. */
export interface DenoiseParams {
  /** À-trous levels (draws), step 2^i at level i: 5 covers a 125-pixel footprint. */
  iterations?: number;
  /** σ_l: luminance differences are measured in this many standard deviations of the pixel's mean (SVGF: 4). */
  colorSigma?: number;
  /**
   * σ_l is multiplied by this per level (level i: decay^i), on top of the variance filtered along
   * the levels as in SVGF (1: SVGF's filter as published).
   */
  colorSigmaDecay?: number;
  /**
   * σ_n: exponent of the normal weight max(0, n_p·n_q)^σ_n (SVGF: 128; far lower here: a volume's
   * normal guide is the gradient at a random first collision, so it is noisy where the image is).
   */
  normalSigma?: number;
  /** σ_z: depth differences are measured against σ_z times the screen-space depth gradient (SVGF: 1). */
  depthSigma?: number;
  /** Added to w_z's denominator, in world units (the volume's longest side is 1): depth differences below it pass. */
  depthEpsilon?: number;
  /** σ_a of the Gaussian weight on the (albedo, hit fraction) difference. */
  albedoSigma?: number;
  /**
   * The relative standard error of a pixel's mean (√Var / mean luminance) below which the filter
   * fades: each level's change is scaled by min(1, error / fadeError), so as samples accumulate
   * (error ∝ 1/√n) the image tends to the plain estimate.
   */
  fadeError?: number;
}

export const DENOISE_DEFAULTS: Readonly<Required<DenoiseParams>> = {
  iterations: 5,
  colorSigma: 4,
  colorSigmaDecay: 1,
  normalSigma: 0,
  depthSigma: 1,
  depthEpsilon: 0.1,
  albedoSigma: 1,
  fadeError: 0.1,
};

/** Allowed ranges; each bound is named in the error. */
const RANGES: Readonly<Record<keyof DenoiseParams, { min: number; max: number; integer?: boolean }>> = {
  iterations: { min: 1, max: 10, integer: true },
  colorSigma: { min: 1e-3, max: 1e6 },
  colorSigmaDecay: { min: 1e-3, max: 1 },
  normalSigma: { min: 0, max: 1e4 },
  depthSigma: { min: 0, max: 1e6 },
  depthEpsilon: { min: 1e-9, max: 1e6 },
  albedoSigma: { min: 1e-3, max: 1e6 },
  fadeError: { min: 1e-9, max: 1e6 },
};

export const DENOISE_PARAM_NAMES = Object.keys(RANGES) as (keyof DenoiseParams)[];

const DENOISE_UNIFORMS = /* @__PURE__ */ new UniformLayout('DenoiseParams', [
  { name: 'stepWidth', type: 'i32' },
  { name: 'passThrough', type: 'i32' },
  { name: 'sigmaScale', type: 'f32' },
  { name: 'colorSigma', type: 'f32' },
  { name: 'normalSigma', type: 'f32' },
  { name: 'depthSigma', type: 'f32' },
  { name: 'depthEpsilon', type: 'f32' },
  { name: 'albedoSigma', type: 'f32' },
  { name: 'fadeError', type: 'f32' },
]);

/**
 * The denoiser (docs/architecture.md, "Denoising"): an edge-avoiding à-trous wavelet filter on
 * the HDR image, guided by the renderer's accumulated normal, depth and albedo and by each pixel's
 * variance of the mean, so it smooths where noise is high and leaves a converged image as it is.
 * Put it first in the chain, before exposure and tone mapping. `enabled = false` passes the image
 * through (one copy), keeping the guides, so switching it back on needs no new samples.
 */
export class DenoiseStep implements PostStep {
  readonly name = 'denoise';
  readonly glsl = glsl.B3_TAPS + glsl.DENOISE;
  readonly wgsl = wgsl.B3_TAPS + wgsl.DENOISE;
  readonly uniforms = DENOISE_UNIFORMS;
  readonly usesGuides = true;
  readonly keepsRadiance = true;
  /** Each level also writes its filtered luminance variance, which the next level reads as `inputState`. */
  readonly stateOutput = true;
  /** When false the step copies its input. */
  enabled = true;
  private readonly params: Required<DenoiseParams>;

  constructor(params: DenoiseParams = {}) {
    this.params = { ...DENOISE_DEFAULTS, ...checkDenoiseParams(params) };
  }

  get repeat(): number {
    return this.enabled ? this.params.iterations : 1;
  }

  getParams(): Readonly<Required<DenoiseParams>> {
    return { ...this.params };
  }

  uniformValues(draw = 0): UniformValues {
    const p = this.params;
    return {
      stepWidth: 2 ** draw,
      passThrough: this.enabled ? 0 : 1,
      sigmaScale: p.colorSigmaDecay ** draw,
      colorSigma: p.colorSigma,
      normalSigma: p.normalSigma,
      depthSigma: p.depthSigma,
      depthEpsilon: p.depthEpsilon,
      albedoSigma: p.albedoSigma,
      fadeError: p.fadeError,
    };
  }
}

/** Checks denoise parameters (unknown keys, types, ranges); throws VptError('invalid-scene') naming the field. */
export function checkDenoiseParams(params: unknown, where = 'denoise'): DenoiseParams {
  if (typeof params !== 'object' || params === null || Array.isArray(params))
    throw new VptError('invalid-scene', `${where}: parameters must be an object`);
  const out: DenoiseParams = {};
  for (const [key, value] of Object.entries(params)) {
    if (value === undefined) continue;
    if (!Object.hasOwn(RANGES, key))
      throw new VptError(
        'invalid-scene',
        `${where}: unknown parameter "${key}" (known: ${DENOISE_PARAM_NAMES.map((k) => `"${k}"`).join(', ')})`,
      );
    const r = RANGES[key as keyof DenoiseParams];
    if (typeof value !== 'number' || !Number.isFinite(value))
      throw new VptError('invalid-scene', `${where}: ${key} must be a finite number, got ${JSON.stringify(value)}`);
    if (r.integer && !Number.isInteger(value))
      throw new VptError('invalid-scene', `${where}: ${key} must be an integer, got ${value}`);
    if (value < r.min || value > r.max)
      throw new VptError('invalid-scene', `${where}: ${key} must lie in [${r.min}, ${r.max}], got ${value}`);
    out[key as keyof DenoiseParams] = value;
  }
  return out;
}
