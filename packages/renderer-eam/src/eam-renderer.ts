import type { Renderer, Scene, UniformField, UniformValues } from '@vpt/core';
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

/** Emission-absorption: HDR = emitted colour + transmittance x background, a = 1 - transmittance. */
export class EamRenderer implements Renderer {
  readonly name = 'eam';
  readonly frameFormats = ['rgba32float'] as const;
  readonly accumulationFormats = ['rgba32float'] as const;
  readonly kernels = {
    generate: { glsl: glsl.generate, wgsl: wgsl.generate },
    integrate: { glsl: glsl.integrate, wgsl: wgsl.integrate },
    render: { glsl: glsl.render, wgsl: wgsl.render },
  };
  readonly paramFields: readonly UniformField[] = [
    { name: 'stepSize', type: 'f32' },
    { name: 'cutoff', type: 'f32' },
  ];
  private _version = 0;
  private params: EamParams;

  constructor(params: EamParams = {}) {
    this.params = { ...params };
  }

  get version(): number { return this._version; }

  setParams(params: EamParams): void {
    this.params = { ...this.params, ...params };
    this._version++;
  }

  getParams(): EamParams { return { ...this.params }; }

  paramValues(scene: Scene): UniformValues {
    return {
      stepSize: this.params.stepSize ?? 0.5 / Math.max(...scene.volume.dims),
      cutoff: this.params.cutoff ?? 1e-6,
    };
  }

  features(): Record<string, boolean | number> { return {}; }
}
