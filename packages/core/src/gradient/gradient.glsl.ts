/**
 * Kernels of the gradient-magnitude build (GLSL here, the WGSL twin in gradient.wgsl.ts with the
 * same arithmetic in the same order): one pass writes |∇f| per voxel into the slice atlas (shaders/slice-atlas.ts), then max
 * reductions of REDUCTION × REDUCTION blocks shrink it to the 1 × 1 largest magnitude,
 * which normalizes the 2D transfer function's gradient axis without a read-back.
 */

import { REDUCTION } from './reduction.js';

// Central differences (one-sided at the borders, divided by the index distance spanned)
// of the normalized volume (each texel mapped by u.valueScale/valueOffset and clamped, as
// volumeValue() in the shared chunks does), scaled by u.gradScale = (valueRange width) / spacing, so the
// result is |∇f| in data units per physical length (Kniss, Kindlmann, Hansen 2002, "Multidimensional Transfer Functions for Interactive Volume Rendering").
export const GRADIENT_MAGNITUDE = /* glsl */ `
float axisDerivative(ivec3 v, ivec3 e, int i, int n) {
  int i0 = max(i - 1, 0);
  int i1 = min(i + 1, n - 1);
  if (i1 == i0) return 0.0;
  float a = clamp(texelFetch(volume, v + e * (i0 - i), 0).r * u.valueScale + u.valueOffset, 0.0, 1.0);
  float b = clamp(texelFetch(volume, v + e * (i1 - i), 0).r * u.valueScale + u.valueOffset, 0.0, 1.0);
  return (b - a) / float(i1 - i0);
}
void main() {
  ivec2 p = vptPixel();
  ivec3 dims = u.gradDims.xyz;
  ivec4 a = atlasVoxel(p, dims, u.gradDims.w);
  if (a.w == 0) { vpt_out0 = vec4(0.0); return; }
  ivec3 v = a.xyz;
  float gx = axisDerivative(v, ivec3(1, 0, 0), v.x, dims.x) * u.gradScale.x;
  float gy = axisDerivative(v, ivec3(0, 1, 0), v.y, dims.y) * u.gradScale.y;
  float gz = axisDerivative(v, ivec3(0, 0, 1), v.z, dims.z) * u.gradScale.z;
  vpt_out0 = vec4(sqrt(gx * gx + gy * gy + gz * gz), 0.0, 0.0, 1.0);
}
`;

// Maximum over a REDUCTION x REDUCTION block of the source (exact, so both backends agree).
export const MAX_REDUCE = /* glsl */ `
void main() {
  ivec2 p = vptPixel();
  float m = 0.0;
  for (int j = 0; j < ${REDUCTION}; j++) {
    for (int i = 0; i < ${REDUCTION}; i++) {
      ivec2 q = p * ${REDUCTION} + ivec2(i, j);
      if (q.x < u.srcSize.x && q.y < u.srcSize.y) m = max(m, texelFetch(src, q, 0).r);
    }
  }
  vpt_out0 = vec4(m, 0.0, 0.0, 1.0);
}
`;
