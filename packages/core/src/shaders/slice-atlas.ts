/**
 * Volumes computed on the GPU (the gradient magnitudes, the MCRT majorant grid) live in a
 * 2D "slice atlas": the backend interface only renders full-screen passes into 2D targets,
 * so slice z of an NX × NY × NZ volume is
 * tile (z mod columns, floor(z / columns)) of a (columns·NX) × (rows·NY) r32float texture.
 * A 2D texture can also be read back, which the tests use. The tiling is a function of
 * the dims only, so kernels and the CPU agree on it without asking the device.
 */
export interface SliceAtlasLayout {
  columns: number;
  rows: number;
  width: number;
  height: number;
}

/** Near-square atlas: columns ≈ sqrt(NZ·NY/NX), so width ≈ height. */
export function sliceAtlasLayout(dims: readonly [number, number, number] | readonly number[]): SliceAtlasLayout {
  const [nx, ny, nz] = dims;
  const columns = Math.max(1, Math.min(nz, Math.ceil(Math.sqrt((nz * ny) / nx))));
  const rows = Math.ceil(nz / columns);
  return { columns, rows, width: columns * nx, height: rows * ny };
}

/** Atlas texel (column, row) of voxel (x, y, z); the shader twin is atlasTexel() of slice-atlas.glsl.ts / .wgsl.ts. */
export function atlasTexel(
  layout: SliceAtlasLayout,
  dims: readonly number[],
  x: number,
  y: number,
  z: number,
): [number, number] {
  return [x + (z % layout.columns) * dims[0], y + Math.floor(z / layout.columns) * dims[1]];
}
