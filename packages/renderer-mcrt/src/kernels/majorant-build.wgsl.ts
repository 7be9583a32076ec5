// Twin of majorant-build.glsl.ts: the majorant grid built on the GPU (pbrt-v4's GridMedium
// majorants; Szirmay-Kalos et al. 2011), same arithmetic in the same order.

export const opacityBounds = /* wgsl */ `
@fragment fn fs_main(@builtin(position) fragCoord: vec4f) -> VptOut {
  let p = vptPixel(fragCoord);
  let rows = i32(textureDimensions(transferFunction).y);
  var lo = textureLoad(transferFunction, vec2i(p.x, 0), 0).a;
  var hi = lo;
  for (var r = 1; r < rows; r++) {
    let a = textureLoad(transferFunction, vec2i(p.x, r), 0).a;
    lo = min(lo, a);
    hi = max(hi, a);
  }
  var o: VptOut;
  o.out0 = vec4f(lo, hi, 0.0, 1.0);
  return o;
}
`;

export const majorantGrid = /* wgsl */ `
fn columnBound(x: f32, n1: i32, upper: bool) -> f32 {
  let i0 = min(i32(floor(x)), n1);
  let i1 = min(i0 + 1, n1);
  let a = textureLoad(opacityBounds, vec2i(i0, 0), 0).rg;
  let b = textureLoad(opacityBounds, vec2i(i1, 0), 0).rg;
  let f = x - f32(i0);
  return select(a.x + (b.x - a.x) * f, a.y + (b.y - a.y) * f, upper);
}
@fragment fn fs_main(@builtin(position) fragCoord: vec4f) -> VptOut {
  let p = vptPixel(fragCoord);
  let cells = u.gridCells.xyz;
  let tx = p.x / cells.x;
  let ty = p.y / cells.y;
  var o: VptOut;
  if (tx + u.gridCells.w * ty >= cells.z) { o.out0 = vec4f(0.0); return o; }
  let range = textureLoad(majorantRanges, p, 0).rg;
  let n1 = i32(textureDimensions(opacityBounds).x) - 1;
  let xa = clamp(range.x, 0.0, 1.0) * f32(n1) * (1.0 - 1e-4);
  let xb = min(f32(n1), clamp(range.y, 0.0, 1.0) * f32(n1) * (1.0 + 1e-4));
  var lo = min(columnBound(xa, n1, false), columnBound(xb, n1, false));
  var hi = max(columnBound(xa, n1, true), columnBound(xb, n1, true));
  let k1 = i32(ceil(xb)) - 1;
  for (var k = i32(floor(xa)) + 1; k <= k1; k++) {
    let t = textureLoad(opacityBounds, vec2i(k, 0), 0).rg;
    lo = min(lo, t.x);
    hi = max(hi, t.y);
  }
  o.out0 = vec4f(hi * u.gridDensity * (1.0 + 1e-5), lo * u.gridDensity * (1.0 - 1e-5), 0.0, 1.0);
  return o;
}
`;
