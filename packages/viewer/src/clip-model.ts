/**
 * What the Clip panel shows of a scene's `clip` (core's scene/clip.ts) and how its controls
 * write one back: one plane per axis (a position along the axis and a flip), the crop box,
 * and any other planes (oblique ones, or a second plane on an axis), which the panel keeps
 * as they are. Positions are world units of the volume box (centred at 0, longest side 1).
 * Plain data and arithmetic: no DOM, so it is unit-tested in Node.
 */
import { MAX_CLIP_PLANES, type Clip, type ClipPlane } from '@vpt/core';
import { round4 } from './color.js';

export type Vec3 = [number, number, number];
export const CLIP_AXES = ['x', 'y', 'z'] as const;
export type ClipAxis = (typeof CLIP_AXES)[number];

/** One axis plane: unflipped it removes p[axis] > position (keeps the low side); flipped it removes p[axis] < position. */
export interface AxisPlane {
  position: number;
  flip: boolean;
}

export interface ClipControls {
  /** The plane of each axis, or null where that axis has none. */
  axes: Record<ClipAxis, AxisPlane | null>;
  /** The crop box, or null for none. */
  box: { min: Vec3; max: Vec3 } | null;
  /** The planes the panel does not show as an axis plane, kept in their order. */
  others: ClipPlane[];
}

/** The axis a normal lies along (exactly one nonzero component), or -1. */
function axisOf(n: readonly number[]): number {
  const nonzero = [0, 1, 2].filter((i) => n[i] !== 0);
  return nonzero.length === 1 ? nonzero[0] : -1;
}

/** The panel's reading of a clip (null: nothing cut). */
export function clipControls(clip: Clip | null): ClipControls {
  const controls: ClipControls = { axes: { x: null, y: null, z: null }, box: null, others: [] };
  for (const p of clip?.planes ?? []) {
    const a = axisOf(p.normal);
    const axis = a >= 0 ? CLIP_AXES[a] : null;
    if (axis && !controls.axes[axis]) {
      // normal k·e_a removes k·p_a > d, that is p_a > d/k for k > 0 and p_a < d/k for k < 0.
      controls.axes[axis] = { position: p.offset / p.normal[a], flip: p.normal[a] < 0 };
    } else controls.others.push(p);
  }
  if (clip?.box) controls.box = { min: [...clip.box.min], max: [...clip.box.max] };
  return controls;
}

/** The clip the controls describe, or null when they cut nothing (no plane, no box). */
export function clipFromControls(c: ClipControls): Clip | null {
  const planes: ClipPlane[] = c.others.map((p) => ({ normal: [...p.normal], offset: p.offset }));
  CLIP_AXES.forEach((axis, i) => {
    const plane = c.axes[axis];
    if (!plane) return;
    const normal: Vec3 = [0, 0, 0];
    normal[i] = plane.flip ? -1 : 1;
    planes.push({ normal, offset: round4(plane.flip ? -plane.position : plane.position) || 0 });
  });
  const clip: Clip = {};
  if (planes.length) clip.planes = planes;
  if (c.box) clip.box = { min: c.box.min.map(round4) as Vec3, max: c.box.max.map(round4) as Vec3 };
  return clip.planes || clip.box ? clip : null;
}

/** Whether one more axis plane fits (a scene has at most MAX_CLIP_PLANES planes). */
export function canAddPlane(c: ClipControls): boolean {
  const count = c.others.length + CLIP_AXES.filter((a) => c.axes[a]).length;
  return count < MAX_CLIP_PLANES;
}

/**
 * The crop box with one bound moved: the value is clamped into the volume box and so that
 * min <= max stays true (the other bound of that axis does not move).
 */
export function moveBoxBound(
  box: { min: Vec3; max: Vec3 },
  volume: { min: Vec3; max: Vec3 },
  side: 'min' | 'max',
  axis: number,
  value: number,
): { min: Vec3; max: Vec3 } {
  const next = { min: [...box.min] as Vec3, max: [...box.max] as Vec3 };
  const lo = side === 'min' ? volume.min[axis] : box.min[axis];
  const hi = side === 'min' ? box.max[axis] : volume.max[axis];
  next[side][axis] = Math.min(hi, Math.max(lo, value));
  return next;
}
