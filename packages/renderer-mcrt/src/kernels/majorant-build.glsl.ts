// The majorant grid built on the GPU whenever the transfer function or density scale
// changes (pbrt-v4's GridMedium majorants; Szirmay-Kalos et al. 2011): the same steps in
// the same order as majorant-grid.ts (OpacityRangeTable.valueRange, buildMajorantGrid),
// in float32. Cells are laid out as a slice atlas (gradientAtlasLayout of the cell counts).

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
  ivec3 cells = u.gridCells.xyz;
  int tx = p.x / cells.x;
  int ty = p.y / cells.y;
  if (tx + u.gridCells.w * ty >= cells.z) { vpt_out0 = vec4(0.0); return; }
  vec2 range = texelFetch(majorantRanges, p, 0).rg;
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
