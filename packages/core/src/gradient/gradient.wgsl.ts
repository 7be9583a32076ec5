/** WGSL twin of gradient.glsl.ts (the gradient-magnitude build), same arithmetic in the same order. */
import { REDUCTION } from './reduction.js';

// Central differences (one-sided at the borders, divided by the index distance spanned)
// of the normalized volume (each texel mapped by u.valueScale/valueOffset and clamped, as
// volumeValue() in the shared chunks does), scaled by u.gradScale = (valueRange width) / spacing, so the
// result is |∇f| in data units per physical length (Kniss, Kindlmann, Hansen 2002, "Multidimensional Transfer Functions for Interactive Volume Rendering").
export const GRADIENT_MAGNITUDE = /* wgsl */ `
fn axisDerivative(v: vec3i, e: vec3i, i: i32, n: i32) -> f32 {
  let i0 = max(i - 1, 0);
  let i1 = min(i + 1, n - 1);
  if (i1 == i0) { return 0.0; }
  let a = clamp(textureLoad(volume, v + e * (i0 - i), 0).r * u.valueScale + u.valueOffset, 0.0, 1.0);
  let b = clamp(textureLoad(volume, v + e * (i1 - i), 0).r * u.valueScale + u.valueOffset, 0.0, 1.0);
  return (b - a) / f32(i1 - i0);
}
@fragment fn fs_main(@builtin(position) fragCoord: vec4f) -> VptOut {
  let p = vptPixel(fragCoord);
  let dims = u.gradDims.xyz;
  let a = atlasVoxel(p, dims, u.gradDims.w);
  var o: VptOut;
  if (a.w == 0) { o.out0 = vec4f(0.0); return o; }
  let v = a.xyz;
  let gx = axisDerivative(v, vec3i(1, 0, 0), v.x, dims.x) * u.gradScale.x;
  let gy = axisDerivative(v, vec3i(0, 1, 0), v.y, dims.y) * u.gradScale.y;
  let gz = axisDerivative(v, vec3i(0, 0, 1), v.z, dims.z) * u.gradScale.z;
  o.out0 = vec4f(sqrt(gx * gx + gy * gy + gz * gz), 0.0, 0.0, 1.0);
  return o;
}
`;

// Maximum over a REDUCTION x REDUCTION block of the source (exact, so both backends agree).
export const MAX_REDUCE = /* wgsl */ `
@fragment fn fs_main(@builtin(position) fragCoord: vec4f) -> VptOut {
  let p = vptPixel(fragCoord);
  var m = 0.0;
  for (var j = 0; j < ${REDUCTION}; j++) {
    for (var i = 0; i < ${REDUCTION}; i++) {
      let q = p * ${REDUCTION} + vec2i(i, j);
      if (q.x < u.srcSize.x && q.y < u.srcSize.y) { m = max(m, textureLoad(src, q, 0).r); }
    }
  }
  var o: VptOut;
  o.out0 = vec4f(m, 0.0, 0.0, 1.0);
  return o;
}
`;
