import {
  BaseRenderer,
  COPY_ACCUMULATION_RENDER,
  RUNNING_MEAN_INTEGRATE,
  type ParamSpecs,
  type Scene,
  type UniformField,
  type UniformValues,
} from '@vpt/core';
import * as glsl from './kernels/eam.glsl.js';
import * as wgsl from './kernels/eam.wgsl.js';

export interface EamParams {
  /** Ray-march segment length in world units (box longest side = 1). Default: half a voxel. */
  stepSize?: number;
  /**
   * Transmittance below which the march stops (early ray termination). Default 1e-6;
   * 0 disables it. The remaining light is dropped, a bias of at most `cutoff`.
   */
  cutoff?: number;
}

/** EAM's parameters and their ranges (core's validateParams; steps also ≥ MIN_STEP_VOXELS voxels per scene). */
export const EAM_PARAM_SPECS: ParamSpecs = {
  stepSize: { kind: 'step' },
  cutoff: { kind: 'number', min: 0, max: 1 },
};

/** Emission-absorption: HDR = emitted colour + transmittance x background, a = 1 - transmittance. */
export class EamRenderer extends BaseRenderer<EamParams> {
  readonly name = 'eam';
  readonly frameFormats = ['rgba32float'] as const;
  readonly accumulationFormats = ['rgba32float'] as const;
  readonly writesGuides = true;
  readonly kernels = {
    generate: { glsl: glsl.generate, wgsl: wgsl.generate },
    integrate: RUNNING_MEAN_INTEGRATE,
    render: COPY_ACCUMULATION_RENDER,
  };
  readonly paramFields: readonly UniformField[] = [
    { name: 'stepSize', type: 'f32' },
    { name: 'cutoff', type: 'f32' },
  ];

  constructor(params: EamParams = {}) {
    super(params, EAM_PARAM_SPECS, 'EAM');
  }

  paramValues(scene: Scene): UniformValues {
    const p = this.getParams();
    return {
      stepSize: p.stepSize ?? 0.5 / Math.max(...scene.volume.dims),
      cutoff: p.cutoff ?? 1e-6,
    };
  }
}
