// The shared integrate and render kernels (GLSL; the twin is accumulation.wgsl.ts), composed in accumulation.ts.

/**
 * Integrate kernel shared by renderers whose estimate is a plain average of frames:
 * running mean acc_n = acc_{n-1} + (x_n - acc_{n-1}) / (n + 1), which stays accurate over
 * very long runs where a growing sum would lose precision. At n = 0 it copies the frame
 * (that is how reset works). One frame/accumulation texture.
 */
export const RUNNING_MEAN_INTEGRATE = /* glsl */ `
void main() {
  ivec2 p = vptPixel();
  vec4 f = texelFetch(frame0, p, 0);
  if (u.iteration == 0u) { vpt_out0 = f; return; }
  vec4 a = texelFetch(accum0, p, 0);
  float w = 1.0 / float(u.iteration + 1u);
  vpt_out0 = a + (f - a) * w;
}
`;

/** Render kernel for renderers whose accumulation already is the HDR image. */
export const COPY_ACCUMULATION_RENDER = /* glsl */ `
void main() {
  vpt_out0 = texelFetch(accum0, vptPixel(), 0);
}
`;
