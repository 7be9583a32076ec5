/** Twin of LABELS in labels.glsl.ts (a scene's label volume, read nearest, and the image + labels mixture; see there). */
export const LABELS = /* wgsl */ `
fn labelIdAt(p: vec3f) -> i32 {
  let dims = vec3i(textureDimensions(labelVolume, 0));
  let tc = (p - u.boxMin) / (u.boxMax - u.boxMin);
  let i = clamp(vec3i(floor(tc * vec3f(dims))), vec3i(0), dims - 1);
  return i32(floor(textureLoad(labelVolume, i, 0).r * u.labelScale + 0.5));
}
fn labelEntry(id: i32) -> vec4f {
  let size = vec2i(textureDimensions(labelTable, 0));
  if (id <= 0 || id >= size.x * size.y) { return vec4f(0.0); }
  return textureLoad(labelTable, vec2i(id % size.x, id / size.x), 0);
}
fn labelAt(p: vec3f) -> vec4f {
  return labelEntry(labelIdAt(p));
}
fn labelVisibleAt(i: vec3i) -> f32 {
  let id = i32(floor(textureLoad(labelVolume, i, 0).r * u.labelScale + 0.5));
  return select(0.0, 1.0, labelEntry(id).a > 0.0);
}
fn labelMask(p: vec3f) -> f32 {
  let tc = (p - u.boxMin) / (u.boxMax - u.boxMin);
  let dims = vec3i(textureDimensions(labelVolume, 0));
  let g = tc * vec3f(dims) - 0.5;
  let g0 = floor(g);
  let f = g - g0;
  let i0 = clamp(vec3i(g0), vec3i(0), dims - 1);
  let i1 = clamp(vec3i(g0) + 1, vec3i(0), dims - 1);
  let c000 = labelVisibleAt(vec3i(i0.x, i0.y, i0.z));
  let c100 = labelVisibleAt(vec3i(i1.x, i0.y, i0.z));
  let c010 = labelVisibleAt(vec3i(i0.x, i1.y, i0.z));
  let c110 = labelVisibleAt(vec3i(i1.x, i1.y, i0.z));
  let c001 = labelVisibleAt(vec3i(i0.x, i0.y, i1.z));
  let c101 = labelVisibleAt(vec3i(i1.x, i0.y, i1.z));
  let c011 = labelVisibleAt(vec3i(i0.x, i1.y, i1.z));
  let c111 = labelVisibleAt(vec3i(i1.x, i1.y, i1.z));
  let c00 = lerp1(c000, c100, f.x);
  let c10 = lerp1(c010, c110, f.x);
  let c01 = lerp1(c001, c101, f.x);
  let c11 = lerp1(c011, c111, f.x);
  return lerp1(lerp1(c00, c10, f.y), lerp1(c01, c11, f.y), f.z);
}
fn transferAt(p: vec3f) -> vec4f {
  let t = imageTransferAt(p);
  let l = labelAt(p);
  let sigma = t.a + l.a;
  let rgb = select(t.rgb, (t.a / sigma) * t.rgb + (l.a / sigma) * l.rgb, sigma > 0.0);
  return vec4f(rgb, sigma);
}
#if SLICE_PLANE
fn slicePlaneColor(p: vec3f) -> vec3f {
  let c = slicePlaneImageColor(p);
  let l = labelAt(p);
  return c + (l.rgb - c) * clamp(l.a, 0.0, 1.0);
}
#endif
`;
