/**
 * MIP described as data (core's RendererDescriptor): its parameters, defaults, uniforms and
 * viewer look. Side-effect free and kernel free, so user interfaces import it alone
 * (`@vpt/renderer-mip/descriptor`).
 */
import { defineRenderer, SAMPLER_PARAM, stepInVoxels, type ParamsOf } from '@vpt/core';

/**
 * MIP's default step in voxels of the volume's longest side. The running maximum over random
 * offsets converges to the maximum along the ray at any step, so the step only trades cost
 * against the iterations to get there; 1 voxel got there soonest (figures:
 * docs/benchmarks.md#fig-mip-step).
 */
export const DEFAULT_MIP_STEP_VOXELS = 1;

/** The UI span of a ray-march step (world units), shared by the march renderers' quality panels. */
const STEP_UI = { label: 'Step size', min: 0.0005, max: 0.05, step: 0.0005 } as const;

export const MIP_DESCRIPTOR = defineRenderer({
  name: 'mip',
  label: 'Maximum intensity',
  owner: 'MIP',
  params: {
    /** Distance between samples along a ray, in world units (box longest side = 1). Default: DEFAULT_MIP_STEP_VOXELS voxels. */
    stepSize: { kind: 'step', ...stepInVoxels(DEFAULT_MIP_STEP_VOXELS), ui: STEP_UI, uniform: { type: 'f32' } },
    /**
     * Jump over the majorant-grid cells whose largest value cannot raise the ray's running
     * maximum, and stop at the largest normalized value (default true). The maximum is the same
     * bits either way; false is the plain march, for tests and benchmarks.
     */
    emptySpaceSkipping: { kind: 'boolean', default: true },
    /**
     * 'blue-noise': the first dimensions of each sample (the march offset) are a rank-1 sequence rotated per
     * pixel by a blue-noise mask (core's shaders/blue-noise.ts); 'pcg': the PCG stream. Default: by
     * measured iterations to 30/35 dB (docs/benchmarks.md, "Blue-noise sampling").
     */
    sampler: SAMPLER_PARAM,
  },
  writesGuides: false,
  needs: { transferFunction: false, lights: false, environment: false },
  look: { densityScale: 20, environment: [0, 0, 0] },
});

export type MipParams = ParamsOf<typeof MIP_DESCRIPTOR>;

/** The package's descriptor under the name every renderer package uses (the generated loaders read it). */
export { MIP_DESCRIPTOR as descriptor };
