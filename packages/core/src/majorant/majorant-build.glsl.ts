// The majorant grid built on the GPU: per-cell value ranges once per volume, then the
// bounds whenever the transfer function or density scale changes (pbrt-v4's GridMedium majorants; Szirmay-Kalos et al. 2011): the same steps in
// the same order as majorant-grid.ts (OpacityRangeTable.valueRange, buildMajorantGrid),
// in float32. Cells are laid out as a slice atlas (sliceAtlasLayout of the cell counts;
// core's slice-atlas chunk, prepended by the renderer, addresses it).

/**
 * Per cell: min and max of the volume texels its points can blend (majorantGrid maps them to
 * normalized values with u.valueScale / u.valueOffset; a filtered value, hardware or exact, is
 * a convex combination of 8 texels, so it stays inside) (the cell's
 * voxels, a one-voxel trilinear border and one voxel of margin: cellVoxelRange in
 * majorant-grid.ts, in exact integer arithmetic). Runs once per volume and cell size.
 */
export const cellRanges = /* glsl */ `
// floor(a / b) for b > 0 (GLSL's integer division truncates toward zero).
int floorDiv(int a, int b) { return a >= 0 ? a / b : -((b - 1 - a) / b); }
// Voxel index range [lo, hi] whose values reach the points of cell c of g along an axis of n voxels:
// lo = floor(c·n/g − ½) − 1, hi = floor((c+1)·n/g − ½) + 2, clamped to the axis.
ivec2 voxelRange(int c, int g, int n) {
  int lo = floorDiv(2 * c * n - g, 2 * g) - 1;
  int hi = floorDiv(2 * (c + 1) * n - g, 2 * g) + 2;
  return ivec2(max(lo, 0), min(hi, n - 1));
}
void main() {
  ivec2 p = vptPixel();
  ivec3 cells = u.gridCells.xyz;
  ivec4 a = atlasVoxel(p, cells, u.gridCells.w);
  if (a.w == 0) { vpt_out0 = vec4(0.0); return; }
  ivec3 c = a.xyz;
  ivec3 n = textureSize(volume, 0);
  ivec2 rx = voxelRange(c.x, cells.x, n.x);
  ivec2 ry = voxelRange(c.y, cells.y, n.y);
  ivec2 rz = voxelRange(c.z, cells.z, n.z);
  float lo = texelFetch(volume, ivec3(rx.x, ry.x, rz.x), 0).r;
  float hi = lo;
  for (int k = rz.x; k <= rz.y; k++) {
    for (int j = ry.x; j <= ry.y; j++) {
      for (int i = rx.x; i <= rx.y; i++) {
        float v = texelFetch(volume, ivec3(i, j, k), 0).r;
        lo = min(lo, v);
        hi = max(hi, v);
      }
    }
  }
  vpt_out0 = vec4(lo, hi, 0.0, 1.0);
}
`;

/** Per TF column: min and max opacity over every row, so a 2D TF's bound holds at any gradient. */
export const opacityBounds = /* glsl */ `
void main() {
  ivec2 p = vptPixel();
  int rows = textureSize(transferFunction, 0).y;
  float lo = texelFetch(transferFunction, ivec2(p.x, 0), 0).a;
  float hi = lo;
  for (int r = 1; r < rows; r++) {
    float a = texelFetch(transferFunction, ivec2(p.x, r), 0).a;
    lo = min(lo, a);
    hi = max(hi, a);
  }
  vpt_out0 = vec4(lo, hi, 0.0, 1.0);
}
`;

/**
 * Per cell: the smallest and largest opacity the kernel's piecewise-linear TF lookup can
 * return for a value in the cell's range (at the range's ends, widened by a relative 1e-4,
 * and at every texel strictly inside), times the density scale, padded by a relative 1e-5.
 */
export const majorantGrid = /* glsl */ `
float columnBound(float x, int n1, bool upper) {
  int i0 = min(int(floor(x)), n1);
  int i1 = min(i0 + 1, n1);
  vec2 a = texelFetch(opacityBounds, ivec2(i0, 0), 0).rg;
  vec2 b = texelFetch(opacityBounds, ivec2(i1, 0), 0).rg;
  float f = x - float(i0);
  return upper ? a.y + (b.y - a.y) * f : a.x + (b.x - a.x) * f;
}
void main() {
  ivec2 p = vptPixel();
  if (atlasVoxel(p, u.gridCells.xyz, u.gridCells.w).w == 0) { vpt_out0 = vec4(0.0); return; }
  // Texel range → normalized value range (an inverted value range swaps the ends).
  vec2 t = texelFetch(majorantRanges, p, 0).rg * u.valueScale + u.valueOffset;
  vec2 range = vec2(min(t.x, t.y), max(t.x, t.y));
  int n1 = textureSize(opacityBounds, 0).x - 1;
  float xa = clamp(range.x, 0.0, 1.0) * float(n1) * (1.0 - 1e-4);
  float xb = min(float(n1), clamp(range.y, 0.0, 1.0) * float(n1) * (1.0 + 1e-4));
  float lo = min(columnBound(xa, n1, false), columnBound(xb, n1, false));
  float hi = max(columnBound(xa, n1, true), columnBound(xb, n1, true));
  int k1 = int(ceil(xb)) - 1;
  for (int k = int(floor(xa)) + 1; k <= k1; k++) {
    vec2 t = texelFetch(opacityBounds, ivec2(k, 0), 0).rg;
    lo = min(lo, t.x);
    hi = max(hi, t.y);
  }
  vpt_out0 = vec4(hi * u.gridDensity * (1.0 + 1e-5), lo * u.gridDensity * (1.0 - 1e-5), 0.0, 1.0);
}
`;
