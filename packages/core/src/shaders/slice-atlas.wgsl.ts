/**
 * The shader twins of atlasTexel (slice-atlas.ts) and its inverse, shared by every pass that
 * writes a slice atlas and every kernel that reads one (the gradient volume, the MCRT majorant grid).
 */
export const SLICE_ATLAS = /* wgsl */ `
// Slice-atlas addressing (slice-atlas.ts): slice z of a dims volume is tile (z mod columns, z / columns).
fn atlasTexel(v: vec3i, dims: vec3i, columns: i32) -> vec2i {
  return vec2i(v.x + (v.z % columns) * dims.x, v.y + (v.z / columns) * dims.y);
}
fn atlasVoxel(p: vec2i, dims: vec3i, columns: i32) -> vec4i {
  let tx = p.x / dims.x;
  let ty = p.y / dims.y;
  let z = tx + columns * ty;
  return vec4i(p.x - tx * dims.x, p.y - ty * dims.y, z, select(0, 1, z < dims.z));
}
`;
