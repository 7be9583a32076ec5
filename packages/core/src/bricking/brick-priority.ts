/**
 * Which bricks the current view needs, in the order they should be loaded: every brick of
 * the coarsest level (so every region is served by something), then, level by level towards
 * level 0, the bricks inside the view frustum — and with level of detail, only those whose
 * coarser level is not fine enough: a level-l voxel projected at the brick's nearest
 * distance spans more than `pixelsPerVoxel` pixels — nearest first; then the bricks outside
 * the frustum (MCRT's scattered paths and ISO's shadow rays see them), coarse first. The
 * cache loads this list from the front as far as its slots go.
 */
import { cameraBasis, type Camera, type Vec3 } from '../scene/camera.js';
import { volumeBox } from '../scene/volume.js';
import type { BrickGeometry } from './brick-geometry.js';
import type { MultiscaleLevel } from './source.js';

export interface BrickView {
  camera: Camera;
  /** Render size in pixels. */
  width: number;
  height: number;
  /** Level of detail: leave out bricks finer than the pixels need (false: every visible level). */
  lod: boolean;
}

/** Largest projected size of one voxel, in pixels, at which a level is fine enough. */
const PIXELS_PER_VOXEL = 1;

export function brickPriority(geometry: BrickGeometry, level0: MultiscaleLevel, view: BrickView | null): number[] {
  const g = geometry;
  const box = volumeBox(level0);
  const B = g.brickSize;
  const keys: number[] = [];
  const outside: number[] = [];
  const coarsest = g.levels[g.coarsest];
  for (let i = 0; i < coarsest.bricks[0] * coarsest.bricks[1] * coarsest.bricks[2]; i++)
    keys.push(coarsest.firstKey + i);
  const frame = view ? viewFrame(view) : null;
  for (let level = g.coarsest - 1; level >= 0; level--) {
    const l = g.levels[level];
    const inView: { key: number; d: number }[] = [];
    // World size of one voxel of this level, per axis (level-0 box → this level's voxel grid).
    const worldVoxel = [0, 1, 2].map((a) => box.size[a] / level0.dims[a] / l.scale[a]);
    const coarserVoxel = Math.max(...worldVoxel) * 2;
    for (let z = 0; z < l.bricks[2]; z++)
      for (let y = 0; y < l.bricks[1]; y++)
        for (let x = 0; x < l.bricks[0]; x++) {
          const key = g.key(level, [x, y, z]);
          // The brick's world box: its level voxels [b·B, (b+1)·B] back to level-0 voxels, then to the box.
          const lo = [x, y, z].map((b, a) => {
            const x0 = (b * B - l.offset[a]) / l.scale[a];
            return box.min[a] + (Math.max(0, x0) / level0.dims[a]) * box.size[a];
          }) as Vec3;
          const hi = [x, y, z].map((b, a) => {
            const x0 = ((b + 1) * B - l.offset[a]) / l.scale[a];
            return box.min[a] + (Math.min(level0.dims[a], x0) / level0.dims[a]) * box.size[a];
          }) as Vec3;
          if (!frame) {
            keys.push(key);
            continue;
          }
          const d = nearestDistance(frame.position, lo, hi);
          if (!inFrustum(frame, lo, hi)) {
            outside.push(key);
            continue;
          }
          // Level of detail: the coarser level's voxel already projects to at most PIXELS_PER_VOXEL.
          if (view!.lod && coarserVoxel / (Math.max(d, 1e-6) * frame.pixelAngle) <= PIXELS_PER_VOXEL) continue;
          inView.push({ key, d });
        }
    inView.sort((a, b) => a.d - b.d);
    for (const b of inView) keys.push(b.key);
  }
  return keys.concat(outside);
}

interface ViewFrame {
  position: Vec3;
  forward: Vec3;
  right: Vec3;
  up: Vec3;
  tanY: number;
  tanX: number;
  /** Angle subtended by one pixel (radians, small-angle). */
  pixelAngle: number;
}

function viewFrame(v: BrickView): ViewFrame {
  const basis = cameraBasis(v.camera);
  const tanY = Math.tan(v.camera.fovy / 2);
  return {
    position: v.camera.position,
    ...basis,
    tanY,
    tanX: (tanY * v.width) / v.height,
    pixelAngle: (2 * tanY) / v.height,
  };
}

/** False only when all 8 corners lie outside one frustum plane (near, left, right, bottom, top): conservative. */
function inFrustum(f: ViewFrame, lo: Vec3, hi: Vec3): boolean {
  const out = [0, 0, 0, 0, 0];
  for (let c = 0; c < 8; c++) {
    const p = [c & 1 ? hi[0] : lo[0], c & 2 ? hi[1] : lo[1], c & 4 ? hi[2] : lo[2]];
    const r = [p[0] - f.position[0], p[1] - f.position[1], p[2] - f.position[2]];
    const z = r[0] * f.forward[0] + r[1] * f.forward[1] + r[2] * f.forward[2];
    const x = r[0] * f.right[0] + r[1] * f.right[1] + r[2] * f.right[2];
    const y = r[0] * f.up[0] + r[1] * f.up[1] + r[2] * f.up[2];
    if (z < 0) out[0]++;
    if (x > z * f.tanX) out[1]++;
    if (-x > z * f.tanX) out[2]++;
    if (y > z * f.tanY) out[3]++;
    if (-y > z * f.tanY) out[4]++;
  }
  return out.every((n) => n < 8);
}

function nearestDistance(p: Vec3, lo: Vec3, hi: Vec3): number {
  let s = 0;
  for (let a = 0; a < 3; a++) {
    const d = Math.max(lo[a] - p[a], 0, p[a] - hi[a]);
    s += d * d;
  }
  return Math.sqrt(s);
}
