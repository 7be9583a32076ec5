import { UniformLayout, VptError, type PostStep, type UniformValues } from '@vpt/core';
import * as glsl from './exposure.glsl.js';
import * as wgsl from './exposure.wgsl.js';

/**
 * Largest |exposure| accepted, in stops. 2^64 ≈ 1.8e19 keeps the packed f32 factor and
 * ordinary HDR radiance times it finite; far beyond it the factor itself would round to
 * 0 or Infinity in f32 (and 0 * Infinity gives NaN).
 */
export const MAX_EXPOSURE_STOPS = 64;

const EXPOSURE_UNIFORMS = /* @__PURE__ */ new UniformLayout('ExposureParams', [{ name: 'scale', type: 'f32' }]);

/** Multiplies linear HDR colour by 2^exposure (photographic stops); alpha passes through. */
export class ExposureStep implements PostStep {
  readonly name = 'exposure';
  readonly glsl = glsl.EXPOSURE;
  readonly wgsl = wgsl.EXPOSURE;
  readonly uniforms = EXPOSURE_UNIFORMS;
  private _exposure = 0;

  constructor(exposure = 0) {
    this.exposure = exposure;
  }

  get exposure(): number {
    return this._exposure;
  }

  /** Takes effect on the next draw (it is a uniform, not a compile-time define). */
  set exposure(stops: number) {
    this._exposure = checkExposure(stops);
  }

  uniformValues(): UniformValues {
    // 2^e is computed here in float64, so the kernel is a single multiply on both backends.
    return { scale: 2 ** this._exposure };
  }
}

/** Returns `stops` if it is a finite number within ±MAX_EXPOSURE_STOPS, else throws VptError('invalid-scene'). */
export function checkExposure(stops: unknown, where = 'exposure'): number {
  if (typeof stops !== 'number' || !Number.isFinite(stops)) {
    throw new VptError('invalid-scene', `${where} must be a finite number of stops, got ${describe(stops)}`);
  }
  if (Math.abs(stops) > MAX_EXPOSURE_STOPS) {
    throw new VptError('invalid-scene', `${where} must lie within ±${MAX_EXPOSURE_STOPS} stops, got ${stops}`);
  }
  return stops;
}

function describe(v: unknown): string {
  return typeof v === 'number'
    ? String(v)
    : typeof v === 'string'
      ? `the string "${v}"`
      : v === null
        ? 'null'
        : typeof v;
}
