/**
 * The label under the pointer, on the CPU (the Labels hover readout, labels-layer.ts): the
 * pixel's camera ray (core's reference cameraRay: the kernels' pinhole, vertical fovy, the
 * image's aspect) walked voxel by voxel through the label volume (Amanatides & Woo 1987, "A
 * fast voxel traversal algorithm") to the first voxel of a visible non-zero label; for the
 * slice renderer, the voxel of its plane under the pixel. Pure: no DOM, no GPU.
 */
import {
  cameraBasis,
  isClippedPoint,
  volumeBox,
  type Camera,
  type Clip,
  type LabelEntry,
  type SliceAxis,
  type SlicePlane,
  type Vec3,
  type Volume,
} from '@vpt/core';

/** What the pick found: the label id and the voxel holding it ([i, j, k]). */
export interface LabelHit {
  id: number;
  voxel: [number, number, number];
}

/** Per id 1 when the table draws it (listed, visible, opacity above 0), as the kernels' table texture does. */
export function visibleIds(table: readonly LabelEntry[], type: Volume['type']): Uint8Array {
  const out = new Uint8Array(type === 'uint8' ? 256 : 65536);
  for (const e of table)
    if (e.id > 0 && e.id < out.length && e.visible !== false && (e.opacity ?? 1) > 0) out[e.id] = 1;
  return out;
}

/** The ray through film point (fx, fy) ∈ [0, 1]², y down: reference/cpu-reference.ts cameraRay, restated for an aspect. */
export function pixelRay(camera: Camera, aspect: number, fx: number, fy: number): { origin: Vec3; dir: Vec3 } {
  const b = cameraBasis(camera);
  const t = Math.tan(camera.fovy / 2);
  const sx = (2 * fx - 1) * t * aspect,
    sy = (1 - 2 * fy) * t;
  const d = [0, 1, 2].map((i) => b.forward[i] + b.right[i] * sx + b.up[i] * sy);
  const l = Math.hypot(d[0], d[1], d[2]);
  return { origin: camera.position, dir: [d[0] / l, d[1] / l, d[2] / l] };
}

/**
 * The first voxel along the ray (origin + t·dir, t ≥ 0) whose id `visible` marks, skipping
 * voxels whose midpoint on the ray the clip removes; null when the ray meets none.
 */
export function pickLabelOnRay(
  volume: Volume,
  visible: Uint8Array,
  origin: readonly number[],
  dir: readonly number[],
  clip?: Clip | null,
): LabelHit | null {
  const { min, size } = volumeBox(volume);
  const n = volume.dims;
  let t0 = 0,
    t1 = Infinity;
  for (let a = 0; a < 3; a++) {
    if (Math.abs(dir[a]) < 1e-12) {
      if (origin[a] < min[a] || origin[a] > min[a] + size[a]) return null;
      continue;
    }
    const ta = (min[a] - origin[a]) / dir[a],
      tb = (min[a] + size[a] - origin[a]) / dir[a];
    t0 = Math.max(t0, Math.min(ta, tb));
    t1 = Math.min(t1, Math.max(ta, tb));
  }
  if (!(t0 < t1)) return null;
  const h = [0, 1, 2].map((a) => size[a] / n[a]);
  const start = [0, 1, 2].map((a) => origin[a] + dir[a] * t0);
  const cell = [0, 1, 2].map((a) => Math.min(n[a] - 1, Math.max(0, Math.floor((start[a] - min[a]) / h[a]))));
  const step = [0, 1, 2].map((a) => (dir[a] > 0 ? 1 : dir[a] < 0 ? -1 : 0));
  const tMax = [0, 1, 2].map((a) =>
    step[a] === 0 ? Infinity : (min[a] + (cell[a] + (step[a] > 0 ? 1 : 0)) * h[a] - origin[a]) / dir[a],
  );
  const tDelta = [0, 1, 2].map((a) => (step[a] === 0 ? Infinity : h[a] / Math.abs(dir[a])));
  let t = t0;
  for (;;) {
    const a = tMax[0] < tMax[1] ? (tMax[0] < tMax[2] ? 0 : 2) : tMax[1] < tMax[2] ? 1 : 2;
    const tNext = Math.min(tMax[a], t1);
    const id = volume.data[cell[0] + n[0] * (cell[1] + n[1] * cell[2])];
    if (id > 0 && visible[id]) {
      const tm = (t + tNext) / 2;
      if (
        !clip ||
        !isClippedPoint(
          clip,
          [0, 1, 2].map((i) => origin[i] + dir[i] * tm),
        )
      )
        return { id, voxel: [cell[0], cell[1], cell[2]] };
    }
    if (tMax[a] >= t1) return null;
    cell[a] += step[a];
    if (cell[a] < 0 || cell[a] >= n[a]) return null;
    t = tMax[a];
    tMax[a] += tDelta[a];
  }
}

/** The label the pixel (fx, fy) of a camera image sees first: pickLabelOnRay along its pinhole ray. */
export function pickLabel(
  volume: Volume,
  visible: Uint8Array,
  camera: Camera,
  aspect: number,
  fx: number,
  fy: number,
  clip?: Clip | null,
): LabelHit | null {
  const { origin, dir } = pixelRay(camera, aspect, fx, fy);
  return pickLabelOnRay(volume, visible, origin, dir, clip);
}

/** The voxel holding world point p, or null outside the box (a hair of tolerance for points on a face). */
export function voxelOf(
  volume: Pick<Volume, 'dims' | 'spacing'>,
  p: readonly number[],
): [number, number, number] | null {
  const { min, size } = volumeBox(volume);
  const out: number[] = [];
  for (let a = 0; a < 3; a++) {
    const f = (p[a] - min[a]) / size[a];
    if (!(f >= -1e-9 && f <= 1 + 1e-9)) return null;
    out.push(Math.min(volume.dims[a] - 1, Math.max(0, Math.floor(f * volume.dims[a]))));
  }
  return out as [number, number, number];
}

/**
 * The slice renderer's point under pixel (fx, fy): with `fit` the plane's rectangle stretched
 * over the image (p(s, t) = origin + u·s + v·t, s = fx, t = fy), else where the pixel's camera
 * ray meets the plane (null when parallel, behind the camera or outside the box).
 */
export function slicePointAt(
  plane: SlicePlane,
  fit: boolean,
  camera: Camera,
  aspect: number,
  fx: number,
  fy: number,
): Vec3 | null {
  if (fit) return [0, 1, 2].map((i) => plane.origin[i] + plane.u[i] * fx + plane.v[i] * fy) as Vec3;
  const { origin, dir } = pixelRay(camera, aspect, fx, fy);
  const nd = plane.normal[0] * dir[0] + plane.normal[1] * dir[1] + plane.normal[2] * dir[2];
  if (Math.abs(nd) < 1e-12) return null;
  const t = [0, 1, 2].reduce((s, i) => s + plane.normal[i] * (plane.origin[i] - origin[i]), 0) / nd;
  if (!(t > 0)) return null;
  return [0, 1, 2].map((i) => origin[i] + dir[i] * t) as Vec3;
}

/**
 * The slice renderer's plane from its parameters (renderer-slice's resolveSliceParams, the
 * defaults restated: this module must not load the renderer): `normal` + `point` (default
 * the box centre), else `axis` (default z) at `index` or `position`.
 */
export function sliceSpecOf(
  p: Record<string, unknown>,
):
  | { kind: 'axis'; axis: SliceAxis; index: number | null; position: number | null }
  | { kind: 'oblique'; normal: Vec3; point: Vec3 } {
  if (Array.isArray(p.normal)) {
    const n = p.normal as number[];
    const l = Math.hypot(n[0], n[1], n[2]) || 1;
    return {
      kind: 'oblique',
      normal: [n[0] / l, n[1] / l, n[2] / l],
      point: Array.isArray(p.point) ? (p.point as Vec3) : [0, 0, 0],
    };
  }
  return {
    kind: 'axis',
    axis: (p.axis as SliceAxis | undefined) ?? 'z',
    index: typeof p.index === 'number' ? p.index : null,
    position: typeof p.position === 'number' ? p.position : null,
  };
}
