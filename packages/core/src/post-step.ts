import type { UniformLayout, UniformValues } from './uniforms/layout.js';

/**
 * A post-processing step: one full-screen pass from an RGBA image to an RGBA image.
 * Its kernels read the previous image from the 2D texture named `inputImage` with
 * texelFetch / textureLoad at `vptPixel()` and write `vpt_out0` / `out0`. The context
 * runs every step into an rgba32float target except the last, which writes the
 * rgba8unorm LDR image (the GPU clamps and rounds when it stores to unorm).
 */
export interface PostStep {
  readonly name: string;
  readonly glsl: string;
  readonly wgsl: string;
  readonly uniforms: UniformLayout;
  /** Current parameter values, packed with `uniforms`. */
  uniformValues(): UniformValues;
  /** Compile-time defines (e.g. which tone-mapping operator). Part of the pass cache key. */
  defines?(): Record<string, boolean | number>;
}
