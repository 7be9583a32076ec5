import {
  BaseRenderer,
  DEFAULT_SKIP_CELL_SIZE,
  GRID_CELLS_FIELD,
  gridGeometry,
  majorantGridTextures,
  type AuxiliaryTexture,
  type ParamSpecs,
  type Scene,
  type UniformField,
  type UniformValues,
  type VolumeBinding,
} from '@vpt/core';
import * as glsl from './kernels/mip.glsl.js';
import * as wgsl from './kernels/mip.wgsl.js';

export interface MipParams {
  /** Distance between samples along a ray, in world units (box longest side = 1). Default: DEFAULT_MIP_STEP_VOXELS voxels. */
  stepSize?: number;
  /**
   * Jump over the majorant-grid cells whose largest value cannot raise the ray's running
   * maximum, and stop at the largest normalized value (default true). The maximum is the same
   * bits either way; false is the plain march, for tests and benchmarks.
   */
  emptySpaceSkipping?: boolean;
}

/** MIP's parameters and their ranges (core's validateParams; steps also ≥ MIN_STEP_VOXELS voxels per scene). */
export const MIP_PARAM_SPECS: ParamSpecs = { stepSize: { kind: 'step' }, emptySpaceSkipping: { kind: 'boolean' } };

/** Maximum intensity projection. HDR output: the maximum normalized value as grey, a = coverage. */
export class MipRenderer extends BaseRenderer<MipParams> {
  readonly name = 'mip';
  readonly frameFormats = ['rgba32float'] as const;
  readonly accumulationFormats = ['rgba32float'] as const;
  readonly kernels = {
    generate: { glsl: glsl.generate, wgsl: wgsl.generate },
    integrate: { glsl: glsl.integrate, wgsl: wgsl.integrate },
    render: { glsl: glsl.render, wgsl: wgsl.render },
  };
  readonly paramFields: readonly UniformField[] = [{ name: 'stepSize', type: 'f32' }, GRID_CELLS_FIELD];

  constructor(params: MipParams = {}) {
    super(params, MIP_PARAM_SPECS, 'MIP');
  }

  override features(_scene: Scene): Record<string, boolean | number> {
    return { SKIP_EMPTY: this.skipping };
  }

  paramValues(scene: Scene): UniformValues {
    return {
      stepSize: this.getParams().stepSize ?? defaultStepSize(scene),
      gridCells: gridGeometry(scene.volume.dims, DEFAULT_SKIP_CELL_SIZE),
    };
  }

  /** With skipping, each majorant-grid cell's range of volume texels, built on the GPU. */
  auxiliaryTextures(scene: Scene, volume: VolumeBinding): readonly AuxiliaryTexture[] {
    return this.skipping ? majorantGridTextures(scene, volume, DEFAULT_SKIP_CELL_SIZE, 'ranges') : [];
  }

  private get skipping(): boolean {
    return this.getParams().emptySpaceSkipping ?? true;
  }
}

/**
 * MIP's default step in voxels of the volume's longest side. The running maximum over random
 * offsets converges to the maximum along the ray at any step, so the step only trades cost
 * against the iterations to get there: 1 voxel reached 35 dB after one iteration on the VPT
 * anchor and the head, and did so soonest (docs/benchmarks.md, "Step sweep").
 */
export const DEFAULT_MIP_STEP_VOXELS = 1;

/** DEFAULT_MIP_STEP_VOXELS along the longest axis in world units. */
export function defaultStepSize(scene: Scene): number {
  return DEFAULT_MIP_STEP_VOXELS / Math.max(...scene.volume.dims);
}
