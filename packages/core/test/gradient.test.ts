import { describe, expect, it } from 'vitest';
import { atlasTexel, createVolume, sliceAtlasLayout, gradientMagnitudes, maxGradientMagnitude } from '../src/index.js';

/** A float32 volume from f(x, y, z) in physical units (voxel centre = index × spacing), normalized over valueRange. */
function field(
  dims: [number, number, number],
  spacing: [number, number, number],
  f: (x: number, y: number, z: number) => number,
  valueRange: [number, number],
) {
  const [nx, ny, nz] = dims;
  const data = new Float32Array(nx * ny * nz);
  for (let z = 0; z < nz; z++)
    for (let y = 0; y < ny; y++)
      for (let x = 0; x < nx; x++) data[x + nx * (y + ny * z)] = f(x * spacing[0], y * spacing[1], z * spacing[2]);
  const v = createVolume(dims, 'float32', data, spacing);
  v.valueRange = valueRange;
  return v;
}

describe('gradient magnitude (CPU reference)', () => {
  it('equals the slope of a linear ramp everywhere, borders included', () => {
    // f = 0.3·x − 0.2·y + 0.5·z with anisotropic spacing: |∇f| = sqrt(0.09 + 0.04 + 0.25)
    const v = field([9, 7, 5], [1, 2, 0.5], (x, y, z) => 0.3 * x - 0.2 * y + 0.5 * z, [-10, 10]);
    const g = gradientMagnitudes(v);
    const slope = Math.sqrt(0.3 ** 2 + 0.2 ** 2 + 0.5 ** 2);
    for (const m of g) expect(m).toBeCloseTo(slope, 5);
    expect(maxGradientMagnitude(g)).toBeCloseTo(slope, 5);
  });

  it('is 1 for a sphere distance field away from the centre', () => {
    const n = 33,
      c = 16;
    const v = field([n, n, n], [1, 1, 1], (x, y, z) => Math.hypot(x - c, y - c, z - c), [0, 30]);
    const g = gradientMagnitudes(v);
    let checked = 0;
    for (let z = 1; z < n - 1; z++)
      for (let y = 1; y < n - 1; y++)
        for (let x = 1; x < n - 1; x++) {
          const r = Math.hypot(x - c, y - c, z - c);
          if (r < 4) continue;
          // Central differences of a distance field: the error is O(1/r²) (curvature), < 2% from r = 4 on.
          expect(Math.abs(g[x + n * (y + n * z)] - 1)).toBeLessThan(0.02);
          checked++;
        }
    expect(checked).toBeGreaterThan(20000);
  });

  it('is 0 for a constant volume', () => {
    const v = field([4, 4, 4], [1, 1, 1], () => 5, [0, 10]);
    expect(maxGradientMagnitude(gradientMagnitudes(v))).toBe(0);
  });
});

describe('gradient slice atlas', () => {
  it('tiles every slice exactly once inside a near-square atlas', () => {
    for (const dims of [
      [128, 128, 84],
      [512, 512, 61],
      [301, 370, 316],
      [4, 4, 1],
      [1, 1, 1],
      [7, 3, 50],
    ] as [number, number, number][]) {
      const l = sliceAtlasLayout(dims);
      expect(l.columns * l.rows).toBeGreaterThanOrEqual(dims[2]);
      expect((l.rows - 1) * l.columns).toBeLessThan(dims[2]); // no empty row of tiles
      expect(l.width).toBe(l.columns * dims[0]);
      expect(l.height).toBe(l.rows * dims[1]);
      const seen = new Set<string>();
      for (let z = 0; z < dims[2]; z++) {
        const [u, v] = atlasTexel(l, dims, 0, 0, z);
        expect(u + dims[0]).toBeLessThanOrEqual(l.width);
        expect(v + dims[1]).toBeLessThanOrEqual(l.height);
        seen.add(`${u},${v}`);
      }
      expect(seen.size).toBe(dims[2]);
    }
    const big = sliceAtlasLayout([301, 370, 316]);
    expect(Math.max(big.width, big.height) / Math.min(big.width, big.height)).toBeLessThan(1.5);
  });
});
