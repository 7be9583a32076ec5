import { describe, expect, it } from 'vitest';
import { createVolume, type Vec3 } from '@vpt/core';
import { colormapTable, resolveSliceParams, slicePlane, windowMapping, type SliceParams } from '../src/index.js';

const planeOf = (params: SliceParams, dims: [number, number, number], spacing: Vec3 = [1, 1, 1]) =>
  slicePlane(resolveSliceParams(params).plane, { dims, spacing });

function expectVec(a: readonly number[], b: readonly number[]) {
  a.forEach((x, i) => expect(x).toBeCloseTo(b[i], 12));
}

describe('slice plane geometry', () => {
  // A [8, 4, 2] volume of unit spacing: the box is [-0.5, 0.5] x [-0.25, 0.25] x [-0.125, 0.125].
  it('an axis-aligned plane runs through the centres of its voxel layer and spans the box face', () => {
    const z = planeOf({ axis: 'z', index: 1 }, [8, 4, 2]);
    expectVec(z.origin, [-0.5, -0.25, 0.0625]); // layer 1 of 2 spans [0, 0.125]: centre 0.0625
    expectVec(z.u, [1, 0, 0]);
    expectVec(z.v, [0, 0.5, 0]);
    expectVec(z.normal, [0, 0, 1]);
    const x = planeOf({ axis: 'x', index: 0 }, [8, 4, 2]);
    expectVec(x.origin, [-0.4375, -0.25, -0.125]);
    expectVec(x.u, [0, 0.5, 0]); // columns along y, rows along z
    expectVec(x.v, [0, 0, 0.25]);
    const y = planeOf({ axis: 'y', position: 0.1 }, [8, 4, 2]);
    expectVec(y.origin, [-0.5, 0.1, -0.125]);
    expectVec(y.u, [1, 0, 0]); // columns along x, rows along z
    expectVec(y.v, [0, 0, 0.25]);
    // Default: layer ⌊n/2⌋.
    expectVec(planeOf({}, [8, 4, 3]).origin, [-0.5, -0.25, 0]);
  });

  it('anisotropic spacing scales the box, not the voxel layers', () => {
    // [4, 4, 4] voxels of spacing [1, 1, 2]: box z in [-0.5, 0.5], x and y in [-0.25, 0.25].
    const p = planeOf({ axis: 'z', index: 0 }, [4, 4, 4], [1, 1, 2]);
    expectVec(p.origin, [-0.25, -0.25, -0.375]);
    expectVec(p.u, [0.5, 0, 0]);
  });

  it('an oblique plane: the diagonal cut of a cube is a √2 x 1 rectangle', () => {
    // Normal (1, 1, 0) through the centre of [-0.5, 0.5]^3; ties pick x as the dominant axis, whose
    // image axes are (y, z): the columns run along y projected into the plane, (-1, 1, 0)/√2.
    const p = planeOf({ normal: [1, 1, 0] }, [8, 8, 8]);
    expectVec(p.normal, [Math.SQRT1_2, Math.SQRT1_2, 0]);
    expectVec(p.origin, [0.5, -0.5, -0.5]);
    expectVec(p.u, [-1, 1, 0]);
    expectVec(p.v, [0, 0, 1]);
  });

  it('an oblique plane: every point of the rectangle lies on the plane, and its corners bound the cut', () => {
    const normal: Vec3 = [0.3, -0.5, 0.8];
    const point: Vec3 = [0.05, 0.02, -0.03];
    const p = planeOf({ normal, point }, [10, 8, 6]);
    const len = Math.hypot(...normal);
    const onPlane = (q: number[]) => q.reduce((s, x, i) => s + (x - point[i]) * (normal[i] / len), 0);
    for (const [s, t] of [
      [0, 0],
      [1, 0],
      [0, 1],
      [0.3, 0.7],
    ]) {
      const q = [0, 1, 2].map((i) => p.origin[i] + p.u[i] * s + p.v[i] * t);
      expect(Math.abs(onPlane(q))).toBeLessThan(1e-12);
    }
    const dot = (a: readonly number[], b: readonly number[]) => a.reduce((s, x, i) => s + x * b[i], 0);
    expect(Math.abs(dot(p.u, p.v))).toBeLessThan(1e-12);
    expect(Math.abs(dot(p.u, normal))).toBeLessThan(1e-12);
  });
});

describe('window in data units', () => {
  it('maps [center − width/2, center + width/2] of the data to [0, 1] whatever the value range', () => {
    const ct = { ...createVolume([2, 2, 2], 'int16'), valueRange: [-1024, 3071] as [number, number] };
    for (const volume of [ct, { ...ct, valueRange: [3071, -1024] as [number, number] }]) {
      const [lo, hi] = volume.valueRange;
      const { windowScale, windowOffset } = windowMapping(volume, [40, 400]);
      // The kernel's normalized value of a datum, then the window.
      const windowed = (hu: number) => ((hu - lo) / (hi - lo)) * windowScale + windowOffset;
      expect(windowed(40)).toBeCloseTo(0.5, 12);
      expect(windowed(-160)).toBeCloseTo(0, 12);
      expect(windowed(240)).toBeCloseTo(1, 12);
    }
    expect(windowMapping(ct, null)).toEqual({ windowScale: 1, windowOffset: 0 });
  });
});

describe('colour maps', () => {
  // Endpoints as published (matplotlib's viridis #440154 … #fde725; Moreland's cool-warm 59,76,192 … 180,4,38).
  const ends: [Parameters<typeof colormapTable>[0], number[], number[]][] = [
    ['viridis', [0x44, 0x01, 0x54], [0xfd, 0xe7, 0x25]],
    ['coolwarm', [59, 76, 192], [180, 4, 38]],
    ['hot', [10.6, 0, 0], [255, 255, 255]],
  ];
  for (const [name, first, last] of ends) {
    it(`${name}: RGBA rows from the first to the last published colour`, () => {
      const t = colormapTable(name);
      const n = t.length / 4;
      expect(n).toBeGreaterThanOrEqual(33);
      for (let c = 0; c < 3; c++) {
        expect(Math.abs(t[c] * 255 - first[c])).toBeLessThan(0.6);
        expect(Math.abs(t[4 * (n - 1) + c] * 255 - last[c])).toBeLessThan(0.6);
      }
      for (let i = 0; i < n; i++) expect(t[4 * i + 3]).toBe(1);
    });
  }
});
