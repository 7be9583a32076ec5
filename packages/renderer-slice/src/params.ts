import {
  checkNumber,
  checkNumbers,
  validateParams,
  VptError,
  type NumberRule,
  type ParamSpec,
  type ParamSpecs,
} from '@vpt/core';
import { COLORMAP_NAMES, type ColormapName } from './colormaps.js';

/** 'transfer-function': the scene's 1D transfer function's colour at the windowed value, instead of a named map. */
export type SliceColormap = ColormapName | 'transfer-function';
export type SliceAxis = 'x' | 'y' | 'z';
export type SliceSampling = 'nearest' | 'linear';

export interface SliceParams {
  /** Axis-aligned plane: the index axis it is perpendicular to (default 'z'). */
  axis?: SliceAxis;
  /** Axis-aligned plane through the centres of this voxel layer along `axis` (default: the middle one, ⌊n/2⌋). */
  index?: number;
  /** Axis-aligned plane at this world coordinate along `axis` (box centred at 0, longest side 1); instead of `index`. */
  position?: number;
  /** Oblique plane: its normal (world directions; need not be unit length). Excludes axis/index/position. */
  normal?: [number, number, number];
  /** Oblique plane: a world point on it (default the box centre [0, 0, 0]). Only with `normal`. */
  point?: [number, number, number];
  /** 'nearest' (the voxel that holds the point, default) or 'linear' (the cell-centred trilinear filter). */
  sampling?: SliceSampling;
  /** [center, width] in data units (HU for CT); default: the volume's value range (its normalized value). */
  window?: [number, number];
  /** The colour map of the windowed value (default 'grey'). */
  colormap?: SliceColormap;
  /** Fill the image with the slice (one pixel per texel when the image size equals the slice's); else draw it in 3D under the camera. */
  fit?: boolean;
}

/**
 * One row per parameter: the single place the slice renderer's parameters are defined
 * (validation spec, user-interface label and range, default in words). The uniforms are
 * not one per parameter: the plane and the window become `planeOrigin`/`planeU`/`planeV`/
 * `planeNormal` and `windowScale`/`windowOffset` (slice-renderer.ts, from plane.ts and
 * window-mapping.ts), the choices become kernel variants (`features()`).
 */
export interface SliceParamRow {
  name: keyof SliceParams;
  label: string;
  spec: ParamSpec;
  /** The default, in words (shown next to an empty field). */
  defaultText: string;
  /** The default value where it is one value (enums, booleans). */
  defaultValue?: string | boolean;
}

const AXES: readonly SliceAxis[] = ['x', 'y', 'z'];
const SAMPLINGS: readonly SliceSampling[] = ['nearest', 'linear'];
export const SLICE_COLORMAPS: readonly SliceColormap[] = [...COLORMAP_NAMES, 'transfer-function'];

/** Voxel layers are counted from 0; the upper bound depends on the volume (SliceRenderer.validateScene). */
const INDEX_RULE: NumberRule = { min: 0, integer: true, unit: 'voxels along the axis' };
/** Scene coordinates are bounded like the camera's (the box has a longest side of 1). */
const COORDINATE_RULE: NumberRule = { min: -1e4, max: 1e4, unit: 'world units' };

export const SLICE_PARAM_TABLE: readonly SliceParamRow[] = [
  { name: 'axis', label: 'Axis', spec: { kind: 'enum', values: AXES }, defaultText: 'z', defaultValue: 'z' },
  { name: 'index', label: 'Slice index', spec: { kind: 'number', ...INDEX_RULE }, defaultText: 'the middle slice' },
  { name: 'position', label: 'Position', spec: { kind: 'number', ...COORDINATE_RULE }, defaultText: 'from index' },
  { name: 'normal', label: 'Normal', spec: { kind: 'custom' }, defaultText: 'axis-aligned' },
  { name: 'point', label: 'Point', spec: { kind: 'custom' }, defaultText: 'the box centre' },
  {
    name: 'sampling',
    label: 'Sampling',
    spec: { kind: 'enum', values: SAMPLINGS },
    defaultText: 'nearest',
    defaultValue: 'nearest',
  },
  { name: 'window', label: 'Window [center, width]', spec: { kind: 'custom' }, defaultText: 'the value range' },
  {
    name: 'colormap',
    label: 'Colour map',
    spec: { kind: 'enum', values: SLICE_COLORMAPS },
    defaultText: 'grey',
    defaultValue: 'grey',
  },
  { name: 'fit', label: 'Fit to image', spec: { kind: 'boolean' }, defaultText: 'off', defaultValue: false },
];

/** The slice renderer's parameter specs (core's validateParams), derived from SLICE_PARAM_TABLE. */
export const SLICE_PARAM_SPECS: ParamSpecs = Object.fromEntries(SLICE_PARAM_TABLE.map((r) => [r.name, r.spec]));

/** The owner named in error messages: `SLICE.window[1]: …`. */
export const SLICE_OWNER = 'SLICE';

function fail(field: string, message: string): never {
  throw new VptError('invalid-scene', `${field}: ${message}`);
}

/** The parameters with defaults filled in and the plane resolved to one of its two forms. */
export interface ResolvedSliceParams {
  plane:
    | { kind: 'axis'; axis: SliceAxis; index: number | null; position: number | null }
    | { kind: 'oblique'; normal: [number, number, number]; point: [number, number, number] };
  sampling: SliceSampling;
  window: [number, number] | null;
  colormap: SliceColormap;
  fit: boolean;
}

/**
 * Every scene-independent rule: the declared specs (unknown keys, enums, ranges), then the
 * vectors and the combinations. Throws VptError('invalid-scene') naming `SLICE.<field>`.
 */
export function resolveSliceParams(params: SliceParams): ResolvedSliceParams {
  validateParams(SLICE_OWNER, SLICE_PARAM_SPECS, params ?? {});
  const p = params ?? {};
  const field = (k: keyof SliceParams) => `${SLICE_OWNER}.${k}`;
  let window: [number, number] | null = null;
  if (p.window !== undefined) {
    const [center, width] = checkNumbers(field('window'), p.window, 2);
    checkNumber(`${field('window')}[1]`, width, { min: 0, exclusiveMin: true, unit: 'the width, in data units' });
    window = [center, width];
  }
  const sampling = p.sampling ?? 'nearest';
  const colormap = p.colormap ?? 'grey';
  const fit = p.fit ?? false;
  if (p.normal === undefined) {
    if (p.point !== undefined)
      fail(field('point'), 'needs "normal" (an oblique plane); an axis-aligned plane takes "position"');
    if (p.index !== undefined && p.position !== undefined)
      fail(field('position'), 'give "index" or "position", not both');
    return {
      plane: { kind: 'axis', axis: p.axis ?? 'z', index: p.index ?? null, position: p.position ?? null },
      sampling,
      window,
      colormap,
      fit,
    };
  }
  for (const k of ['axis', 'index', 'position'] as const) {
    if (p[k] !== undefined) fail(field(k), 'is for an axis-aligned plane; an oblique plane takes "normal" and "point"');
  }
  const normal = checkNumbers(field('normal'), p.normal, 3, COORDINATE_RULE) as [number, number, number];
  const length = Math.hypot(...normal);
  if (!(length > 1e-6)) fail(field('normal'), `must have a length above 1e-6, got ${JSON.stringify(p.normal)}`);
  const point = (p.point === undefined ? [0, 0, 0] : checkNumbers(field('point'), p.point, 3, COORDINATE_RULE)) as [
    number,
    number,
    number,
  ];
  return {
    plane: { kind: 'oblique', normal: normal.map((c) => c / length) as [number, number, number], point },
    sampling,
    window,
    colormap,
    fit,
  };
}
