/**
 * The shader twins of atlasTexel (slice-atlas.ts) and its inverse, shared by every pass that
 * writes a slice atlas and every kernel that reads one (the gradient volume, the MCRT majorant grid).
 */
export const SLICE_ATLAS = /* glsl */ `
// Slice-atlas addressing (slice-atlas.ts): slice z of a dims volume is tile (z mod columns, z / columns).
ivec2 atlasTexel(ivec3 v, ivec3 dims, int columns) {
  return ivec2(v.x + (v.z % columns) * dims.x, v.y + (v.z / columns) * dims.y);
}
// The voxel at atlas texel p; w = 0 on the padding past the last slice.
ivec4 atlasVoxel(ivec2 p, ivec3 dims, int columns) {
  int tx = p.x / dims.x;
  int ty = p.y / dims.y;
  int z = tx + columns * ty;
  return ivec4(p.x - tx * dims.x, p.y - ty * dims.y, z, z < dims.z ? 1 : 0);
}
`;
