/**
 * The `sampler` renderer parameter (EAM, MIP, ISO, MCRT descriptors). The sampler itself (mask,
 * texture, shader chunk, CPU twin) is the subpath `@vpt/core/blue-noise` (shaders/blue-noise.ts),
 * which only the renderers import: the descriptors live in the viewer's entry, the renderers in
 * its lazy chunks, so the entry carries just these lines.
 */

/** The parameter's choices: the PCG stream everywhere, or blue noise for the first dimensions. */
export type Sampler = 'pcg' | 'blue-noise';

/**
 * The `sampler` parameter's spec, shared by the four descriptors: 'blue-noise' compiles the
 * kernels with BLUE_NOISE and binds the mask. Its default is 'pcg'; a descriptor takes
 * `samplerParam('blue-noise')` where the measurement says blue noise pays (EAM, ISO:
 * docs/benchmarks.md, "Blue-noise sampling").
 */
export const SAMPLER_PARAM = { kind: 'enum', values: ['pcg', 'blue-noise'], default: 'pcg' as Sampler } as const;

/** SAMPLER_PARAM with another default. */
export function samplerParam(defaultSampler: Sampler) {
  return { ...SAMPLER_PARAM, default: defaultSampler };
}
