/**
 * Twin of cell-walk.glsl.ts: the 3D DDA through the majorant grid's cells (Amanatides & Woo
 * 1987) and the march-lattice arithmetic of empty-space skipping, same arithmetic in the same order.
 */
export const CELL_WALK = /* wgsl */ `
struct CellWalk { tNext: vec3f, tDelta: vec3f, cell: vec3i, stepDir: vec3i };
fn cellWalkStart(o: vec3f, d: vec3f, t0: f32) -> CellWalk {
  var s: CellWalk;
  let cells = u.gridCells.xyz;
  let cellSize = (u.boxMax - u.boxMin) / vec3f(cells);
  let inv = safeInverse(d);
  let p = (o + d * t0 - u.boxMin) / cellSize;
  s.cell = clamp(vec3i(floor(p)), vec3i(0), cells - 1);
  s.stepDir = vec3i(select(1, -1, d.x < 0.0), select(1, -1, d.y < 0.0), select(1, -1, d.z < 0.0));
  let boundary = vec3f(s.cell + max(s.stepDir, vec3i(0)));
  s.tNext = (u.boxMin + boundary * cellSize - o) * inv;
  s.tDelta = abs(cellSize * inv);
  return s;
}
fn cellWalkTexel(s: CellWalk) -> vec2i {
  let cells = u.gridCells.xyz;
  return atlasTexel(clamp(s.cell, vec3i(0), cells - 1), cells, u.gridCells.w);
}
fn cellWalkStep(s: ptr<function, CellWalk>) -> f32 {
  var tExit: f32;
  if ((*s).tNext.x <= (*s).tNext.y && (*s).tNext.x <= (*s).tNext.z) {
    tExit = (*s).tNext.x; (*s).cell.x += (*s).stepDir.x; (*s).tNext.x += (*s).tDelta.x;
  } else if ((*s).tNext.y <= (*s).tNext.z) {
    tExit = (*s).tNext.y; (*s).cell.y += (*s).stepDir.y; (*s).tNext.y += (*s).tDelta.y;
  } else {
    tExit = (*s).tNext.z; (*s).cell.z += (*s).stepDir.z; (*s).tNext.z += (*s).tDelta.z;
  }
  return tExit;
}
fn latticeIndexAt(tEnd: f32, t0: f32, seg: f32, offset: f32, k: i32, n: i32) -> i32 {
  return i32(clamp(ceil((tEnd - t0) / seg - offset), f32(k), f32(n)));
}
`;
