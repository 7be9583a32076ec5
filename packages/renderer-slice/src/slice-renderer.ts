import {
  BaseRenderer,
  checkedWindowCoefficients,
  colormapTable,
  COPY_ACCUMULATION_RENDER,
  RUNNING_MEAN_INTEGRATE,
  paramSpecsOf,
  slicePlane,
  volumeRange,
  VptError,
  type AuxiliaryTexture,
  type ParamSpecs,
  type Scene,
  type UniformField,
  type UniformValues,
  type Volume,
  channelNormalizationRange,
  enabledChannels,
} from '@vpt/core';
import * as glsl from './kernels/slice.glsl.js';
import * as wgsl from './kernels/slice.wgsl.js';
import {
  resolveSliceParams,
  SLICE_DESCRIPTOR,
  SLICE_OWNER,
  type ResolvedSliceParams,
  type SliceParams,
} from './descriptor.js';

const channelRanges = new WeakMap<object, [number, number]>();
/** The data range of what the slice shows: the volume's, or a channel scene's first drawn channel's (memoized per channel list). */
function shownRange(scene: Scene): [number, number] {
  if (!scene.channels) return volumeRange(scene.volume);
  let r = channelRanges.get(scene.channels);
  if (!r) {
    const first = enabledChannels(scene.channels)[0];
    r = channelNormalizationRange(scene.volume, first, scene.channels[first]);
    channelRanges.set(scene.channels, r);
  }
  return r;
}

/** The slice renderer's parameter specs (core's validateParams), from its descriptor. */
export const SLICE_PARAM_SPECS: ParamSpecs = paramSpecsOf(SLICE_DESCRIPTOR);

/** The slice's uniforms, after the scene's (SCENE_UNIFORM_FIELDS): the plane (core's slice-geometry.ts) and the window (slice-window.ts). */
export const SLICE_UNIFORM_FIELDS: readonly UniformField[] = [
  { name: 'planeOrigin', type: 'vec3' },
  { name: 'windowScale', type: 'f32' },
  { name: 'planeU', type: 'vec3' },
  { name: 'windowOffset', type: 'f32' },
  { name: 'planeV', type: 'vec3' },
  { name: 'planeNormal', type: 'vec3' },
];

/** A plane no pixel meets: in fit mode every point is the origin, outside the box; under the camera no ray meets a zero normal. */
const NOTHING_DRAWN: UniformValues = {
  planeOrigin: [2e4, 2e4, 2e4],
  planeU: [0, 0, 0],
  planeV: [0, 0, 0],
  planeNormal: [0, 0, 0],
  windowScale: 1,
  windowOffset: 0,
};

/**
 * A slice through the volume: a plane (axis-aligned by axis + index or position, or oblique
 * by normal + point), sampled nearest or linear, windowed in data units and colour-mapped.
 * HDR output: the colour-mapped windowed value in [0, 1] (grey: the value itself; a named map:
 * its published sRGB components), a = 1 on the slice and 0 elsewhere. Every iteration renders
 * the same image, so the estimate is final after one.
 */
export class SliceRenderer extends BaseRenderer<SliceParams> {
  readonly name = SLICE_DESCRIPTOR.name;
  readonly writesGuides = SLICE_DESCRIPTOR.writesGuides;
  /** Lays a scene's label colours over the slice (core's scene/labels.ts) under VPT_LABELS. */
  readonly drawsLabels = true;
  readonly frameFormats = ['rgba32float'] as const;
  readonly accumulationFormats = ['rgba32float'] as const;
  readonly kernels = {
    generate: { glsl: glsl.generate, wgsl: wgsl.generate },
    integrate: RUNNING_MEAN_INTEGRATE,
    render: COPY_ACCUMULATION_RENDER,
  };
  readonly paramFields = SLICE_UNIFORM_FIELDS;
  private resolved: ResolvedSliceParams;
  /**
   * What setParams checks the plane and the window against: the last validated volume's shape and
   * value range (not the volume itself, which this renderer must not keep alive).
   */
  private shape: VolumeShape | null = null;
  /** The error of the last paramValues() whose scene the plane or window did not fit. */
  private problem: string | null = null;

  constructor(params: SliceParams = {}) {
    const resolved = resolveSliceParams(params);
    super(params, SLICE_PARAM_SPECS, SLICE_DESCRIPTOR.owner);
    this.resolved = resolved;
  }

  /** Merge and validate new parameters (VptError 'invalid-scene' naming the field, nothing changed); resets accumulation. */
  override setParams(params: Partial<SliceParams>): void {
    const resolved = resolveSliceParams({ ...this.getParams(), ...params });
    if (this.shape) checkForShape(resolved, this.shape);
    super.setParams(params);
    this.resolved = resolved;
  }

  /** The parameters with defaults filled in. */
  get resolvedParams(): ResolvedSliceParams {
    return structuredClone(this.resolved);
  }

  /**
   * Scene-dependent rules, run by RenderContext.setScene: the plane must cut this volume's box,
   * the window must be finite in float32 against its value range, 'transfer-function' needs a 1D one.
   */
  validateScene(scene: Scene): void {
    const shape = shapeOf(scene.volume);
    checkForShape(this.resolved, shape);
    if (this.resolved.colormap === 'transfer-function' && scene.transferFunction.dimensions !== '1d') {
      throw new VptError(
        'invalid-scene',
        `${SLICE_OWNER}.colormap: "transfer-function" reads a 1D transfer function; the scene's is ${scene.transferFunction.dimensions}`,
      );
    }
    this.shape = shape;
  }

  override features(_scene: Scene): Record<string, boolean | number> {
    const c = this.resolved.colormap;
    return {
      FIT: this.resolved.fit,
      NEAREST: this.resolved.sampling === 'nearest',
      COLOR_TF: c === 'transfer-function',
      COLOR_TABLE: c !== 'grey' && c !== 'transfer-function',
    };
  }

  paramValues(scene: Scene): UniformValues {
    try {
      const plane = slicePlane(this.resolved.plane, scene.volume);
      const window = checkedWindowCoefficients(shownRange(scene), this.resolved.window);
      this.problem = null;
      return { planeOrigin: plane.origin, planeU: plane.u, planeV: plane.v, planeNormal: plane.normal, ...window };
    } catch (e) {
      if (!(e instanceof VptError)) throw e;
      // Only for a scene these parameters were never validated against (RenderContext.setRenderer
      // keeps the scene it has, and setScene is what runs validateScene): draw nothing rather than
      // stop the render loop with an exception, and say why in stats().
      this.problem = e.message;
      return NOTHING_DRAWN;
    }
  }

  /** Why nothing is drawn, when the parameters do not fit the scene being rendered (else nothing to report). */
  stats(): Record<string, string> {
    return this.problem ? { slice: `nothing drawn: ${this.problem}` } : {};
  }

  /** The named colour map's table (core's colormaps.ts), uploaded once per map. */
  auxiliaryTextures(_scene: Scene): readonly AuxiliaryTexture[] {
    const c = this.resolved.colormap;
    if (c === 'grey' || c === 'transfer-function') return [];
    return [
      {
        name: 'colormap',
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
}

/** What the scene-dependent rules read of a volume. */
interface VolumeShape {
  dims: Volume['dims'];
  spacing: Volume['spacing'];
  range: [number, number];
}

function shapeOf(volume: Volume): VolumeShape {
  return { dims: [...volume.dims], spacing: [...volume.spacing], range: volumeRange(volume) };
}

/** The rules that need the volume: the plane (core's slice-geometry.ts) and the window's float32 range (slice-window.ts). */
function checkForShape(p: ResolvedSliceParams, shape: VolumeShape): void {
  slicePlane(p.plane, shape);
  checkedWindowCoefficients(shape.range, p.window);
}
