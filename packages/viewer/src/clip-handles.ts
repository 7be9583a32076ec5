/**
 * Handles on the image for the axis clip planes (clip-model.ts): each plane's handle sits
 * where the centre of its cut face (the point `position` along its axis) appears, and
 * dragging it moves the plane along its axis by the drag's component along the axis's
 * on-screen direction. The projection is the kernels' camera (reference/ cameraRay: vertical
 * fovy, the image's aspect), in fractions of the image (0..1, top row first).
 */
import { cameraBasis, type Camera } from '@vpt/core';
import { CLIP_AXES, type ClipAxis, type Vec3 } from './clip-model.js';

/** Where a world point appears, in fractions of the image (null: behind the camera). */
export function projectPoint(camera: Camera, aspect: number, p: readonly number[]): { x: number; y: number } | null {
  const b = cameraBasis(camera);
  const v = [0, 1, 2].map((i) => p[i] - camera.position[i]);
  const dot = (a: readonly number[]) => a[0] * v[0] + a[1] * v[1] + a[2] * v[2];
  const z = dot(b.forward);
  if (!(z > 1e-6)) return null;
  const t = Math.tan(camera.fovy / 2);
  return { x: (dot(b.right) / (z * t * aspect) + 1) / 2, y: (1 - dot(b.up) / (z * t)) / 2 };
}

/** The point at `position` on `axis` (the centre of that plane's cut face in the box centred at 0). */
export function axisPoint(axis: ClipAxis, position: number): Vec3 {
  const p: Vec3 = [0, 0, 0];
  p[CLIP_AXES.indexOf(axis)] = position;
  return p;
}

/**
 * The plane position after a drag of (dx, dy) fractions of the image (width, height) that
 * started at `position`: the drag's component along the axis's on-screen direction, in world
 * units, clamped to [min, max]. An axis that points (nearly) at the camera does not move.
 */
export function draggedPosition(
  camera: Camera,
  aspect: number,
  axis: ClipAxis,
  position: number,
  drag: { dx: number; dy: number },
  range: { min: number; max: number },
): number {
  const eps = 1e-3;
  const a = projectPoint(camera, aspect, axisPoint(axis, position));
  const b = projectPoint(camera, aspect, axisPoint(axis, position + eps));
  if (!a || !b) return position;
  // Screen movement per world unit along the axis, measured in the image's aspect (pixels alike in x and y).
  const sx = ((b.x - a.x) / eps) * aspect,
    sy = (b.y - a.y) / eps;
  const len2 = sx * sx + sy * sy;
  if (len2 < 1e-4) return position;
  const delta = (drag.dx * aspect * sx + drag.dy * sy) / len2;
  return Math.min(range.max, Math.max(range.min, position + delta));
}
