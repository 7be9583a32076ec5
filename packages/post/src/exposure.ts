import { UniformLayout, VptError, type PostStep, type UniformValues } from '@vpt/core';
import * as glsl from './exposure.glsl.js';
import * as wgsl from './exposure.wgsl.js';

/**
 * Largest |exposure| accepted, in stops. 2^64 ≈ 1.8e19 keeps the packed f32 factor and
 * ordinary HDR radiance times it finite; far beyond it the factor itself would round to
 * 0 or Infinity in f32 (and 0 * Infinity gives NaN).
 */
export const MAX_EXPOSURE_STOPS = 64;

/**
 * Largest |value| an exposure step writes. Every tone mapper maps 1e30 to white (to f32
 * precision), and 1e30 × 2^64 still overflows f32 — so the step clamps its input instead of
 * its output, and a chain of steps (each within ±64 stops) stays finite.
 */
export const EXPOSURE_OUTPUT_MAX = 1e30;

/** The f32 ceiling for the packed limit (a limit of Inf would be an Inf in the kernel). */
const F32_MAX = 3.4028234663852886e38;

const EXPOSURE_UNIFORMS = /* @__PURE__ */ new UniformLayout('ExposureParams', [
  { name: 'scale', type: 'f32' },
  { name: 'limit', type: 'f32' },
]);

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
    const scale = 2 ** this._exposure;
    // Rounded down to f32 below the bound, so limit × scale ≤ EXPOSURE_OUTPUT_MAX · (1 + 2^-23).
    return { scale, limit: Math.min(EXPOSURE_OUTPUT_MAX / scale, F32_MAX) };
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
