/**
 * Histograms the transfer-function editors draw behind their controls: counts of the
 * normalized value (what the 1D transfer function is indexed by) and, for 2D transfer
 * functions, of value × gradient magnitude. Large volumes are subsampled on a regular
 * grid so this stays well under a frame's worth of work per million voxels.
 */
import { gradientMagnitudes, maxGradientMagnitude, normalizationRange, normalizedData, type Volume } from '@vpt/core';

/** At most this many voxels are visited (every k-th along each axis beyond it). */
const MAX_VISITED = 2_000_000;

export interface Histogram1D {
  bins: Float64Array;
  max: number;
}
export interface Histogram2D {
  width: number;
  height: number;
  bins: Float64Array;
  max: number;
  maxGradient: number;
}

function strideFor(v: Volume): number {
  const n = v.dims[0] * v.dims[1] * v.dims[2];
  return Math.max(1, Math.ceil(Math.cbrt(n / MAX_VISITED)));
}

/** `bins` counts of the normalized value in [0, 1]; `max` ignores bin 0 when it dominates (the empty background). */
export function valueHistogram(v: Volume, binCount = 256): Histogram1D {
  const [lo, hi] = normalizationRange(v);
  const scale = 1 / (hi - lo);
  const bins = new Float64Array(binCount);
  const [nx, ny, nz] = v.dims;
  const s = strideFor(v);
  for (let z = 0; z < nz; z += s) {
    for (let y = 0; y < ny; y += s) {
      const row = nx * (y + ny * z);
      for (let x = 0; x < nx; x += s) {
        const t = (v.data[row + x] - lo) * scale;
        if (!Number.isFinite(t)) continue;
        bins[Math.min(binCount - 1, Math.max(0, Math.floor(t * binCount)))]++;
      }
    }
  }
  return { bins, max: robustMax(bins) };
}

/**
 * The volume's (normalized value, gradient magnitude) pairs, the data of the 2D
 * histogram. Gradient magnitudes are what the renderers see (core's gradientMagnitudes:
 * central differences, data units per spacing unit), computed exactly for volumes up to
 * two million voxels and on every k-th voxel beyond, where `maxGradient` is then the
 * largest sampled magnitude rather than the exact one.
 */
export interface GradientSamples {
  values: Float32Array;
  gradients: Float32Array;
  maxGradient: number;
}

export function gradientSamples(v: Volume): GradientSamples {
  const [lo, hi] = normalizationRange(v);
  const scale = 1 / (hi - lo);
  const [nx, ny, nz] = v.dims;
  const s = strideFor(v);
  if (s === 1) {
    const normalized = normalizedData(v);
    const gradients = gradientMagnitudes(v, normalized);
    return { values: normalized, gradients, maxGradient: maxGradientMagnitude(gradients) };
  }
  const norm = (i: number) => {
    const t = (v.data[i] - lo) * scale;
    return Number.isFinite(t) ? Math.min(1, Math.max(0, t)) : 0;
  };
  const at = (x: number, y: number, z: number) => norm(x + nx * (y + ny * z));
  // Same formula as core's gradientMagnitudes, evaluated only at the sampled voxels.
  const deriv = (i: number, n: number, f: (j: number) => number) => {
    const i0 = Math.max(i - 1, 0),
      i1 = Math.min(i + 1, n - 1);
    return i1 === i0 ? 0 : (f(i1) - f(i0)) / (i1 - i0);
  };
  const k = v.spacing.map((sp) => Math.abs(hi - lo) / sp); // |hi − lo|: an inverted range keeps magnitudes
  const count = Math.ceil(nx / s) * Math.ceil(ny / s) * Math.ceil(nz / s);
  const values = new Float32Array(count),
    gradients = new Float32Array(count);
  let n = 0,
    max = 0;
  for (let z = 0; z < nz; z += s) {
    for (let y = 0; y < ny; y += s) {
      for (let x = 0; x < nx; x += s) {
        const gx = deriv(x, nx, (j) => at(j, y, z)) * k[0];
        const gy = deriv(y, ny, (j) => at(x, j, z)) * k[1];
        const gz = deriv(z, nz, (j) => at(x, y, j)) * k[2];
        const g = Math.sqrt(gx * gx + gy * gy + gz * gz);
        values[n] = at(x, y, z);
        gradients[n++] = g;
        if (g > max) max = g;
      }
    }
  }
  return { values, gradients, maxGradient: max };
}

/**
 * Counts over value (x, `width` bins) × normalized gradient magnitude (y, `height` bins,
 * row 0 = gradient 0): the axes of a 2D transfer function, the gradient divided by
 * `gradientMax` (the TF's own, else the volume's largest) and clamped to 1 as the kernels do.
 */
export function valueGradientHistogram(
  s: GradientSamples,
  gradientMax = s.maxGradient,
  width = 128,
  height = 64,
): Histogram2D {
  const bins = new Float64Array(width * height);
  const inv = gradientMax > 0 ? 1 / gradientMax : 0;
  for (let i = 0; i < s.values.length; i++) {
    const bx = Math.min(width - 1, Math.floor(s.values[i] * width));
    const by = Math.min(height - 1, Math.floor(Math.min(1, s.gradients[i] * inv) * height));
    bins[bx + width * by]++;
  }
  return { width, height, bins, max: robustMax(bins), maxGradient: gradientMax };
}

/** The largest count once the single largest bin is set aside (usually the empty background). */
function robustMax(bins: Float64Array): number {
  let first = 0,
    second = 0;
  for (const b of bins) {
    if (b > first) {
      second = first;
      first = b;
    } else if (b > second) second = b;
  }
  return Math.max(1, second > 0 ? second : first);
}
