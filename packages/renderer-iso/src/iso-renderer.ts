import {
  BaseRenderer,
  buildEnvironmentSampling,
  DEFAULT_SKIP_CELL_SIZE,
  environmentEmits,
  environmentTextures,
  GRID_CELLS_FIELD,
  gridGeometry,
  majorantGridTextures,
  paramUniformFields,
  paramUniformValues,
  resolveRendererParams,
  volumeBox,
  VptError,
  type AuxiliaryTexture,
  type LatLongEnvironment,
  type Scene,
  type UniformField,
  type UniformValues,
  type VolumeBinding,
} from '@vpt/core';
import { blueNoiseTexture } from '@vpt/core/blue-noise';
import * as glsl from './kernels/iso.glsl.js';
import * as wgsl from './kernels/iso.wgsl.js';
import { ISO_DESCRIPTOR } from './descriptor.js';
import {
  ISO_PARAM_SPECS,
  MAX_ISO_LIGHTS,
  MAX_ISO_SURFACES,
  resolveIsoParams,
  type IsoParams,
  type ResolvedIsoParams,
} from './params.js';

export const ISO_PARAM_FIELDS: readonly UniformField[] = [
  { name: 'isoValues', type: 'vec4' },
  { name: 'isoSurface', type: 'vec4', count: MAX_ISO_SURFACES },
  { name: 'isoLightDirection', type: 'vec4', count: MAX_ISO_LIGHTS },
  { name: 'isoLightIrradiance', type: 'vec4', count: MAX_ISO_LIGHTS },
  { name: 'gradientStep', type: 'vec3' },
  // stepSize, specular, shininess, aoRadius
  ...paramUniformFields(ISO_DESCRIPTOR),
  { name: 'rayEpsilon', type: 'f32' },
  GRID_CELLS_FIELD,
];

const OUTPUT_CODE = { shaded: 0, depth: 1, normal: 2 } as const;

/**
 * Monte Carlo isosurface renderer (Lesar et al. 2018, ISO), extended with several
 * semi-transparent surfaces, shadows and ambient occlusion. Per iteration the generate
 * pass finds the first crossing along a jittered camera ray (bisection-refined), shades it
 * with one stochastic shadow ray per light and one ambient-occlusion/environment sample,
 * and writes two targets: the shaded sample and the first visible crossing (depth, normal).
 * The accumulation keeps the running mean of the first and the nearest hit of the second
 * (a depth test, as in the paper); the render pass outputs the image or, for `output:
 * 'depth' | 'normal'`, the nearest hit's depth or normal.
 *
 * Lights: the scene's directional lights (at most 4) and its environment (constant or
 * lat-long). The scene's transfer function, 1D or 2D, is not used.
 */
export class IsoRenderer extends BaseRenderer<IsoParams> {
  readonly name = ISO_DESCRIPTOR.name;
  readonly frameFormats = ['rgba32float', 'rgba32float'] as const;
  readonly writesGuides = ISO_DESCRIPTOR.writesGuides;
  /** Draws a scene's slicePlane (core's scene/slice-plane.ts) under VPT_SLICE_PLANE. */
  readonly drawsSlicePlane = true;
  /** Draws a scene's labels (core's scene/labels.ts) under VPT_LABELS: the 0.5 level of the visible labels' mask, in the label's colour. */
  readonly drawsLabels = true;
  readonly accumulationFormats = ['rgba32float', 'rgba32float'] as const;
  readonly kernels = {
    generate: { glsl: glsl.generate, wgsl: wgsl.generate },
    integrate: { glsl: glsl.integrate, wgsl: wgsl.integrate },
    render: { glsl: glsl.render, wgsl: wgsl.render },
  };
  readonly paramFields = ISO_PARAM_FIELDS;
  private resolved: ResolvedIsoParams;

  constructor(params: IsoParams = {}) {
    const resolved = resolveIsoParams(params);
    super(params, ISO_PARAM_SPECS, ISO_DESCRIPTOR.owner);
    this.resolved = resolved;
  }

  /** Merge and validate new parameters (VptError 'invalid-scene' on a bad value, nothing changed); resets accumulation. */
  override setParams(params: Partial<IsoParams>): void {
    const resolved = resolveIsoParams({ ...this.getParams(), ...params });
    super.setParams(params);
    this.resolved = resolved;
  }

  /** The parameters with defaults filled in. */
  get resolvedParams(): ResolvedIsoParams {
    return structuredClone(this.resolved);
  }

  override features(scene: Scene): Record<string, boolean | number> {
    const p = this.resolved;
    if (scene.lights.length > MAX_ISO_LIGHTS) {
      throw new VptError(
        'limit-exceeded',
        `IsoRenderer: the scene has ${scene.lights.length} lights; at most ${MAX_ISO_LIGHTS} directional lights are supported`,
      );
    }
    const env = scene.environment;
    return {
      ISO_COUNT: p.surfaces.length,
      ISO_LIGHTS: scene.lights.length,
      // 0: no environment light (black), 1: constant, 2: lat-long map
      ISO_ENV: !environmentEmits(env) ? 0 : env.type === 'latlong' ? 2 : 1,
      ISO_SHADOWS: p.shadows,
      ISO_AO: p.ambientOcclusion,
      ISO_SOFT_LIGHTS: p.lightAngularRadius > 0,
      ISO_JITTER: p.jitter,
      ISO_OUTPUT: OUTPUT_CODE[p.output],
      // A channel scene has no single value range per cell to skip by (majorant/grid-textures.ts);
      // a label scene's label surface is not in the value ranges either.
      SKIP_EMPTY: p.emptySpaceSkipping && !scene.channels && !scene.labels,
      BLUE_NOISE: p.sampler === 'blue-noise',
    };
  }

  /** A channel scene: surface k lies on drawn channel k, so there are at most as many surfaces as drawn channels. */
  validateScene(scene: Scene): void {
    if (!scene.channels) return;
    const drawn = scene.channels.filter((c) => c.enabled !== false).length;
    if (this.resolved.surfaces.length > drawn)
      throw new VptError(
        'invalid-scene',
        `IsoRenderer.surfaces: ${this.resolved.surfaces.length} surfaces for ${drawn} drawn channel${drawn === 1 ? '' : 's'}; surface k lies on drawn channel k`,
      );
  }

  paramValues(scene: Scene): UniformValues {
    const p = this.resolved;
    const values = new Float32Array(4);
    const surface = new Float32Array(4 * MAX_ISO_SURFACES);
    p.surfaces.forEach((s, i) => {
      values[i] = s.value;
      surface.set([...s.color, s.opacity], 4 * i);
    });
    const dirs = new Float32Array(4 * MAX_ISO_LIGHTS),
      irr = new Float32Array(4 * MAX_ISO_LIGHTS);
    const cosRadius = Math.cos(p.lightAngularRadius);
    scene.lights.slice(0, MAX_ISO_LIGHTS).forEach((l, i) => {
      const d = l.direction,
        len = Math.hypot(d[0], d[1], d[2]);
      dirs.set([d[0] / len, d[1] / len, d[2] / len, cosRadius], 4 * i);
      irr.set([...l.irradiance, 0], 4 * i);
    });
    const box = volumeBox(scene.volume);
    const voxel = box.size.map((s, i) => s / scene.volume.dims[i]);
    return {
      isoValues: values,
      isoSurface: surface,
      isoLightDirection: dirs,
      isoLightIrradiance: irr,
      gradientStep: voxel,
      ...paramUniformValues(ISO_DESCRIPTOR, resolveRendererParams(ISO_DESCRIPTOR, this.getParams(), scene)),
      // Shadow/AO rays start half a voxel off the surface, outside the crossing they left.
      rayEpsilon: 0.5 * Math.min(...voxel),
      gridCells: gridGeometry(scene.volume.dims, DEFAULT_SKIP_CELL_SIZE),
    };
  }

  /**
   * The environment's lookup and sampling textures (shared chunk GLSL_ENVIRONMENT_MAP), for
   * a lat-long map only: other scenes compile the ISO_ENV < 2 variant, which names none.
   */
  auxiliaryTextures(scene: Scene, volume?: VolumeBinding): readonly AuxiliaryTexture[] {
    // With skipping (and a volume binding: inside a RenderContext), each grid cell's range of volume texels.
    const grid = [
      ...(this.resolved.emptySpaceSkipping && volume && !scene.channels && !scene.labels
        ? majorantGridTextures(scene, volume, DEFAULT_SKIP_CELL_SIZE, 'ranges')
        : []),
      ...(this.resolved.sampler === 'blue-noise' ? [blueNoiseTexture()] : []),
    ];
    const env = scene.environment;
    if (env.type === 'latlong' && environmentEmits(env)) {
      const e = env as LatLongEnvironment;
      let tables: ReturnType<typeof buildEnvironmentSampling> | null = null;
      return [...grid, ...environmentTextures(e, () => (tables ??= buildEnvironmentSampling(e)))];
    }
    return grid;
  }
}
