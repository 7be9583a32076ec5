// The shared integrate and render kernels (WGSL; the twin is accumulation.glsl.ts), composed in accumulation.ts.

/**
 * Integrate kernel shared by renderers whose estimate is a plain average of frames:
 * running mean acc_n = acc_{n-1} + (x_n - acc_{n-1}) / (n + 1), which stays accurate over
 * very long runs where a growing sum would lose precision. At n = 0 it copies the frame
 * (that is how reset works). One frame/accumulation texture.
 */
export const RUNNING_MEAN_INTEGRATE = /* wgsl */ `
@fragment fn fs_main(@builtin(position) fragCoord: vec4f) -> VptOut {
  let p = vptPixel(fragCoord);
  let f = textureLoad(frame0, p, 0);
  var o: VptOut;
  if (u.iteration == 0u) { o.out0 = f; return o; }
  let a = textureLoad(accum0, p, 0);
  let w = 1.0 / f32(u.iteration + 1u);
  o.out0 = a + (f - a) * w;
  return o;
}
`;

/**
 * Integrate kernel for renderers with half accumulations (Renderer.halfAccumulations = [1, 2]):
 * running means of all iterations (out0) and of the even (out1) and odd (out2) iterations
 * alone, independent halves of equal size from which RenderContext.estimateError() reports
 * the live error of the full mean. Three accumulation textures.
 */
export const RUNNING_MEANS_WITH_HALVES_INTEGRATE = /* wgsl */ `
@fragment fn fs_main(@builtin(position) fragCoord: vec4f) -> VptOut {
  let p = vptPixel(fragCoord);
  let f = textureLoad(frame0, p, 0);
  let n = u.iteration;
  var r: VptOut;
  if (n == 0u) { r.out0 = f; r.out1 = f; r.out2 = vec4f(0.0); return r; }
  let a = textureLoad(accum0, p, 0);
  let e = textureLoad(accum1, p, 0);
  let o = textureLoad(accum2, p, 0);
  r.out0 = a + (f - a) * (1.0 / f32(n + 1u));
  let wHalf = 1.0 / f32(n / 2u + 1u);
  if ((n & 1u) == 0u) {
    r.out1 = e + (f - e) * wHalf;
    r.out2 = o;
  } else {
    r.out1 = e;
    r.out2 = o + (f - o) * wHalf;
  }
  return r;
}
`;

/** Render kernel for renderers whose accumulation already is the HDR image. */
export const COPY_ACCUMULATION_RENDER = /* wgsl */ `
@fragment fn fs_main(@builtin(position) fragCoord: vec4f) -> VptOut {
  var o: VptOut;
  o.out0 = textureLoad(accum0, vptPixel(fragCoord), 0);
  return o;
}
`;
