/**
 * CPU twins of the shared shader chunks (shaders/common.glsl.ts), in float64 except
 * where the kernel's integer arithmetic must be reproduced exactly (the PCG hash).
 * Tests use them to compute the image a kernel should produce, sample for sample.
 */
import { cameraBasis, type Vec3 } from '../scene/camera.js';
import type { Scene } from '../scene/scene.js';
import { normalizationRange, volumeBox } from '../scene/volume.js';

export function pcgHash(v: number): number {
  const state = (Math.imul(v >>> 0, 747796405) + 2891336453) >>> 0;
  const word = Math.imul(((state >>> (((state >>> 28) + 4) >>> 0)) ^ state) >>> 0, 277803737) >>> 0;
  return ((word >>> 22) ^ word) >>> 0;
}

export class CpuRng {
  state: number;
  constructor(px: number, py: number, iteration: number, seed: number) {
    this.state = pcgHash((px + pcgHash((py + pcgHash((iteration + pcgHash(seed)) >>> 0)) >>> 0)) >>> 0);
  }
  next(): number {
    this.state = pcgHash(this.state);
    return (this.state >>> 8) / 16777216;
  }
}

export function intersectBox(o: Vec3, d: Vec3, min: Vec3, max: Vec3): [number, number] {
  let tNear = 0,
    tFar = Infinity;
  for (let a = 0; a < 3; a++) {
    const inv = (d[a] < 0 ? -1 : 1) / Math.max(Math.abs(d[a]), 1e-20);
    const t0 = (min[a] - o[a]) * inv,
      t1 = (max[a] - o[a]) * inv;
    tNear = Math.max(tNear, Math.min(t0, t1));
    tFar = Math.min(tFar, Math.max(t0, t1));
  }
  return [tNear, tFar];
}

/** The ray through film point (fx, fy) ∈ [0,1]², y down (docs/design.md camera convention). */
export function cameraRay(
  scene: Scene,
  width: number,
  height: number,
  fx: number,
  fy: number,
): { origin: Vec3; dir: Vec3 } {
  const b = cameraBasis(scene.camera);
  const t = Math.tan(scene.camera.fovy / 2);
  const sx = (2 * fx - 1) * t * (width / height),
    sy = (1 - 2 * fy) * t;
  const d: Vec3 = [0, 1, 2].map((i) => b.forward[i] + b.right[i] * sx + b.up[i] * sy) as Vec3;
  const l = Math.hypot(...d);
  return { origin: scene.camera.position, dir: [d[0] / l, d[1] / l, d[2] / l] };
}

/** CPU twin of the kernels' jitteredCameraRay (shaders/common): a uniform point inside pixel (x, y), two numbers drawn from `rng`. */
export function jitteredCameraRay(
  scene: Scene,
  width: number,
  height: number,
  x: number,
  y: number,
  rng: CpuRng,
): { origin: Vec3; dir: Vec3 } {
  const jx = rng.next(),
    jy = rng.next();
  return cameraRay(scene, width, height, (x + jx) / width, (y + jy) / height);
}

/**
 * Cell-centred trilinear sampling with clamp-to-edge, in world coordinates, of the data
 * mapped by the value range (LO → 0, HI → 1; LO > HI inverts) and then clamped to [0, 1],
 * as the kernels do (gpu/volume-format.ts: the clamp follows the filter). Non-finite voxels read as 0.
 */
export class CpuVolumeSampler {
  readonly data: Float32Array;
  readonly dims: [number, number, number];
  readonly box: ReturnType<typeof volumeBox>;
  constructor(scene: Pick<Scene, 'volume'>) {
    const [lo, hi] = normalizationRange(scene.volume);
    const src = scene.volume.data;
    this.data = new Float32Array(src.length);
    for (let i = 0; i < src.length; i++) {
      const x = (src[i] - lo) / (hi - lo);
      this.data[i] = Number.isFinite(x) ? x : 0;
    }
    this.dims = scene.volume.dims;
    this.box = volumeBox(scene.volume);
  }
  sample(p: Vec3): number {
    const [nx, ny, nz] = this.dims;
    const g = [0, 1, 2].map((a) => ((p[a] - this.box.min[a]) / this.box.size[a]) * this.dims[a] - 0.5);
    const g0 = g.map(Math.floor);
    const f = g.map((x, a) => x - g0[a]);
    const cl = (i: number, n: number) => Math.min(n - 1, Math.max(0, i));
    const x0 = cl(g0[0], nx),
      x1 = cl(g0[0] + 1, nx),
      y0 = cl(g0[1], ny),
      y1 = cl(g0[1] + 1, ny),
      z0 = cl(g0[2], nz),
      z1 = cl(g0[2] + 1, nz);
    const at = (x: number, y: number, z: number) => this.data[x + nx * (y + ny * z)];
    const l = (a: number, b: number, t: number) => a + (b - a) * t;
    const c00 = l(at(x0, y0, z0), at(x1, y0, z0), f[0]);
    const c10 = l(at(x0, y1, z0), at(x1, y1, z0), f[0]);
    const c01 = l(at(x0, y0, z1), at(x1, y0, z1), f[0]);
    const c11 = l(at(x0, y1, z1), at(x1, y1, z1), f[0]);
    return Math.min(1, Math.max(0, l(l(c00, c10, f[1]), l(c01, c11, f[1]), f[2])));
  }
}
