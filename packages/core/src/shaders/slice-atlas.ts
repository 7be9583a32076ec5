/**
 * The gradient-magnitude volume lives in a 2D "slice atlas": the backend interface only
 * renders full-screen passes into 2D targets, so slice z of the NX × NY × NZ volume is
 * tile (z mod columns, floor(z / columns)) of a (columns·NX) × (rows·NY) r32float texture.
 * A 2D texture can also be read back, which the tests use. The tiling is a function of
 * the dims only, so kernels and the CPU agree on it without asking the device.
 */
export interface GradientAtlasLayout {
  columns: number;
  rows: number;
  width: number;
  height: number;
}

/** Near-square atlas: columns ≈ sqrt(NZ·NY/NX), so width ≈ height. */
export function gradientAtlasLayout(dims: readonly [number, number, number] | readonly number[]): GradientAtlasLayout {
  const [nx, ny, nz] = dims;
  const columns = Math.max(1, Math.min(nz, Math.ceil(Math.sqrt((nz * ny) / nx))));
  const rows = Math.ceil(nz / columns);
  return { columns, rows, width: columns * nx, height: rows * ny };
}

/**
 * The shader twins of atlasTexel and its inverse, shared by every pass that writes a slice
 * atlas and every kernel that reads one (the gradient volume, the MCRT majorant grid).
 */
export const GLSL_ATLAS = /* glsl */ `
// Slice-atlas addressing (gradient/atlas.ts): slice z of a dims volume is tile (z mod columns, z / columns).
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

export const WGSL_ATLAS = /* wgsl */ `
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

/** Atlas texel (column, row) of voxel (x, y, z). */
export function atlasTexel(layout: GradientAtlasLayout, dims: readonly number[], x: number, y: number, z: number): [number, number] {
  return [x + (z % layout.columns) * dims[0], y + Math.floor(z / layout.columns) * dims[1]];
}
