/**
 * EAM described as data (core's RendererDescriptor): its parameters, defaults, uniforms and
 * viewer look. Side-effect free and kernel free, so user interfaces import it alone
 * (`@vpt/renderer-eam/descriptor`).
 */
import { defineRenderer, stepInVoxels, type ParamsOf } from '@vpt/core';

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
  },
  writesGuides: true,
  needs: { transferFunction: true, lights: false, environment: true },
  // The palette's emissive top (2.2) saturates a dense volume; 0.55× keeps its structure.
  look: { densityScale: 60, environment: [0.03, 0.035, 0.05], transferFunction: { scaleColors: 0.55 } },
});

export type EamParams = ParamsOf<typeof EAM_DESCRIPTOR>;

/** The package's descriptor under the name every renderer package uses (the generated loaders read it). */
export { EAM_DESCRIPTOR as descriptor };
