import type { UniformLayout, UniformValues } from './uniforms/layout.js';

/**
 * A post-processing step: a full-screen pass from an RGBA image to an RGBA image.
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
  /** Current parameter values, packed with `uniforms`; `draw` is the draw's index when the step repeats. */
  uniformValues(draw?: number): UniformValues;
  /** Compile-time defines (e.g. which tone-mapping operator). Part of the pass cache key. */
  defines?(): Record<string, boolean | number>;
  /**
   * How many times the pass is drawn in a row (default 1), each draw reading the previous
   * draw's output as `inputImage` (an iterative filter such as the à-trous denoiser).
   */
  readonly repeat?: number;
  /**
   * The step reads the accumulated denoiser guides (docs/architecture.md, "Denoising"): the
   * context then has the renderer write them during generate and binds `guideNormalDepth`
   * (mean normal, mean depth), `guideAlbedo` (mean albedo, hit fraction) and `guideMoments`
   * (mean luminance, mean squared luminance, sample count).
   */
  readonly usesGuides?: boolean;
  /**
   * The output is still linear scene radiance (a denoiser, not exposure or tone mapping):
   * `RenderContext.readHDR({ afterPost: true })` returns the image after the leading steps
   * that set this.
   */
  readonly keepsRadiance?: boolean;
  /**
   * Each draw writes a second rgba32float output, its state, which the next draw of the step
   * reads as the texture `inputState` (SVGF's filtered variance). The first draw's `inputState`
   * is a placeholder it must not read (the guide moments with `usesGuides`, else its input image).
   */
  readonly stateOutput?: boolean;
}
