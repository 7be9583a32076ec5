/**
 * The subpath `@vpt/core/sampling`: the shared light/phase sampling and lat-long environment
 * chunks (sampling.glsl.ts / .wgsl.ts) that only the ISO and MCRT kernels include. Not reached
 * from core's index, so in the viewer's bundle they ride in those renderers' lazy chunks
 * instead of the entry (which re-exports all of the index).
 */
export { SAMPLING as GLSL_SAMPLING, ENVIRONMENT_MAP as GLSL_ENVIRONMENT_MAP } from './sampling.glsl.js';
export { SAMPLING as WGSL_SAMPLING, ENVIRONMENT_MAP as WGSL_ENVIRONMENT_MAP } from './sampling.wgsl.js';
