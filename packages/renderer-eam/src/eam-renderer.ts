import {
  BaseRenderer,
  COPY_ACCUMULATION_RENDER,
  DEFAULT_SKIP_CELL_SIZE,
  GRID_CELLS_FIELD,
  gridGeometry,
  majorantGridTextures,
  RUNNING_MEAN_INTEGRATE,
  type AuxiliaryTexture,
  type ParamSpecs,
  type Scene,
  type UniformField,
  type UniformValues,
  type VolumeBinding,
} from '@vpt/core';
import * as glsl from './kernels/eam.glsl.js';
import * as wgsl from './kernels/eam.wgsl.js';

export interface EamParams {
  /**
   * Ray-march segment length in world units (box longest side = 1). Default: DEFAULT_EAM_STEP_VOXELS
   * (1.5) voxels of the longest side, chosen by time to 35 dB (docs/benchmarks.md, "Step sweep").
   */
  stepSize?: number;
  /**
   * Transmittance below which the march stops (early ray termination). Default 1e-3 (VPT's
   * EAM stops at 1e-2); 0 disables it. The remaining light is dropped: a bias of at most
   * `cutoff` times the brightest TF colour or background (60 dB below a peak of 1).
   */
  cutoff?: number;
  /**
   * Jump over the majorant-grid cells whose opacity bound is 0 (default true). Their samples
   * add nothing, so the image is the same bits either way; false is the plain march, for
   * tests and benchmarks.
   */
  emptySpaceSkipping?: boolean;
}

/**
 * The default step in voxels (was 0.5, then 1). Measured (docs/benchmarks.md, "Step sweep"): on
 * the VPT anchor scene and the head, EAM is within 35 dB of the finest step's converged image
 * after one iteration at every step from 0.25 to 2 voxels (the pixel jitter dominates its
 * error), so the cheapest step wins: 1.5 voxels cost 0.6–0.9× 1 voxel per iteration with
 * skipping. 2 voxels is no cheaper on the anchor (a cell then holds 4 samples and the cell walk
 * costs what it saves) and converges too slowly on thin high-gradient shells (the 2D-TF block of
 * tests/tf2d-eam.test.ts: 0.036 from the CPU model after 32 iterations, limit 0.03; 1.5 passes).
 */
export const DEFAULT_EAM_STEP_VOXELS = 1.5;

/** The default early-termination transmittance (EamParams.cutoff). */
export const DEFAULT_EAM_CUTOFF = 1e-3;

/** EAM's parameters and their ranges (core's validateParams; steps also ≥ MIN_STEP_VOXELS voxels per scene). */
export const EAM_PARAM_SPECS: ParamSpecs = {
  stepSize: { kind: 'step' },
  cutoff: { kind: 'number', min: 0, max: 1 },
  emptySpaceSkipping: { kind: 'boolean' },
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
    GRID_CELLS_FIELD,
  ];

  constructor(params: EamParams = {}) {
    super(params, EAM_PARAM_SPECS, 'EAM');
  }

  override features(_scene: Scene): Record<string, boolean | number> {
    return { SKIP_EMPTY: this.skipping };
  }

  paramValues(scene: Scene): UniformValues {
    const p = this.getParams();
    return {
      stepSize: p.stepSize ?? DEFAULT_EAM_STEP_VOXELS / Math.max(...scene.volume.dims),
      cutoff: p.cutoff ?? DEFAULT_EAM_CUTOFF,
      gridCells: gridGeometry(scene.volume.dims, DEFAULT_SKIP_CELL_SIZE),
    };
  }

  /** With skipping, the majorant grid (max of densityScale·opacity per cell; 0 = empty), built on the GPU. */
  auxiliaryTextures(scene: Scene, volume: VolumeBinding): readonly AuxiliaryTexture[] {
    return this.skipping ? majorantGridTextures(scene, volume, DEFAULT_SKIP_CELL_SIZE, 'majorants') : [];
  }

  private get skipping(): boolean {
    return this.getParams().emptySpaceSkipping ?? true;
  }
}
