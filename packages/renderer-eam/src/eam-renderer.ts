import {
  BaseRenderer,
  COPY_ACCUMULATION_RENDER,
  DEFAULT_SKIP_CELL_SIZE,
  GRID_CELLS_FIELD,
  gridGeometry,
  majorantGridTextures,
  RUNNING_MEAN_INTEGRATE,
  paramSpecsOf,
  paramUniformFields,
  paramUniformValues,
  resolveRendererParams,
  type AuxiliaryTexture,
  type ParamSpecs,
  type Scene,
  type UniformField,
  type UniformValues,
  type VolumeBinding,
} from '@vpt/core';
import { blueNoiseTexture } from '@vpt/core/blue-noise';
import * as glsl from './kernels/eam.glsl.js';
import * as wgsl from './kernels/eam.wgsl.js';
import { EAM_DESCRIPTOR, type EamParams } from './descriptor.js';

/** EAM's parameters and their ranges (core's validateParams; steps also ≥ MIN_STEP_VOXELS voxels per scene). */
export const EAM_PARAM_SPECS: ParamSpecs = paramSpecsOf(EAM_DESCRIPTOR);

/** Emission-absorption: HDR = emitted colour + transmittance x background, a = 1 - transmittance. */
export class EamRenderer extends BaseRenderer<EamParams> {
  readonly name = EAM_DESCRIPTOR.name;
  readonly frameFormats = ['rgba32float'] as const;
  readonly accumulationFormats = ['rgba32float'] as const;
  readonly writesGuides = EAM_DESCRIPTOR.writesGuides;
  /** Its guide normal is a gradient inside the medium, noise at a sample or two: no normal test in temporal reuse. */
  readonly temporalNormalTest = false;
  /** A history of 6 samples: at 12 its reprojection error, added at each camera update, outweighed its noise gain (paced orbit ×0.58 against ×0.47). */
  readonly temporalMaxHistory = 6;
  /** Draws a scene's slicePlane (core's scene/slice-plane.ts) under VPT_SLICE_PLANE. */
  readonly drawsSlicePlane = true;
  /** Draws a scene's labels (core's scene/labels.ts) under VPT_LABELS: their opacity and colour join the medium (transferAt). */
  readonly drawsLabels = true;
  readonly kernels = {
    generate: { glsl: glsl.generate, wgsl: wgsl.generate },
    integrate: RUNNING_MEAN_INTEGRATE,
    render: COPY_ACCUMULATION_RENDER,
  };
  readonly paramFields: readonly UniformField[] = [...paramUniformFields(EAM_DESCRIPTOR), GRID_CELLS_FIELD];

  constructor(params: EamParams = {}) {
    super(params, EAM_PARAM_SPECS, EAM_DESCRIPTOR.owner);
  }

  override features(_scene: Scene): Record<string, boolean | number> {
    return { SKIP_EMPTY: this.skipping, BLUE_NOISE: this.blueNoise };
  }

  paramValues(scene: Scene): UniformValues {
    return {
      ...paramUniformValues(EAM_DESCRIPTOR, resolveRendererParams(EAM_DESCRIPTOR, this.getParams(), scene)),
      gridCells: gridGeometry(scene.volume.dims, DEFAULT_SKIP_CELL_SIZE),
    };
  }

  /** With skipping, the majorant grid (max of densityScale·opacity per cell; 0 = empty), built on the GPU. */
  auxiliaryTextures(scene: Scene, volume: VolumeBinding): readonly AuxiliaryTexture[] {
    const grid = this.skipping ? majorantGridTextures(scene, volume, DEFAULT_SKIP_CELL_SIZE, 'majorants') : [];
    return this.blueNoise ? [...grid, blueNoiseTexture()] : grid;
  }

  private get blueNoise(): boolean {
    return (this.getParams().sampler ?? EAM_DESCRIPTOR.params.sampler.default) === 'blue-noise';
  }

  private get skipping(): boolean {
    return this.getParams().emptySpaceSkipping ?? true;
  }
}
