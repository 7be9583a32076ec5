import { orientationFromAxisCodes, volumeBox, type Camera, type Volume } from '@vpt/core';
import { DEFAULT_FOVY } from './attributes.js';

type Vec3 = [number, number, number];

/** Direction the default camera looks from when the data carries no orientation: front-right, a little above (+y up). */
const DEFAULT_DIRECTION: Vec3 = [0.55, 0.35, 1];

/** What a volume may say about its orientation (@vpt/loaders' LoadedVolume, or a sidecar's axes). */
export interface OrientedVolume extends Pick<Volume, 'dims' | 'spacing'> {
  /** 3×3 row-major direction cosines: columns are the world directions of the index axes. */
  orientation?: readonly number[];
  meta?: { space?: unknown; axisCodes?: unknown } | Record<string, unknown>;
}

/** Anatomical directions in the volume's own (index) frame, each snapped to the nearest axis. */
export interface AnatomicalFrame {
  superior: Vec3;
  anterior: Vec3;
  right: Vec3;
}

/** The index axis (with sign) a direction runs closest to. */
function snap(v: Vec3): Vec3 {
  let best = 0;
  for (let i = 1; i < 3; i++) if (Math.abs(v[i]) > Math.abs(v[best])) best = i;
  const out: Vec3 = [0, 0, 0];
  out[best] = v[best] >= 0 ? 1 : -1;
  return out;
}

/**
 * Superior, anterior and right in the volume's frame, from its orientation (NIfTI, NRRD,
 * DICOM through @vpt/loaders) or its axis codes (a sidecar's `axes`); null when it has
 * neither. The world S, A, R axes map back to index space through the transpose of the
 * (orthonormal) orientation: row r of the matrix is world axis r seen from the volume.
 */
export function anatomicalFrame(volume: OrientedVolume): AnatomicalFrame | null {
  const meta = (volume.meta ?? {}) as { space?: unknown; axisCodes?: unknown };
  let o: readonly number[] | null = volume.orientation && volume.orientation.length === 9 ? volume.orientation : null;
  let space = meta.space === 'LPS' ? 'LPS' : 'RAS';
  if (!o && typeof meta.axisCodes === 'string') {
    o = orientationFromAxisCodes(meta.axisCodes);
    space = 'RAS';
  }
  if (!o || !o.every(Number.isFinite)) return null;
  // LPS: world x is left and y posterior, so right and anterior are their negatives; S is +z in both.
  const k = space === 'LPS' ? -1 : 1;
  const right = snap([k * o[0], k * o[1], k * o[2]]);
  const anterior = snap([k * o[3], k * o[4], k * o[5]]);
  const superior = snap([o[6], o[7], o[8]]);
  const axis = (v: Vec3) => v.findIndex((x) => x !== 0);
  if (new Set([axis(right), axis(anterior), axis(superior)]).size !== 3) return null; // too oblique to snap
  return { superior, anterior, right };
}

/**
 * A camera that frames the whole volume box (its bounding sphere fits the vertical field
 * of view). With an orientation the view is from the front-right, a little above, with
 * superior up; without one, from +z/+x/+y with +y up.
 */
export function fitCamera(volume: OrientedVolume, fovy = DEFAULT_FOVY): Camera {
  const { size } = volumeBox(volume);
  const radius = Math.hypot(size[0], size[1], size[2]) / 2;
  const distance = (1.05 * radius) / Math.sin(fovy / 2);
  const frame = anatomicalFrame(volume);
  let dir: Vec3 = DEFAULT_DIRECTION;
  let up: Vec3 = [0, 1, 0];
  if (frame) {
    const { anterior: a, right: r, superior: s } = frame;
    dir = [0, 1, 2].map((i) => a[i] + 0.55 * r[i] + 0.35 * s[i]) as Vec3;
    up = [...s];
  }
  const len = Math.hypot(dir[0], dir[1], dir[2]);
  const position = dir.map((d) => Math.round((d / len) * distance * 1e6) / 1e6) as Camera['position'];
  return { position, target: [0, 0, 0], up, fovy };
}
