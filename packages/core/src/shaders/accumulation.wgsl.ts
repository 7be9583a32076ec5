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

/** Render kernel for renderers whose accumulation already is the HDR image. */
export const COPY_ACCUMULATION_RENDER = /* wgsl */ `
@fragment fn fs_main(@builtin(position) fragCoord: vec4f) -> VptOut {
  var o: VptOut;
  o.out0 = textureLoad(accum0, vptPixel(fragCoord), 0);
  return o;
}
`;
