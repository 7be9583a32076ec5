import { HALF_MEANS_INTEGRATE, preprocess, type Flags, type KernelSource } from '@vpt/core';
import { GLSL_ENVIRONMENT_MAP, GLSL_SAMPLING, WGSL_ENVIRONMENT_MAP, WGSL_SAMPLING } from '@vpt/core/sampling';
import { GLSL_SAMPLE_DIMS, WGSL_SAMPLE_DIMS } from '@vpt/core/blue-noise';
import type { McrtFeatures } from './features.js';
import * as glslPath from './kernels/path.glsl.js';
import * as wgslPath from './kernels/path.wgsl.js';
import * as glslTracking from './kernels/tracking.glsl.js';
import * as wgslTracking from './kernels/tracking.wgsl.js';

/**
 * The generate kernel of one feature variant, in both languages: the shared sampling chunks,
 * the environment-map chunk only when the variant binds an environment map, then tracking
 * and the path loop, each cut down to the variant's code by the same preprocessor.
 */
export function generateKernel(f: McrtFeatures): KernelSource {
  const flags = f as unknown as Flags;
  const glsl =
    GLSL_SAMPLE_DIMS + GLSL_SAMPLING + (f.ENV_MAP ? GLSL_ENVIRONMENT_MAP : '') + glslTracking.tracking + glslPath.path;
  const wgsl =
    WGSL_SAMPLE_DIMS + WGSL_SAMPLING + (f.ENV_MAP ? WGSL_ENVIRONMENT_MAP : '') + wgslTracking.tracking + wgslPath.path;
  // VPT_GUIDES, VPT_CLIP, VPT_DEPTH_LIMIT and VPT_SLICE_PLANE are the context's flags (RenderContext
  // defines them while a post step uses guides, for a clipped scene, while a depth limit is set and
  // for a scene with a slice plane).
  const defer = { defer: ['VPT_GUIDES', 'VPT_CLIP', 'VPT_DEPTH_LIMIT', 'VPT_SLICE_PLANE'] };
  return { glsl: preprocess(glsl, flags, defer), wgsl: preprocess(wgsl, flags, defer) };
}

/** Running means of all, even and odd iterations (core's, three rgba32float accumulation targets). */
export const INTEGRATE_HALVES: KernelSource = HALF_MEANS_INTEGRATE;
