/**
 * The slice renderer described as data (core's RendererDescriptor): its parameters, their
 * rules and defaults, and how its output is shown. Side-effect free and kernel free, so user
 * interfaces import it alone (`@vpt/renderer-slice/descriptor`).
 *
 * The plane and the window are not one uniform per parameter: they become `planeOrigin`/
 * `planeU`/`planeV`/`planeNormal` (core's slice-geometry.ts) and `windowScale`/`windowOffset`
 * (core's slice-window.ts) in slice-renderer.ts; the choices become kernel variants (`features()`).
 */
import {
  COLORMAP_NAMES,
  checkNumber,
  checkNumbers,
  defineRenderer,
  paramSpecsOf,
  validateParams,
  VptError,
  type ColormapName,
  type NumberRule,
  type ParamsOf,
  type SliceAxis,
  type SlicePlaneSpec,
} from '@vpt/core';

export type { SliceAxis };
/** 'transfer-function': the scene's 1D transfer function's colour at the windowed value, instead of a named map. */
export type SliceColormap = ColormapName | 'transfer-function';
export type SliceSampling = 'nearest' | 'linear';
type Vec3 = [number, number, number];

const AXES: readonly SliceAxis[] = ['x', 'y', 'z'];
const SAMPLINGS: readonly SliceSampling[] = ['nearest', 'linear'];
export const SLICE_COLORMAPS: readonly SliceColormap[] = [...COLORMAP_NAMES, 'transfer-function'];

/** Voxel layers are counted from 0; the upper bound depends on the volume (SliceRenderer.validateScene). */
const INDEX_RULE: NumberRule = { min: 0, integer: true, unit: 'voxels along the axis' };
/** Scene coordinates are bounded like the camera's (the box has a longest side of 1). */
const COORDINATE_RULE: NumberRule = { min: -1e4, max: 1e4, unit: 'world units' };

/** The owner named in error messages: `SLICE.window[1]: …`. */
export const SLICE_OWNER = 'SLICE';

/** A parameter checked by the descriptor's `check` (a vector), of type T, with no constant default. */
const vector = <T>(defaultText: string) => ({
  kind: 'custom' as const,
  default: undefined as T | undefined,
  defaultText,
});

export const SLICE_DESCRIPTOR = defineRenderer({
  name: 'slice',
  label: 'Slice',
  owner: SLICE_OWNER,
  params: {
    /** Axis-aligned plane: the index axis it is perpendicular to (default 'z'). */
    axis: { kind: 'enum', values: AXES, default: 'z' },
    /**
     * Axis-aligned plane through the centres of this voxel layer along `axis` (default: the
     * middle one, ⌊n/2⌋, of the volume's layers along the axis). Offered without a
     * placeholder: its default depends on the volume and the axis.
     */
    index: { kind: 'number', ...INDEX_RULE, ui: { label: 'Slice index', step: 1, max: 2047 } },
    /** Axis-aligned plane at this world coordinate along `axis` (box centred at 0, longest side 1); instead of `index`. */
    position: { kind: 'number', ...COORDINATE_RULE, defaultText: 'from index' },
    /** Oblique plane: its normal (world directions; need not be unit length). Excludes axis/index/position. */
    normal: vector<Vec3>('axis-aligned'),
    /** Oblique plane: a world point on it (default the box centre [0, 0, 0]). Only with `normal`. */
    point: vector<Vec3>('the box centre'),
    /** 'nearest' (the voxel that holds the point, default) or 'linear' (the cell-centred trilinear filter). */
    sampling: { kind: 'enum', values: SAMPLINGS, default: 'nearest', ui: { label: 'Sampling' } },
    /** [center, width] in data units (HU for CT); default: the volume's value range (its normalized value). */
    window: vector<[number, number]>('the value range'),
    /** The colour map of the windowed value (default 'grey'). */
    colormap: { kind: 'enum', values: SLICE_COLORMAPS, default: 'grey', ui: { label: 'Colour map' } },
    /** Fill the image with the slice (one pixel per texel when the image size equals the slice's); else draw it in 3D under the camera. */
    fit: { kind: 'boolean', default: false, ui: { label: 'Fit to image' } },
  },
  check: (p) => void resolveChecked(p as SliceParams),
  // Every iteration renders the same image: no guides, nothing for a denoiser to do.
  writesGuides: false,
  // Its HDR output is the windowed, colour-mapped value in [0, 1]: shown as it is, never tone-mapped.
  displayReferred: true,
  needs: { transferFunction: true, lights: false, environment: false },
  look: { densityScale: 20, environment: [0, 0, 0] },
});

export type SliceParams = ParamsOf<typeof SLICE_DESCRIPTOR>;

/** The package's descriptor under the name every renderer package uses (the generated loaders read it). */
export { SLICE_DESCRIPTOR as descriptor };

/** The parameters with defaults filled in and the plane resolved to one of its two forms. */
export interface ResolvedSliceParams {
  plane: SlicePlaneSpec;
  sampling: SliceSampling;
  window: [number, number] | null;
  colormap: SliceColormap;
  fit: boolean;
}

function fail(field: string, message: string): never {
  throw new VptError('invalid-scene', `${field}: ${message}`);
}

/**
 * Every scene-independent rule: the declared specs (unknown keys, enums, ranges), then the
 * vectors and the combinations. Throws VptError('invalid-scene') naming `SLICE.<field>`.
 */
export function resolveSliceParams(params: SliceParams): ResolvedSliceParams {
  validateParams(SLICE_OWNER, paramSpecsOf(SLICE_DESCRIPTOR), params ?? {});
  return resolveChecked(params ?? {});
}

/** The vectors and the combinations of parameters that passed the declared specs (the descriptor's `check`). */
function resolveChecked(p: SliceParams): ResolvedSliceParams {
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
  const normal = checkNumbers(field('normal'), p.normal, 3, COORDINATE_RULE) as Vec3;
  const length = Math.hypot(...normal);
  if (!(length > 1e-6)) fail(field('normal'), `must have a length above 1e-6, got ${JSON.stringify(p.normal)}`);
  const point = (p.point === undefined ? [0, 0, 0] : checkNumbers(field('point'), p.point, 3, COORDINATE_RULE)) as Vec3;
  return {
    plane: { kind: 'oblique', normal: normal.map((c) => c / length) as Vec3, point },
    sampling,
    window,
    colormap,
    fit,
  };
}
