/**
 * Walking a ray through the majorant grid's cells for the ray marches (EAM, MIP, ISO): a 3D
 * DDA (Amanatides & Woo 1987, "A Fast Voxel Traversal Algorithm for Ray Tracing") and the
 * lattice arithmetic that lets a march skip a cell's samples while keeping the others on the
 * unskipped march's positions. Reads `u.gridCells` (GRID_CELLS_FIELD) and the box; needs the
 * generate chunks (safeInverse, atlasTexel).
 */
export const CELL_WALK = /* glsl */ `
struct CellWalk { vec3 tNext; vec3 tDelta; ivec3 cell; ivec3 stepDir; };
// The walk along o + t·d from the cell holding the point at t0 (clamped into the grid).
CellWalk cellWalkStart(vec3 o, vec3 d, float t0) {
  CellWalk s;
  ivec3 cells = u.gridCells.xyz;
  vec3 cellSize = (u.boxMax - u.boxMin) / vec3(cells);
  vec3 inv = safeInverse(d);
  vec3 p = (o + d * t0 - u.boxMin) / cellSize;
  s.cell = clamp(ivec3(floor(p)), ivec3(0), cells - 1);
  s.stepDir = ivec3(d.x < 0.0 ? -1 : 1, d.y < 0.0 ? -1 : 1, d.z < 0.0 ? -1 : 1);
  vec3 boundary = vec3(s.cell + max(s.stepDir, ivec3(0)));
  s.tNext = (u.boxMin + boundary * cellSize - o) * inv;
  s.tDelta = abs(cellSize * inv);
  return s;
}
// The current cell's texel in the grid's slice atlas (a cell past the grid's edge reads its nearest cell).
ivec2 cellWalkTexel(CellWalk s) {
  ivec3 cells = u.gridCells.xyz;
  return atlasTexel(clamp(s.cell, ivec3(0), cells - 1), cells, u.gridCells.w);
}
// The current cell's exit distance; then step into the next cell.
float cellWalkStep(inout CellWalk s) {
  float tExit;
  if (s.tNext.x <= s.tNext.y && s.tNext.x <= s.tNext.z) {
    tExit = s.tNext.x; s.cell.x += s.stepDir.x; s.tNext.x += s.tDelta.x;
  } else if (s.tNext.y <= s.tNext.z) {
    tExit = s.tNext.y; s.cell.y += s.stepDir.y; s.tNext.y += s.tDelta.y;
  } else {
    tExit = s.tNext.z; s.cell.z += s.stepDir.z; s.tNext.z += s.tDelta.z;
  }
  return tExit;
}
// The first index j >= k (at most n) of the march lattice t0 + (j + offset)·seg at or past tEnd: where a march
// resumes after skipping a cell. Rounding can put it one sample off only for a sample within float rounding of
// the cell's face; the grid's bounds hold a voxel beyond each cell, so that sample is empty either way.
int latticeIndexAt(float tEnd, float t0, float seg, float offset, int k, int n) {
  return int(clamp(ceil((tEnd - t0) / seg - offset), float(k), float(n)));
}
`;
