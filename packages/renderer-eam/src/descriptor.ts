/**
 * EAM described as data (core's RendererDescriptor): its parameters, defaults, uniforms and
 * viewer look. Side-effect free and kernel free, so user interfaces import it alone
 * (`@vpt/renderer-eam/descriptor`).
 */
import { defineRenderer, samplerParam, stepInVoxels, type ParamsOf } from '@vpt/core';

/**
 * The default step in voxels: the pixel jitter, not the step, dominates EAM's early error at
 * any step up to 2 voxels, so the cheapest step wins; 2 voxels saves no time on the cell walk
 * and converges too slowly on thin high-gradient shells (figures: docs/benchmarks.md#fig-eam-step).
 */
export const DEFAULT_EAM_STEP_VOXELS = 1.5;

/** The default early-termination transmittance (EamParams.cutoff). */
export const DEFAULT_EAM_CUTOFF = 1e-3;

export const EAM_DESCRIPTOR = defineRenderer({
  name: 'eam',
  label: 'Emission–absorption',
  owner: 'EAM',
  params: {
    /**
     * Ray-march segment length in world units (box longest side = 1). Default: DEFAULT_EAM_STEP_VOXELS
     * (1.5) voxels of the longest side, chosen by time to 35 dB (docs/benchmarks.md, "Step sweep").
     */
    stepSize: {
      kind: 'step',
      ...stepInVoxels(DEFAULT_EAM_STEP_VOXELS),
      ui: { label: 'Step size', min: 0.0005, max: 0.05, step: 0.0005 },
      uniform: { type: 'f32' },
    },
    /**
     * Transmittance below which the march stops (early ray termination). Default 1e-3 (VPT's
     * EAM stops at 1e-2); 0 disables it. The remaining light is dropped: a bias of at most
     * `cutoff` times the brightest TF colour or background (60 dB below a peak of 1).
     */
    cutoff: {
      kind: 'number',
      min: 0,
      max: 1,
      default: DEFAULT_EAM_CUTOFF,
      ui: { label: 'Early-exit transmittance', max: 0.1, step: 0.0001 },
      uniform: { type: 'f32' },
    },
    /**
     * Jump over the majorant-grid cells whose opacity bound is 0 (default true). Their samples
     * add nothing, so the image is the same bits either way; false is the plain march, for
     * tests and benchmarks.
     */
    emptySpaceSkipping: { kind: 'boolean', default: true },
    /**
     * 'blue-noise': the first dimensions of each sample (pixel jitter, march offset) are a rank-1 sequence rotated per
     * pixel by a blue-noise mask (core's shaders/blue-noise.ts); 'pcg': the PCG stream. Default
     * blue noise: 1.3–2.0× fewer iterations to 35 dB (docs/benchmarks.md, "Blue-noise sampling").
     */
    sampler: samplerParam('blue-noise'),
  },
  writesGuides: true,
  // Nearly noise-free at 2 samples: in an orbit the denoiser only blurred (docs/benchmarks.md, "Orbit").
  denoiseWhileMoving: false,
  needs: { transferFunction: true, lights: false, environment: true },
  // The palette's emissive top (2.2) saturates a dense volume; 0.55× keeps its structure.
  look: { densityScale: 60, environment: [0.03, 0.035, 0.05], transferFunction: { scaleColors: 0.55 } },
});

export type EamParams = ParamsOf<typeof EAM_DESCRIPTOR>;

/** The package's descriptor under the name every renderer package uses (the generated loaders read it). */
export { EAM_DESCRIPTOR as descriptor };
