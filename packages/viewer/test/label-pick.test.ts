import { describe, expect, it } from 'vitest';
import { createVolume, reference, volumeBox, type Camera, type Volume } from '@vpt/core';
import { pickLabel, pickLabelOnRay, pixelRay, slicePointAt, visibleIds, voxelOf } from '../src/label-pick.js';
import { seededRandom as mulberry32 } from '../../../tests/helpers/seeded-random.js';

// The hover pick (label-pick.ts): the voxel walk against a brute-force march of tiny steps, the
// pinhole ray against core's reference camera ray, hidden labels and the clip skipped.

/** The first visible id along the ray by marching 1e-4 world units at a time (floor of the box coordinate). */
function marched(v: Volume, visible: Uint8Array, o: number[], d: number[]): number {
  const { min, max, size } = volumeBox(v);
  const [t0, t1] = reference.intersectBox(o as never, d as never, min, max);
  for (let t = t0 + 5e-5; t < t1; t += 1e-4) {
    const idx = [0, 1, 2].map((a) =>
      Math.min(v.dims[a] - 1, Math.max(0, Math.floor(((o[a] + d[a] * t - min[a]) / size[a]) * v.dims[a]))),
    );
    const id = v.data[idx[0] + v.dims[0] * (idx[1] + v.dims[1] * idx[2])];
    if (id && visible[id]) return id;
  }
  return 0;
}

function randomLabels(dims: [number, number, number], spacing: [number, number, number], seed: number): Volume {
  const rnd = mulberry32(seed);
  const data = new Uint8Array(dims[0] * dims[1] * dims[2]);
  // Sparse: most voxels background, so rays cross several before a hit.
  for (let i = 0; i < data.length; i++) data[i] = rnd() < 0.08 ? 1 + Math.floor(rnd() * 4) : 0;
  return createVolume(dims, 'uint8', data, spacing);
}

describe('label pick', () => {
  it('finds the first visible label on a ray as a fine march does, hidden labels passed through', () => {
    const v = randomLabels([7, 5, 9], [1, 1.5, 0.7], 3);
    const table = [1, 2, 3, 4].map((id) => ({ id, visible: id !== 2 }));
    const visible = visibleIds(table, 'uint8');
    const rnd = mulberry32(11);
    let hits = 0,
      compared = 0;
    for (let k = 0; k < 300; k++) {
      const o = [0, 1, 2].map(() => (rnd() - 0.5) * 3);
      const target = [0, 1, 2].map(() => (rnd() - 0.5) * 0.8);
      const d0 = target.map((x, i) => x - o[i]);
      const l = Math.hypot(...d0);
      const d = d0.map((x) => x / l);
      const got = pickLabelOnRay(v, visible, o, d);
      const want = marched(v, visible, o, d);
      // A ray grazing a voxel corner within the march's step may differ: skip those (rare).
      if ((got?.id ?? 0) !== want) {
        const again = marched(
          v,
          visible,
          o.map((x, i) => x + d[i] * 1e-5),
          d,
        );
        if ((got?.id ?? 0) !== again) expect(got?.id ?? 0).toBe(want);
      }
      compared++;
      if (got) {
        hits++;
        expect(got.id).not.toBe(2);
        expect(v.data[got.voxel[0] + 7 * (got.voxel[1] + 5 * got.voxel[2])]).toBe(got.id);
      }
    }
    expect(compared).toBe(300);
    expect(hits).toBeGreaterThan(50);
    expect(hits).toBeLessThan(300);
  });

  it('reports the nearest of two labels on a column, the farther one when the nearer is hidden or clipped, none on a miss', () => {
    const data = new Uint8Array(64);
    // Column x = 1, y = 2 (4³ box centred at 0): id 5 at z index 2, id 7 at z index 1.
    data[1 + 4 * (2 + 4 * 2)] = 5;
    data[1 + 4 * (2 + 4 * 1)] = 7;
    const v = createVolume([4, 4, 4], 'uint8', data, [1, 1, 1]);
    const o = [-0.5 + 1.5 / 4, -0.5 + 2.5 / 4, 2];
    const d = [0, 0, -1];
    const all = visibleIds(
      [
        { id: 5, name: 'a' },
        { id: 7, name: 'b' },
      ],
      'uint8',
    );
    expect(pickLabelOnRay(v, all, o, d)).toEqual({ id: 5, voxel: [1, 2, 2] });
    const no5 = visibleIds([{ id: 5, visible: false }, { id: 7 }], 'uint8');
    expect(pickLabelOnRay(v, no5, o, d)).toEqual({ id: 7, voxel: [1, 2, 1] });
    // Opacity 0 draws nothing either.
    expect(pickLabelOnRay(v, visibleIds([{ id: 5, opacity: 0 }, { id: 7 }], 'uint8'), o, d)?.id).toBe(7);
    // A clip removing z > 0 (index 2 and 3) leaves id 7.
    expect(pickLabelOnRay(v, all, o, d, { planes: [{ normal: [0, 0, 1], offset: 0 }] })?.id).toBe(7);
    expect(pickLabelOnRay(v, all, [o[0] + 0.25, o[1], o[2]], d)).toBeNull();
    expect(pickLabelOnRay(v, all, [2, 2, 2], d)).toBeNull();
  });

  it("casts the kernels' camera ray (core's reference cameraRay) and picks through it", () => {
    const camera: Camera = { position: [0.3, 0.4, 2], target: [0, 0, 0], up: [0, 1, 0], fovy: 0.7 };
    for (const [fx, fy] of [
      [0.5, 0.5],
      [0.1, 0.9],
      [0.77, 0.2],
    ]) {
      const mine = pixelRay(camera, 1.5, fx, fy);
      const ref = reference.cameraRay({ camera } as never, 48, 32, fx, fy);
      mine.dir.forEach((x, i) => expect(x).toBeCloseTo(ref.dir[i], 12));
    }
    const data = new Uint8Array(8).fill(3);
    const v = createVolume([2, 2, 2], 'uint8', data, [1, 1, 1]);
    const vis = visibleIds([{ id: 3 }], 'uint8');
    expect(pickLabel(v, vis, camera, 1, 0.5, 0.5)?.id).toBe(3);
    expect(pickLabel(v, vis, camera, 1, 0.01, 0.01)).toBeNull();
  });

  it("finds the slice renderer's point: the stretched rectangle with fit, the ray's meeting with the plane without", () => {
    const plane = {
      origin: [-0.5, -0.5, 0] as [number, number, number],
      u: [1, 0, 0] as [number, number, number],
      v: [0, 1, 0] as [number, number, number],
      normal: [0, 0, 1] as [number, number, number],
    };
    const camera: Camera = { position: [0.1, 0, 2], target: [0, 0, 0], up: [0, 1, 0], fovy: 0.6 };
    expect(slicePointAt(plane, true, camera, 1, 0.25, 0.75)).toEqual([-0.25, 0.25, 0]);
    const p = slicePointAt(plane, false, camera, 1, 0.3, 0.6)!;
    expect(p[2]).toBeCloseTo(0, 12);
    const r = pixelRay(camera, 1, 0.3, 0.6);
    const t = (p[0] - r.origin[0]) / r.dir[0];
    expect(p[1]).toBeCloseTo(r.origin[1] + r.dir[1] * t, 12);
    expect(voxelOf({ dims: [4, 4, 4], spacing: [1, 1, 1] }, [-0.25, 0.25, 0])).toEqual([1, 3, 2]);
    expect(voxelOf({ dims: [4, 4, 4], spacing: [1, 1, 1] }, [0.6, 0, 0])).toBeNull();
  });
});
