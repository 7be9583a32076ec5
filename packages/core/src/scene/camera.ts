import { VptError } from '../errors.js';
import { FLOAT32_MAX, MAX_CAMERA_COORDINATE } from '../validation/limits.js';

export type Vec3 = [number, number, number];

/** A pinhole camera; fovy is the full vertical field of view in radians (docs/design.md). */
export interface Camera {
  position: Vec3;
  target: Vec3;
  up: Vec3;
  fovy: number;
}

export const sub = (a: Vec3, b: Vec3): Vec3 => [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
export const dot = (a: Vec3, b: Vec3) => a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
export const cross = (a: Vec3, b: Vec3): Vec3 => [
  a[1] * b[2] - a[2] * b[1],
  a[2] * b[0] - a[0] * b[2],
  a[0] * b[1] - a[1] * b[0],
];
export const normalize = (a: Vec3): Vec3 => {
  const l = Math.hypot(a[0], a[1], a[2]);
  return [a[0] / l, a[1] / l, a[2] / l];
};

/** Orthonormal basis: f = normalize(target - position), r = normalize(f × up), u = r × f. */
export function cameraBasis(c: Camera): { forward: Vec3; right: Vec3; up: Vec3 } {
  const forward = normalize(sub(c.target, c.position));
  const right = normalize(cross(forward, c.up));
  return { forward, right, up: cross(right, forward) };
}

export function validateCamera(c: Camera): void {
  const bad = (msg: string) => {
    throw new VptError('invalid-scene', `Camera: ${msg}`);
  };
  if (!c || typeof c !== 'object') bad('missing');
  for (const key of ['position', 'target', 'up'] as const) {
    const v = c[key];
    if (!Array.isArray(v) || v.length !== 3 || !v.every((x) => typeof x === 'number' && Number.isFinite(x)))
      bad(`${key} must be three finite numbers, got ${JSON.stringify(v)}`);
    // A coordinate finite in float64 but not in float32 would reach the kernels as Infinity;
    // far positions lose the box to float32 rounding (MAX_CAMERA_COORDINATE).
    const limit = key === 'up' ? FLOAT32_MAX : MAX_CAMERA_COORDINATE;
    v.forEach((x, i) => {
      if (Math.abs(x) > limit)
        bad(
          `${key}[${i}] = ${x} exceeds the limit ±${limit}${key === 'up' ? ' (float32 range)' : ' (MAX_CAMERA_COORDINATE: the box has a longest side of 1; float32 ray arithmetic loses it further out)'}`,
        );
    });
  }
  if (typeof c.fovy !== 'number' || !Number.isFinite(c.fovy) || c.fovy <= 0 || c.fovy >= Math.PI)
    bad(`fovy must be in (0, π) radians, got ${c.fovy}`);
  const f = sub(c.target, c.position);
  if (Math.hypot(...f) < 1e-9) bad('position and target coincide');
  const side = cross(normalize(f), c.up);
  if (Math.hypot(...side) < 1e-6) bad('up is parallel to the view direction (or zero)');
}

export function defaultCamera(): Camera {
  return { position: [0, 0, 2], target: [0, 0, 0], up: [0, 1, 0], fovy: (40 * Math.PI) / 180 };
}
