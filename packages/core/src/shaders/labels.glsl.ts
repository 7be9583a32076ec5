/**
 * A scene's label volume (scene/labels.ts; only in variants compiled with LABELS): `labelVolume`
 * holds the ids (r8unorm / r16unorm / r32float, id = round(texel · u.labelScale)), read with
 * texelFetch at the voxel holding the point, never filtered between ids (nearest-neighbour lookup
 * of a segmentation); `labelTable` holds per id (linear rgb, opacity) at (id mod W, id / W), 0 for
 * the background and hidden labels. The labels and the image are one medium: extinctions add,
 * colour / albedo is share-weighted (Novák et al. 2018, CGF 37(2), Sec. 2, as the channels' mixture).
 */
export const LABELS = /* glsl */ `
int labelIdAt(vec3 p) {
  ivec3 dims = textureSize(labelVolume, 0);
  vec3 tc = (p - u.boxMin) / (u.boxMax - u.boxMin);
  ivec3 i = clamp(ivec3(floor(tc * vec3(dims))), ivec3(0), dims - 1);
  return int(floor(texelFetch(labelVolume, i, 0).r * u.labelScale + 0.5));
}
vec4 labelEntry(int id) {
  ivec2 size = textureSize(labelTable, 0);
  if (id <= 0 || id >= size.x * size.y) return vec4(0.0);
  return texelFetch(labelTable, ivec2(id % size.x, id / size.x), 0);
}
vec4 labelAt(vec3 p) {
  return labelEntry(labelIdAt(p));
}
// 1 where the voxel holds a visible label, else 0.
float labelVisibleAt(ivec3 i) {
  int id = int(floor(texelFetch(labelVolume, i, 0).r * u.labelScale + 0.5));
  return labelEntry(id).a > 0.0 ? 1.0 : 0.0;
}
// The visible labels' binary mask, trilinear (cell-centred, clamped, as the exact volume filter)
// from nearest reads of the 8 neighbours: a smooth inside / outside field, never a blend of ids.
float labelMask(vec3 p) {
  vec3 tc = (p - u.boxMin) / (u.boxMax - u.boxMin);
  ivec3 dims = textureSize(labelVolume, 0);
  vec3 g = tc * vec3(dims) - 0.5;
  vec3 g0 = floor(g);
  vec3 f = g - g0;
  ivec3 i0 = clamp(ivec3(g0), ivec3(0), dims - 1);
  ivec3 i1 = clamp(ivec3(g0) + 1, ivec3(0), dims - 1);
  float c000 = labelVisibleAt(ivec3(i0.x, i0.y, i0.z));
  float c100 = labelVisibleAt(ivec3(i1.x, i0.y, i0.z));
  float c010 = labelVisibleAt(ivec3(i0.x, i1.y, i0.z));
  float c110 = labelVisibleAt(ivec3(i1.x, i1.y, i0.z));
  float c001 = labelVisibleAt(ivec3(i0.x, i0.y, i1.z));
  float c101 = labelVisibleAt(ivec3(i1.x, i0.y, i1.z));
  float c011 = labelVisibleAt(ivec3(i0.x, i1.y, i1.z));
  float c111 = labelVisibleAt(ivec3(i1.x, i1.y, i1.z));
  float c00 = lerp1(c000, c100, f.x);
  float c10 = lerp1(c010, c110, f.x);
  float c01 = lerp1(c001, c101, f.x);
  float c11 = lerp1(c011, c111, f.x);
  return lerp1(lerp1(c00, c10, f.y), lerp1(c01, c11, f.y), f.z);
}
vec4 transferAt(vec3 p) {
  vec4 t = imageTransferAt(p);
  vec4 l = labelAt(p);
  float sigma = t.a + l.a;
  vec3 rgb = sigma > 0.0 ? (t.a / sigma) * t.rgb + (l.a / sigma) * l.rgb : t.rgb;
  return vec4(rgb, sigma);
}
#if SLICE_PLANE
// The label colour over the slice with its opacity (clamped to 1): the segmentation overlay of a viewer.
vec3 slicePlaneColor(vec3 p) {
  vec3 c = slicePlaneImageColor(p);
  vec4 l = labelAt(p);
  return c + (l.rgb - c) * clamp(l.a, 0.0, 1.0);
}
#endif
`;
