import type { KernelSource } from '../renderer.js';

/**
 * Integrate kernel shared by renderers whose estimate is a plain average of frames:
 * running mean acc_n = acc_{n-1} + (x_n - acc_{n-1}) / (n + 1), which stays accurate over
 * very long runs where a growing sum would lose precision. At n = 0 it copies the frame
 * (that is how reset works). One frame/accumulation texture.
 */
export const RUNNING_MEAN_INTEGRATE: KernelSource = {
  glsl: /* glsl */ `
void main() {
  ivec2 p = vptPixel();
  vec4 f = texelFetch(frame0, p, 0);
  if (u.iteration == 0u) { vpt_out0 = f; return; }
  vec4 a = texelFetch(accum0, p, 0);
  float w = 1.0 / float(u.iteration + 1u);
  vpt_out0 = a + (f - a) * w;
}
`,
  wgsl: /* wgsl */ `
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
`,
};

/** Render kernel for renderers whose accumulation already is the HDR image. */
export const COPY_ACCUMULATION_RENDER: KernelSource = {
  glsl: /* glsl */ `
void main() {
  vpt_out0 = texelFetch(accum0, vptPixel(), 0);
}
`,
  wgsl: /* wgsl */ `
@fragment fn fs_main(@builtin(position) fragCoord: vec4f) -> VptOut {
  var o: VptOut;
  o.out0 = textureLoad(accum0, vptPixel(fragCoord), 0);
  return o;
}
`,
};
