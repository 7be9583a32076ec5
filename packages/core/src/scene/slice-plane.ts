import type { AuxiliaryTexture } from '../renderer.js';
import type { UniformField, UniformValues } from '../uniforms/layout.js';
import { checkKnownKeys, checkNumber, checkNumbers, checkObject, checkOneOf, fail } from '../validation/checks.js';
import type { Vec3 } from './camera.js';
import { COLORMAP_NAMES, colormapTable, type ColormapName } from './colormaps.js';
import { slicePlane, type SliceAxis, type SlicePlaneSpec } from './slice-geometry.js';
import { checkedWindowCoefficients, volumeRange } from './slice-window.js';
import type { Volume } from './volume.js';

/**
 * A slice shown inside the 3D view ("slice in 3D"): an opaque plane through the volume that the
 * ray-marching and path-tracing renderers draw as an unlit surface. A camera ray ends at the
 * plane, and the plane's windowed, colour-mapped value is the colour there, composited behind
 * what lies in front. The plane, the window (in data units) and the colour maps are the slice
 * renderer's own definitions (slice-geometry.ts, slice-window.ts, colormaps.ts).
 */
export interface SceneSlicePlane {
  /** Axis-aligned plane: the index axis it is perpendicular to (default 'z'). */
  axis?: SliceAxis;
  /** Through the centres of this voxel layer along `axis` (default the middle one). */
  index?: number;
  /** At this world coordinate along `axis`, instead of `index`. */
  position?: number;
  /** Oblique plane: its normal (need not be unit length); excludes axis/index/position. */
  normal?: Vec3;
  /** Oblique plane: a world point on it (default the box centre). */
  point?: Vec3;
  /** [center, width] in data units; default the volume's value range. */
  window?: [number, number];
  /** 'grey' (default) or a named colour map. */
  colormap?: ColormapName;
  /** 'nearest' (the voxel holding the point, default) or 'linear' (the shared trilinear filter). */
  sampling?: 'nearest' | 'linear';
}

export interface ResolvedSlicePlane {
  plane: SlicePlaneSpec;
  window: [number, number] | null;
  colormap: ColormapName;
  sampling: 'nearest' | 'linear';
}

const COORDINATE = { min: -1e4, max: 1e4, unit: 'world units' };
const KEYS = ['axis', 'index', 'position', 'normal', 'point', 'window', 'colormap', 'sampling'];

/** The scene-independent rules of a `slicePlane`, with its defaults; errors name the field. */
export function resolveSlicePlane(value: unknown, field = 'Scene: slicePlane'): ResolvedSlicePlane {
  const s = checkObject(field, value);
  checkKnownKeys(field, s, KEYS);
  const f = (k: string) => `${field}.${k}`;
  let window: [number, number] | null = null;
  if (s.window !== undefined) {
    const [center, width] = checkNumbers(f('window'), s.window, 2);
    checkNumber(`${f('window')}[1]`, width, { min: 0, exclusiveMin: true, unit: 'the width, in data units' });
    window = [center, width];
  }
  const colormap = (
    s.colormap === undefined ? 'grey' : checkOneOf(f('colormap'), s.colormap, COLORMAP_NAMES)
  ) as ColormapName;
  const sampling = (
    s.sampling === undefined ? 'nearest' : checkOneOf(f('sampling'), s.sampling, ['nearest', 'linear'] as const)
  ) as 'nearest' | 'linear';
  if (s.normal === undefined) {
    if (s.point !== undefined)
      fail(f('point'), 'needs "normal" (an oblique plane); an axis-aligned plane takes "position"');
    if (s.index !== undefined && s.position !== undefined) fail(f('position'), 'give "index" or "position", not both');
    const axis = (s.axis === undefined ? 'z' : checkOneOf(f('axis'), s.axis, ['x', 'y', 'z'] as const)) as SliceAxis;
    const index =
      s.index === undefined ? null : checkNumber(f('index'), s.index, { min: 0, integer: true, unit: 'voxels' });
    const position = s.position === undefined ? null : checkNumber(f('position'), s.position, COORDINATE);
    return { plane: { kind: 'axis', axis, index, position }, window, colormap, sampling };
  }
  for (const k of ['axis', 'index', 'position'])
    if (s[k] !== undefined) fail(f(k), 'is for an axis-aligned plane; an oblique plane takes "normal" and "point"');
  const n = checkNumbers(f('normal'), s.normal, 3, COORDINATE);
  const length = Math.hypot(...n);
  if (!(length > 1e-6)) fail(f('normal'), `must have a length above 1e-6, got [${n.join(', ')}]`);
  const point = (s.point === undefined ? [0, 0, 0] : checkNumbers(f('point'), s.point, 3, COORDINATE)) as Vec3;
  return {
    plane: { kind: 'oblique', normal: n.map((c) => c / length) as Vec3, point },
    window,
    colormap,
    sampling,
  };
}

/**
 * Every rule of a scene's `slicePlane`, the volume's included: the plane must cut the box and
 * the window must be finite in float32 against the value range (the slice renderer's rules).
 */
export function validateSlicePlane(value: unknown, volume: Volume, field = 'Scene: slicePlane'): ResolvedSlicePlane {
  const r = resolveSlicePlane(value, field);
  slicePlane(r.plane, volume, field);
  checkedWindowCoefficients(volumeRange(volume), r.window, `${field}.window`);
  return r;
}

/**
 * The slice plane's uniforms (only in the layout of a variant compiled with VPT_SLICE_PLANE,
 * after the clip's, so a layout without it is unchanged): the plane as dot(normal, p) = offset
 * and the window as the affine map of the normalized value (slice-window.ts).
 */
export const SLICE_PLANE_UNIFORM_FIELDS: readonly UniformField[] = [
  { name: 'slicePlaneNormal', type: 'vec3' },
  { name: 'slicePlaneOffset', type: 'f32' },
  { name: 'slicePlaneWindow', type: 'vec2' },
];

export function slicePlaneUniformValues(value: SceneSlicePlane, volume: Volume): UniformValues {
  const r = resolveSlicePlane(value);
  const p = slicePlane(r.plane, volume, 'Scene: slicePlane');
  const w = checkedWindowCoefficients(volumeRange(volume), r.window, 'Scene: slicePlane.window');
  const n = p.normal;
  return {
    slicePlaneNormal: n,
    slicePlaneOffset: n[0] * p.origin[0] + n[1] * p.origin[1] + n[2] * p.origin[2],
    slicePlaneWindow: [w.windowScale, w.windowOffset],
  };
}

/** The kernel flags of a slice plane (the shared chunk's SLICE_PLANE_NEAREST, SLICE_PLANE_TABLE). */
export function slicePlaneFlags(value: SceneSlicePlane): { nearest: boolean; table: boolean } {
  const r = resolveSlicePlane(value);
  return { nearest: r.sampling === 'nearest', table: r.colormap !== 'grey' };
}

/** The named colour map's table as the auxiliary texture `slicePlaneColormap` (none for grey). */
export function slicePlaneTextures(value: SceneSlicePlane): AuxiliaryTexture[] {
  const c = resolveSlicePlane(value).colormap;
  if (c === 'grey') return [];
  return [
    {
      name: 'slicePlaneColormap',
      dimension: '2d',
      key: `colormap ${c}`,
      create: () => {
        const data = colormapTable(c);
        return {
          dimension: '2d',
          width: data.length / 4,
          height: 1,
          format: 'rgba32float',
          data,
          label: `colormap ${c}`,
        };
      },
    },
  ];
}
