import { checkKnownKeys, checkNumber, checkNumbers, checkObject, countUpTo, fail } from '../validation/checks.js';
import { FLOAT32_MAX, MAX_CLIP_COORDINATE, MAX_CLIP_PLANES } from '../validation/limits.js';
import type { UniformField, UniformValues } from '../uniforms/layout.js';
import { volumeBox } from './volume.js';

type Vec3 = [number, number, number];

/** A clip plane: it removes the points p with dot(normal, p) > offset (world units of the volume box). */
export interface ClipPlane {
  normal: Vec3;
  offset: number;
}

/**
 * What of the volume is cut away: up to MAX_CLIP_PLANES half-spaces and an axis-aligned crop
 * box (points outside it are removed), in world units of the volume box (scene/volume.ts
 * volumeBox: centred at 0, longest side 1). The kept region is convex, so every ray meets it
 * in one interval. In MIP/EAM/ISO the ray interval is cut; in MCRT the removed region is vacuum.
 */
export interface Clip {
  planes?: ClipPlane[];
  box?: { min: Vec3; max: Vec3 };
}

const COORDINATE = { min: -MAX_CLIP_COORDINATE, max: MAX_CLIP_COORDINATE, unit: 'world units; MAX_CLIP_COORDINATE' };

/** Checks a scene's `clip`; errors name the field (`Scene: clip.planes[2].normal: ...`). */
export function validateClip(clip: unknown, field = 'Scene: clip'): void {
  const c = checkObject(field, clip);
  checkKnownKeys(field, c, ['planes', 'box']);
  if (c.planes !== undefined) {
    if (!Array.isArray(c.planes)) fail(`${field}.planes`, 'must be an array of { normal, offset }');
    const planes = c.planes as unknown[];
    checkNumber(`${field}.planes: count`, planes.length, countUpTo(MAX_CLIP_PLANES, 'planes; MAX_CLIP_PLANES', 0));
    planes.forEach((p, i) => {
      const f = `${field}.planes[${i}]`;
      const o = checkObject(f, p);
      checkKnownKeys(f, o, ['normal', 'offset']);
      const n = checkNumbers(`${f}.normal`, o.normal, 3, { min: -FLOAT32_MAX, max: FLOAT32_MAX });
      // The normal is normalized on upload; a (near) zero one has no direction.
      if (!(Math.hypot(...n) >= 1e-9)) fail(`${f}.normal`, `must have a nonzero length, got [${n.join(', ')}]`);
      checkNumber(`${f}.offset`, o.offset, COORDINATE);
    });
  }
  if (c.box !== undefined) {
    const f = `${field}.box`;
    const b = checkObject(f, c.box);
    checkKnownKeys(f, b, ['min', 'max']);
    const lo = checkNumbers(`${f}.min`, b.min, 3, COORDINATE);
    const hi = checkNumbers(`${f}.max`, b.max, 3, COORDINATE);
    for (let i = 0; i < 3; i++) if (!(lo[i] <= hi[i])) fail(`${f}.min[${i}]`, `${lo[i]} must be <= max[${i}] ${hi[i]}`);
  }
}

/** Whether a scene's clip removes anything at all (an empty `{}` or `{ planes: [] }` does not). */
export function hasClip(clip: Clip | undefined): clip is Clip {
  return !!clip && ((clip.planes?.length ?? 0) > 0 || clip.box !== undefined);
}

/**
 * The uniforms of a clipped scene's kernels (only in the layout of a variant compiled with
 * VPT_CLIP, after the renderer's own fields, so an unclipped layout is unchanged): the planes
 * as (unit normal, offset), scaled so the half-space is the same, and the box (the volume's
 * own box where the scene sets none).
 */
export const CLIP_UNIFORM_FIELDS: readonly UniformField[] = [
  { name: 'clipPlanes', type: 'vec4', count: MAX_CLIP_PLANES },
  { name: 'clipBoxMin', type: 'vec3' },
  { name: 'clipPlaneCount', type: 'i32' },
  { name: 'clipBoxMax', type: 'vec3' },
];

export function clipUniformValues(clip: Clip, volume: Parameters<typeof volumeBox>[0]): UniformValues {
  const planes = new Float32Array(4 * MAX_CLIP_PLANES);
  const list = clip.planes ?? [];
  list.forEach((p, i) => {
    const len = Math.hypot(...p.normal);
    planes.set([p.normal[0] / len, p.normal[1] / len, p.normal[2] / len, p.offset / len], 4 * i);
  });
  const box = clip.box ?? volumeBox(volume);
  return { clipPlanes: planes, clipBoxMin: box.min, clipPlaneCount: list.length, clipBoxMax: box.max };
}

/** CPU twin of the kernels' isClipped(p) (common.*.ts CLIP), for tests and reference volumes. */
export function isClippedPoint(clip: Clip, p: readonly number[]): boolean {
  for (const pl of clip.planes ?? []) {
    if (pl.normal[0] * p[0] + pl.normal[1] * p[1] + pl.normal[2] * p[2] > pl.offset) return true;
  }
  const b = clip.box;
  return !!b && [0, 1, 2].some((i) => p[i] < b.min[i] || p[i] > b.max[i]);
}
