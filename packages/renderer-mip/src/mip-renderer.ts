import {
  BaseRenderer,
  DEFAULT_SKIP_CELL_SIZE,
  GRID_CELLS_FIELD,
  gridGeometry,
  majorantGridTextures,
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
  VptError,
} from '@vpt/core';
import { blueNoiseTexture } from '@vpt/core/blue-noise';
import * as glsl from './kernels/mip.glsl.js';
import * as wgsl from './kernels/mip.wgsl.js';
import { DEFAULT_MIP_STEP_VOXELS, MIP_DESCRIPTOR, type MipParams } from './descriptor.js';

/** MIP's parameters and their ranges (core's validateParams; steps also ≥ MIN_STEP_VOXELS voxels per scene). */
export const MIP_PARAM_SPECS: ParamSpecs = paramSpecsOf(MIP_DESCRIPTOR);

/** Maximum intensity projection. HDR output: the maximum normalized value as grey, a = coverage. */
export class MipRenderer extends BaseRenderer<MipParams> {
  readonly name = MIP_DESCRIPTOR.name;
  readonly frameFormats = ['rgba32float'] as const;
  readonly accumulationFormats = ['rgba32float'] as const;
  readonly writesGuides = MIP_DESCRIPTOR.writesGuides;
  /** Draws a scene's slicePlane (core's scene/slice-plane.ts) under VPT_SLICE_PLANE. */
  readonly drawsSlicePlane = true;
  /** Draws a scene's labels (core's scene/labels.ts) under VPT_LABELS: the most opaque visible label's colour over the maximum. */
  readonly drawsLabels = true;
  readonly kernels = {
    generate: { glsl: glsl.generate, wgsl: wgsl.generate },
    integrate: { glsl: glsl.integrate, wgsl: wgsl.integrate },
    render: { glsl: glsl.render, wgsl: wgsl.render },
  };
  readonly paramFields: readonly UniformField[] = [...paramUniformFields(MIP_DESCRIPTOR), GRID_CELLS_FIELD];

  constructor(params: MipParams = {}) {
    super(params, MIP_PARAM_SPECS, MIP_DESCRIPTOR.owner);
  }

  override features(scene: Scene): Record<string, boolean | number> {
    // A channel scene has no single value range per cell to skip by (majorant/grid-textures.ts);
    // a label scene marches every sample (a skipped cell could hold a label).
    return { SKIP_EMPTY: this.skipping && !scene.channels && !scene.labels, BLUE_NOISE: this.blueNoise };
  }

  paramValues(scene: Scene): UniformValues {
    return {
      ...paramUniformValues(MIP_DESCRIPTOR, resolveRendererParams(MIP_DESCRIPTOR, this.getParams(), scene)),
      gridCells: gridGeometry(scene.volume.dims, DEFAULT_SKIP_CELL_SIZE),
    };
  }

  /** With skipping, each majorant-grid cell's range of volume texels, built on the GPU. */
  auxiliaryTextures(scene: Scene, volume: VolumeBinding): readonly AuxiliaryTexture[] {
    const grid =
      this.skipping && !scene.channels && !scene.labels
        ? majorantGridTextures(scene, volume, DEFAULT_SKIP_CELL_SIZE, 'ranges')
        : [];
    return this.blueNoise ? [...grid, blueNoiseTexture()] : grid;
  }

  private get blueNoise(): boolean {
    return (this.getParams().sampler ?? MIP_DESCRIPTOR.params.sampler.default) === 'blue-noise';
  }

  /** Labels are drawn over a scalar volume: the frame's free components hold the label, a channel scene's hold channels. */
  validateScene(scene: Scene): void {
    if (scene.labels && scene.channels)
      throw new VptError(
        'invalid-scene',
        'MIP: labels are drawn over a single-channel volume (a channel scene fills the frame with channel maxima); drop "labels" or "channels"',
      );
  }

  private get skipping(): boolean {
    return this.getParams().emptySpaceSkipping ?? true;
  }
}

/** DEFAULT_MIP_STEP_VOXELS along the longest axis in world units. */
export function defaultStepSize(scene: Scene): number {
  return DEFAULT_MIP_STEP_VOXELS / Math.max(...scene.volume.dims);
}
