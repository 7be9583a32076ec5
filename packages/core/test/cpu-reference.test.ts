import { describe, expect, it } from 'vitest';
import { createVolume, reference, type Scene, type Vec3 } from '../src/index.js';

describe('PCG hash (CPU twin of the kernels RNG)', () => {
  // Independent re-implementation with BigInt arithmetic modulo 2^32, following
  // Jarzynski & Olano 2020's listing; the kernel twin must match it exactly.
  const M = 0xffffffffn;
  function pcgBig(v: number): number {
    const state = (BigInt(v) * 747796405n + 2891336453n) & M;
    const word = (((state >> ((state >> 28n) + 4n)) ^ state) * 277803737n) & M;
    return Number(((word >> 22n) ^ word) & M);
  }
  it('matches a BigInt implementation over many inputs', () => {
    for (const v of [0, 1, 2, 0x7fffffff, 0x80000000, 0xffffffff, 123456789, 42])
      expect(reference.pcgHash(v)).toBe(pcgBig(v));
    for (let i = 0; i < 2000; i++) {
      const v = (i * 2654435761) >>> 0;
      expect(reference.pcgHash(v)).toBe(pcgBig(v));
    }
  });
  it('streams uniform numbers in [0, 1) with the right mean', () => {
    let sum = 0;
    const n = 20000;
    for (let i = 0; i < n; i++) {
      const x = new reference.CpuRng(i % 97, Math.floor(i / 97), 3, 7).next();
      expect(x).toBeGreaterThanOrEqual(0);
      expect(x).toBeLessThan(1);
      sum += x;
    }
    expect(Math.abs(sum / n - 0.5)).toBeLessThan(4 * Math.sqrt(1 / 12 / n));
  });
});

/**
 * The CPU twins (camera ray, box intersection, trilinear sampler) feed both the GPU kernels'
 * expected images and the CPU references of the tests; a convention error shared by both
 * would go unseen. These pin each convention to a closed form, independent of the code.
 */
describe('CPU twin conventions against closed forms', () => {
  const scene = (position: Vec3, fovy: number) =>
    ({ camera: { position, target: [0, 0, 0] as Vec3, up: [0, 1, 0] as Vec3, fovy } }) as Scene;

  it('camera ray: the film centre looks at the target, film (0,0) is the top-left corner at the half field of view, y down', () => {
    const s = scene([0, 0, 3], 2 * Math.atan(0.5)); // tan(fovy/2) = 0.5
    const centre = reference.cameraRay(s, 4, 4, 0.5, 0.5);
    expect(centre.origin).toEqual([0, 0, 3]);
    for (let a = 0; a < 3; a++) expect(centre.dir[a]).toBeCloseTo([0, 0, -1][a], 14);
    // Top-left film corner of a 2:1 image: x = −tan·aspect = −1, y = +tan = +0.5 at unit distance.
    const corner = reference.cameraRay(s, 8, 4, 0, 0).dir;
    const l = Math.hypot(1, 0.5, 1);
    for (let a = 0; a < 3; a++) expect(corner[a]).toBeCloseTo([-1 / l, 0.5 / l, -1 / l][a], 14);
    // The ray through the centre of pixel (0, 0) of a 2×2 image hits the plane z = 0 at (−tan/2, +tan/2)·3.
    const p = reference.cameraRay(s, 2, 2, 0.25, 0.25);
    const t = 3 / -p.dir[2];
    expect(p.origin[0] + t * p.dir[0]).toBeCloseTo(-0.75, 12);
    expect(p.origin[1] + t * p.dir[1]).toBeCloseTo(0.75, 12);
  });

  it('box intersection: chord lengths of an axis ray, a diagonal ray, a ray from inside and a miss', () => {
    const min: Vec3 = [-0.5, -0.25, -0.5],
      max: Vec3 = [0.5, 0.25, 0.5];
    expect(reference.intersectBox([0, 0, 2], [0, 0, -1], min, max)).toEqual([1.5, 2.5]);
    const d = 1 / Math.sqrt(3);
    const [t0, t1] = reference.intersectBox([-1, -1, -1], [d, d, d], [-0.5, -0.5, -0.5], [0.5, 0.5, 0.5]);
    expect(t1 - t0).toBeCloseTo(Math.sqrt(3), 12); // the cube's space diagonal
    expect(t0).toBeCloseTo(Math.sqrt(3) / 2, 12);
    expect(reference.intersectBox([0, 0, 0], [1, 0, 0], min, max)).toEqual([0, 0.5]); // from inside: tNear clamps to 0
    const miss = reference.intersectBox([0, 1, 2], [0, 0, -1], min, max); // passes above the slab
    expect(miss[0]).toBeGreaterThan(miss[1]);
  });

  it('trilinear sampling is exact on a linear ramp (cell-centred voxels, clamped half a voxel from the faces)', () => {
    // value(i, j, k) = (i + 2j + 3k) / 36 at voxel centres; the box is [−0.5, 0.5]·(6, 4, 2)/6.
    const dims: [number, number, number] = [6, 4, 2];
    const data = new Float32Array(48).map(
      (_, n) => ((n % 6) + 2 * (Math.floor(n / 6) % 4) + 3 * Math.floor(n / 24)) / 36,
    );
    const volume = createVolume(dims, 'float32', data);
    volume.valueRange = [0, 1];
    const sampler = new reference.CpuVolumeSampler({ volume });
    const h = 1 / 6; // voxel edge in world units (longest side 1)
    expect(sampler.box.min).toEqual([-0.5, -2 * h, -h]);
    // Voxel coordinate g = (p − min)/h − ½ per axis; inside the centres the sample is the ramp at g.
    const ramp = (g: number[]) => (g[0] + 2 * g[1] + 3 * g[2]) / 36;
    for (const g of [
      [0, 0, 0],
      [2.5, 1.25, 0.5],
      [4.9, 2.1, 0.3],
      [5, 3, 1],
      [1.75, 0.5, 0.99],
    ]) {
      const p = g.map((x, a) => sampler.box.min[a] + (x + 0.5) * h) as Vec3;
      expect(sampler.sample(p)).toBeCloseTo(ramp(g), 6);
    }
    // Between a face and the outermost centre the value is clamped (constant), not extrapolated.
    const face = [sampler.box.min[0] + 0.2 * h, sampler.box.min[1] + 1.5 * h, sampler.box.min[2] + 0.5 * h] as Vec3;
    expect(sampler.sample(face)).toBeCloseTo(ramp([0, 1, 0]), 6);
  });
});
