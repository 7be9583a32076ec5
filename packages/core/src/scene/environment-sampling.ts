/**
 * Lat-long environment maps: the direction mapping (Mitsuba 3's envmap convention, see
 * docs/architecture.md) and the importance-sampling tables the kernels read
 * (shaders/sampling.glsl.ts ENVIRONMENT_MAP), plus CPU twins of the kernel's lookup
 * and sampling for tests.
 *
 * Mapping: u = atan2(x, −z) / 2π wrapped to [0, 1), v = acos(y) / π. Column i covers
 * u ∈ [i/W, (i+1)/W), row j covers v ∈ [j/H, (j+1)/H); row 0 is the top (+y). The radiance
 * is piecewise constant per texel (no filtering), exactly the function the sampler draws from.
 */
import { VptError } from '../errors.js';
import type { Vec3 } from './camera.js';
import type { Environment } from './lights.js';

export type LatLongEnvironment = Extract<Environment, { type: 'latlong' }>;

export interface EnvironmentSamplingTables {
  width: number;
  height: number;
  /** W x H RGBA: rgb = radiance x scale, a = the texel's density in (u, v) space (mean 1 over the image). */
  map: Float32Array;
  /** H + 1 entries: CDF over rows, marginal[0] = 0, marginal[H] = 1. */
  marginal: Float32Array;
  /** (W + 1) x H entries, row j at offset j (W + 1): CDF over the columns of row j. */
  conditional: Float32Array;
  /** Sum over texels of luminance x sinθ / (W H), for diagnostics. */
  meanWeightedLuminance: number;
}

/** Rec. 709 luminance. */
export const luminance = (r: number, g: number, b: number) => 0.2126 * r + 0.7152 * g + 0.0722 * b;

export function directionToLatLong(d: Vec3): [number, number] {
  let u = d[0] === 0 && d[2] === 0 ? 0 : Math.atan2(d[0], -d[2]) / (2 * Math.PI);
  if (u < 0) u += 1;
  const v = Math.acos(Math.min(1, Math.max(-1, d[1]))) / Math.PI;
  return [u, v];
}

export function latLongToDirection(u: number, v: number): Vec3 {
  const phi = 2 * Math.PI * u,
    theta = Math.PI * v;
  const st = Math.sin(theta);
  return [st * Math.sin(phi), Math.cos(theta), -st * Math.cos(phi)];
}

/**
 * The sampling tables of a lat-long environment: texels are chosen with probability
 * proportional to luminance × sinθ (θ at the row centre), so p(ω) = p(u, v) / (2π² sinθ).
 * An environment with no light at all gets uniform tables (it is never worth sampling, but
 * the kernel's arithmetic stays finite). Computed in float64, stored as float32; the CDFs
 * end in exactly 1.
 */
export function buildEnvironmentSampling(env: LatLongEnvironment): EnvironmentSamplingTables {
  const { width: W, height: H, data } = env;
  const scale = env.scale ?? 1;
  if (!Number.isFinite(scale) || scale < 0)
    throw new VptError('invalid-scene', `Environment: scale must be finite and non-negative, got ${scale}`);
  if (data.length !== W * H * 3)
    throw new VptError('invalid-scene', 'Environment: lat-long image needs width*height*3 floats');
  const map = new Float32Array(W * H * 4);
  const weight = new Float64Array(W * H);
  const rowSum = new Float64Array(H);
  let total = 0;
  for (let j = 0; j < H; j++) {
    const sinTheta = Math.sin((Math.PI * (j + 0.5)) / H);
    for (let i = 0; i < W; i++) {
      const k = j * W + i;
      const r = data[3 * k] * scale,
        g = data[3 * k + 1] * scale,
        b = data[3 * k + 2] * scale;
      map[4 * k] = r;
      map[4 * k + 1] = g;
      map[4 * k + 2] = b;
      const w = Math.max(0, luminance(r, g, b)) * sinTheta;
      weight[k] = w;
      rowSum[j] += w;
    }
    total += rowSum[j];
  }
  const uniform = !(total > 0) || !Number.isFinite(total);
  if (uniform) {
    weight.fill(1);
    rowSum.fill(W);
    total = W * H;
  }
  const mean = total / (W * H);
  for (let k = 0; k < W * H; k++) map[4 * k + 3] = weight[k] / mean;
  const marginal = new Float32Array(H + 1);
  let acc = 0;
  for (let j = 0; j < H; j++) {
    acc += rowSum[j];
    marginal[j + 1] = acc / total;
  }
  marginal[H] = 1;
  const conditional = new Float32Array((W + 1) * H);
  for (let j = 0; j < H; j++) {
    const o = j * (W + 1);
    let c = 0;
    for (let i = 0; i < W; i++) {
      c += weight[j * W + i];
      conditional[o + i + 1] = rowSum[j] > 0 ? c / rowSum[j] : (i + 1) / W;
    }
    conditional[o + W] = 1;
  }
  return { width: W, height: H, map, marginal, conditional, meanWeightedLuminance: uniform ? 0 : mean };
}

/** True when the environment emits any light (a lat-long map with a positive texel, or a positive constant). */
export function environmentEmits(env: Environment): boolean {
  if (env.type === 'constant') return env.radiance.some((x) => x > 0);
  if ((env.scale ?? 1) <= 0) return false;
  for (let i = 0; i < env.data.length; i++) if (env.data[i] > 0) return true;
  return false;
}

/** CPU twin of the kernel's environmentLookup: radiance along d and the sampler's solid-angle pdf. */
export function environmentLookupCpu(t: EnvironmentSamplingTables, d: Vec3): { radiance: Vec3; pdf: number } {
  const [u, v] = directionToLatLong(d);
  const i = Math.min(t.width - 1, Math.max(0, Math.floor(u * t.width)));
  const j = Math.min(t.height - 1, Math.max(0, Math.floor(v * t.height)));
  const k = 4 * (j * t.width + i);
  const sinTheta = Math.sqrt(Math.max(0, (1 - d[1]) * (1 + d[1])));
  return {
    radiance: [t.map[k], t.map[k + 1], t.map[k + 2]],
    pdf: sinTheta > 0 ? t.map[k + 3] / (2 * Math.PI * Math.PI * sinTheta) : 0,
  };
}

/** Largest index in [0, n-1] with cdf[offset + index] <= xi (the kernel's binary search). */
function searchCdf(cdf: Float32Array, offset: number, n: number, xi: number): number {
  let lo = 0,
    hi = n - 1;
  while (lo < hi) {
    const mid = (lo + hi + 1) >> 1;
    if (cdf[offset + mid] <= xi) lo = mid;
    else hi = mid - 1;
  }
  return lo;
}

/** CPU twin of the kernel's sampleEnvironment. */
export function sampleEnvironmentCpu(
  t: EnvironmentSamplingTables,
  xi1: number,
  xi2: number,
): { direction: Vec3; pdf: number; radiance: Vec3; texel: [number, number] } {
  const W = t.width,
    H = t.height;
  const j = searchCdf(t.marginal, 0, H, xi1);
  const dv = Math.min(0.99999994, Math.max(0, (xi1 - t.marginal[j]) / (t.marginal[j + 1] - t.marginal[j])));
  const o = j * (W + 1);
  const i = searchCdf(t.conditional, o, W, xi2);
  const du = Math.min(
    0.99999994,
    Math.max(0, (xi2 - t.conditional[o + i]) / (t.conditional[o + i + 1] - t.conditional[o + i])),
  );
  const u = (i + du) / W,
    v = (j + dv) / H;
  const k = 4 * (j * W + i);
  const sinTheta = Math.sin(Math.PI * v);
  return {
    direction: latLongToDirection(u, v),
    pdf: sinTheta > 0 ? t.map[k + 3] / (2 * Math.PI * Math.PI * sinTheta) : 0,
    radiance: [t.map[k], t.map[k + 1], t.map[k + 2]],
    texel: [i, j],
  };
}
