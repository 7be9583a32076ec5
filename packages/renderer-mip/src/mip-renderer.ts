import { BaseRenderer, type ParamSpecs, type Scene, type UniformField, type UniformValues } from '@vpt/core';
import * as glsl from './kernels/mip.glsl.js';
import * as wgsl from './kernels/mip.wgsl.js';

export interface MipParams {
  /** Distance between samples along a ray, in world units (box longest side = 1). Default: half a voxel. */
  stepSize?: number;
}

/** MIP's parameters and their ranges (core's validateParams; steps also ≥ MIN_STEP_VOXELS voxels per scene). */
export const MIP_PARAM_SPECS: ParamSpecs = { stepSize: { kind: 'step' } };

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
  readonly paramFields: readonly UniformField[] = [{ name: 'stepSize', type: 'f32' }];

  constructor(params: MipParams = {}) {
    super(params, MIP_PARAM_SPECS, 'MIP');
  }

  paramValues(scene: Scene): UniformValues {
    return { stepSize: this.getParams().stepSize ?? defaultStepSize(scene) };
  }
}

/** Half a voxel along the longest axis in world units. */
export function defaultStepSize(scene: Scene): number {
  return 0.5 / Math.max(...scene.volume.dims);
}
