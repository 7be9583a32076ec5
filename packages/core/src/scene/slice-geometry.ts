import { VptError } from '../errors.js';
import type { Vec3 } from './camera.js';
import { volumeBox, type Volume } from './volume.js';

export type SliceAxis = 'x' | 'y' | 'z';

/**
 * A plane through the volume, resolved: axis-aligned (through the centres of voxel layer
 * `index`, default the middle one, or at world coordinate `position` along the axis) or oblique
 * (unit `normal` through `point`).
 */
export type SlicePlaneSpec =
  | { kind: 'axis'; axis: SliceAxis; index: number | null; position: number | null }
  | { kind: 'oblique'; normal: Vec3; point: Vec3 };

/**
 * The slice's plane in world coordinates (the volume's box, centred at 0, longest side 1):
 * p(s, t) = origin + u·s + v·t for s, t ∈ [0, 1] spans the bounding rectangle of the plane's
 * cut through the box (what `fit` stretches over the image: s along the columns, t down the
 * rows); `normal` is the unit normal. Computed in float64 on the CPU, once per scene.
 */
export interface SlicePlane {
  origin: Vec3;
  u: Vec3;
  v: Vec3;
  normal: Vec3;
}

const AXIS_INDEX: Readonly<Record<SliceAxis, 0 | 1 | 2>> = { x: 0, y: 1, z: 2 };
/**
 * Image axes of the slice perpendicular to each index axis: (columns, rows). The usual
 * axial/coronal/sagittal convention of index space: z → (x, y), y → (x, z), x → (y, z), row 0
 * at the lowest index. An oblique plane takes the pair of its normal's dominant axis.
 */
const IMAGE_AXES: Readonly<Record<0 | 1 | 2, readonly [number, number]>> = { 0: [1, 2], 1: [0, 2], 2: [0, 1] };

type Box = ReturnType<typeof volumeBox>;

const dot = (a: readonly number[], b: readonly number[]) => a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
const axpy = (a: readonly number[], s: number, b: readonly number[]): Vec3 => [
  a[0] + s * b[0],
  a[1] + s * b[1],
  a[2] + s * b[2],
];
const unit = (i: number): Vec3 => [i === 0 ? 1 : 0, i === 1 ? 1 : 0, i === 2 ? 1 : 0];
const normalize = (a: Vec3): Vec3 => {
  const l = Math.hypot(...a);
  return [a[0] / l, a[1] / l, a[2] / l];
};

function fail(owner: string, field: string, message: string): never {
  throw new VptError('invalid-scene', `${owner}.${field}: ${message}`);
}

/**
 * The plane of resolved parameters for a volume; throws VptError('invalid-scene') naming the
 * field when it does not fit this volume (an index past its last layer, a position outside
 * its box, an oblique plane that misses the box or only touches it).
 */
export function slicePlane(
  plane: SlicePlaneSpec,
  volume: Pick<Volume, 'dims' | 'spacing'>,
  owner = 'SLICE',
): SlicePlane {
  const box = volumeBox(volume);
  if (plane.kind === 'axis') {
    const a = AXIS_INDEX[plane.axis];
    const n = volume.dims[a];
    let c: number;
    if (plane.position !== null) {
      if (!(plane.position >= box.min[a] && plane.position <= box.max[a]))
        fail(
          owner,
          'position',
          `${plane.position} is outside the volume's box along ${plane.axis}: [${box.min[a]}, ${box.max[a]}] world units`,
        );
      c = plane.position;
    } else {
      const index = plane.index ?? Math.floor(n / 2);
      if (index > n - 1)
        fail(
          owner,
          'index',
          `${index} is past the last of the volume's ${n} layers along ${plane.axis} (0 to ${n - 1})`,
        );
      // Through the centres of voxel layer `index` (cell-centred: layer i spans [i, i + 1] voxels).
      c = box.min[a] + ((index + 0.5) * box.size[a]) / n;
    }
    const point: Vec3 = [0, 0, 0];
    point[a] = c;
    return planeThroughBox(point, unit(a), a, box, owner, 'position');
  }
  const n = plane.normal;
  const dominant = [0, 1, 2].reduce((m, i) => (Math.abs(n[i]) > Math.abs(n[m]) ? i : m), 0) as 0 | 1 | 2;
  return planeThroughBox(plane.point, n, dominant, box, owner, 'point');
}

/**
 * Basis and extent of the plane (point, unit normal) inside the box: in-plane axes by
 * Gram–Schmidt from the image axes of `dominant` (so an axis-aligned plane gets exactly those
 * axes), extent from the vertices where the box's 12 edges cross the plane.
 */
function planeThroughBox(
  point: Vec3,
  normal: Vec3,
  dominant: 0 | 1 | 2,
  box: Box,
  owner: string,
  field: string,
): SlicePlane {
  const [col, row] = IMAGE_AXES[dominant];
  const ec = unit(col),
    er = unit(row);
  const u = normalize(axpy(ec, -dot(normal, ec), normal));
  const v = normalize(axpy(axpy(er, -dot(normal, er), normal), -dot(u, er), u));
  const corner = (i: number): Vec3 => [0, 1, 2].map((k) => ((i >> k) & 1 ? box.max[k] : box.min[k])) as Vec3;
  const distance = (c: Vec3) => dot([c[0] - point[0], c[1] - point[1], c[2] - point[2]], normal);
  const vertices: Vec3[] = [];
  for (let i = 0; i < 8; i++) {
    const c0 = corner(i),
      d0 = distance(c0);
    if (d0 === 0) vertices.push(c0);
    for (let k = 0; k < 3; k++) {
      if ((i >> k) & 1) continue; // each edge once: from the corner with bit k clear
      const c1 = corner(i | (1 << k)),
        d1 = distance(c1);
      if ((d0 < 0 && d1 > 0) || (d0 > 0 && d1 < 0)) {
        const f = d0 / (d0 - d1);
        vertices.push([c0[0] + (c1[0] - c0[0]) * f, c0[1] + (c1[1] - c0[1]) * f, c0[2] + (c1[2] - c0[2]) * f]);
      }
    }
  }
  const along = (axis: Vec3) => vertices.map((p) => dot([p[0] - point[0], p[1] - point[1], p[2] - point[2]], axis));
  const su = along(u),
    sv = along(v);
  const [u0, u1, v0, v1] = [Math.min(...su), Math.max(...su), Math.min(...sv), Math.max(...sv)];
  if (!(vertices.length >= 3 && u1 > u0 && v1 > v0))
    fail(
      owner,
      field,
      `the plane through [${point.join(', ')}] with normal [${normal.map((x) => +x.toFixed(6)).join(', ')}] does not cut the volume's box [${box.min.join(', ')}]..[${box.max.join(', ')}]`,
    );
  const origin = axpy(axpy(point, u0, u), v0, v);
  return { origin, u: u.map((x) => x * (u1 - u0)) as Vec3, v: v.map((x) => x * (v1 - v0)) as Vec3, normal };
}
