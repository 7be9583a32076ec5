import type { Volume } from '../scene/volume.js';
import { normalizationRange, normalizedData } from '../scene/volume.js';

/**
 * CPU reference of the gradient pass (gradient.glsl.ts / gradient.wgsl.ts), for tests and offline use:
 * per voxel, central differences of the normalized values (one-sided at the borders,
 * divided by the index distance actually spanned), scaled back to data units per
 * physical length: |∇f| with f in the volume's own units and lengths in spacing units.
 * Runs on the calling thread: RenderContext computes the gradient on the GPU instead.
 * Returns one float per voxel, x fastest.
 */
export function gradientMagnitudes(volume: Volume, normalized: Float32Array = normalizedData(volume)): Float32Array {
  const [nx, ny, nz] = volume.dims;
  const [lo, hi] = normalizationRange(volume);
  const scale = volume.spacing.map((s) => Math.abs(hi - lo) / s);
  const out = new Float32Array(nx * ny * nz);
  const at = (x: number, y: number, z: number) => normalized[x + nx * (y + ny * z)];
  const deriv = (i: number, n: number, f: (j: number) => number) => {
    const i0 = Math.max(i - 1, 0),
      i1 = Math.min(i + 1, n - 1);
    return i1 === i0 ? 0 : (f(i1) - f(i0)) / (i1 - i0);
  };
  for (let z = 0; z < nz; z++) {
    for (let y = 0; y < ny; y++) {
      for (let x = 0; x < nx; x++) {
        const gx = deriv(x, nx, (j) => at(j, y, z)) * scale[0];
        const gy = deriv(y, ny, (j) => at(x, j, z)) * scale[1];
        const gz = deriv(z, nz, (j) => at(x, y, j)) * scale[2];
        out[x + nx * (y + ny * z)] = Math.sqrt(gx * gx + gy * gy + gz * gz);
      }
    }
  }
  return out;
}

/** The largest gradient magnitude (the 2D transfer function's normalization); 0 for a constant volume. */
export function maxGradientMagnitude(magnitudes: Float32Array): number {
  let m = 0;
  for (let i = 0; i < magnitudes.length; i++) if (magnitudes[i] > m) m = magnitudes[i];
  return m;
}
