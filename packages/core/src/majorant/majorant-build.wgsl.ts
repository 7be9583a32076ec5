// Twin of majorant-build.glsl.ts: the majorant grid built on the GPU (pbrt-v4's GridMedium
// majorants; Szirmay-Kalos et al. 2011), same arithmetic in the same order.

export const cellRanges = /* wgsl */ `
fn floorDiv(a: i32, b: i32) -> i32 { return select(-((b - 1 - a) / b), a / b, a >= 0); }
fn voxelRange(c: i32, g: i32, n: i32) -> vec2i {
  let lo = floorDiv(2 * c * n - g, 2 * g) - 1;
  let hi = floorDiv(2 * (c + 1) * n - g, 2 * g) + 2;
  return vec2i(max(lo, 0), min(hi, n - 1));
}
@fragment fn fs_main(@builtin(position) fragCoord: vec4f) -> VptOut {
  let p = vptPixel(fragCoord);
  let cells = u.gridCells.xyz;
  let a = atlasVoxel(p, cells, u.gridCells.w);
  var o: VptOut;
  if (a.w == 0) { o.out0 = vec4f(0.0); return o; }
  let c = a.xyz;
  let n = vec3i(textureDimensions(volume));
  let rx = voxelRange(c.x, cells.x, n.x);
  let ry = voxelRange(c.y, cells.y, n.y);
  let rz = voxelRange(c.z, cells.z, n.z);
  var lo = textureLoad(volume, vec3i(rx.x, ry.x, rz.x), 0).r;
  var hi = lo;
  for (var k = rz.x; k <= rz.y; k++) {
    for (var j = ry.x; j <= ry.y; j++) {
      for (var i = rx.x; i <= rx.y; i++) {
        let v = textureLoad(volume, vec3i(i, j, k), 0).r;
        lo = min(lo, v);
        hi = max(hi, v);
      }
    }
  }
  o.out0 = vec4f(lo, hi, 0.0, 1.0);
  return o;
}
`;

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
  var o: VptOut;
  if (atlasVoxel(p, u.gridCells.xyz, u.gridCells.w).w == 0) { o.out0 = vec4f(0.0); return o; }
  let t = textureLoad(majorantRanges, p, 0).rg * u.valueScale + u.valueOffset;
  let range = vec2f(min(t.x, t.y), max(t.x, t.y));
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
