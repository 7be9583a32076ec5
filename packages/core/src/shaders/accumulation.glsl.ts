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

/**
 * Integrate kernel for renderers with half accumulations (Renderer.halfAccumulations = [1, 2]):
 * running means of all iterations (out0) and of the even (out1) and odd (out2) iterations
 * alone, independent halves of equal size from which RenderContext.estimateError() reports
 * the live error of the full mean. Three accumulation textures.
 */
export const RUNNING_MEANS_WITH_HALVES_INTEGRATE = /* glsl */ `
void main() {
  ivec2 p = vptPixel();
  vec4 f = texelFetch(frame0, p, 0);
  uint n = u.iteration;
  if (n == 0u) { vpt_out0 = f; vpt_out1 = f; vpt_out2 = vec4(0.0); return; }
  vec4 a = texelFetch(accum0, p, 0);
  vec4 e = texelFetch(accum1, p, 0);
  vec4 o = texelFetch(accum2, p, 0);
  vpt_out0 = a + (f - a) * (1.0 / float(n + 1u));
  float wHalf = 1.0 / float(n / 2u + 1u);
  if ((n & 1u) == 0u) {
    vpt_out1 = e + (f - e) * wHalf;
    vpt_out2 = o;
  } else {
    vpt_out1 = e;
    vpt_out2 = o + (f - o) * wHalf;
  }
}
`;

/** Render kernel for renderers whose accumulation already is the HDR image. */
export const COPY_ACCUMULATION_RENDER = /* glsl */ `
void main() {
  vpt_out0 = texelFetch(accum0, vptPixel(), 0);
}
`;
