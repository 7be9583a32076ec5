import { MAX_MARCH_STEPS, WGSL_CELL_WALK, WGSL_DEPTH_LIMIT } from '@vpt/core';
import { WGSL_SAMPLE_DIMS } from '@vpt/core/blue-noise';

// Monte Carlo maximum intensity projection (Lesar, Bohak, Marolt 2018, Web3D, its MIP renderer): each
// iteration marches the pixel-centre ray with a random sample offset; the accumulation keeps the max.
// Twin of mip.glsl.ts (SKIP_EMPTY: cells whose largest value cannot raise the maximum are jumped over).

export const generate = /* wgsl */ `
${WGSL_SAMPLE_DIMS}
#if VPT_DEPTH_LIMIT
${WGSL_DEPTH_LIMIT}
#endif
#if SKIP_EMPTY
${WGSL_CELL_WALK}
fn cellMaxValue(walk: CellWalk) -> f32 {
  let r = textureLoad(majorantRanges, cellWalkTexel(walk), 0).rg;
  let m = max(volumeValue(r.x), volumeValue(r.y));
  return select(0.0, m + 1e-5, m > 0.0);
}
#endif
@fragment fn fs_main(@builtin(position) fragCoord: vec4f) -> VptOut {
  let pixel = vptPixel(fragCoord);
  var rng = rngInit(pixel, u.iteration + u.sampleBase, u.seed);
  sampleDimsInit(pixel);
  let dir = centreCameraRay(pixel, vptTargetSize());
#if VPT_CLIP
  var t = keptInterval(u.cameraPosition, dir);
#else
  var t = intersectBox(u.cameraPosition, dir, u.boxMin, u.boxMax);
#endif
#if VPT_DEPTH_LIMIT
  t.y = min(t.y, depthLimitAlong(pixel, dir));
#endif
#if VPT_CHANNELS
  var maxValue = vec4f(0.0);
#else
#if VPT_SLICE_PLANE
  // The slice plane is opaque: the ray ends there (scene/slice-plane.ts).
  let tPlane = slicePlaneHit(u.cameraPosition, dir);
  let onPlane = tPlane > 0.0 && tPlane <= t.y;
  if (onPlane) { t.y = tPlane; }
#endif
  var maxValue = 0.0;
#endif
#if VPT_LABELS
  var labelA = 0.0;
  var labelId = 0;
#endif
  var coverage = 0.0;
  if (t.x < t.y) {
    coverage = 1.0;
    let offset = rngDim(&rng, 2);
    let len = t.y - t.x;
    let n = max(1, i32(min(ceil(len / u.stepSize), ${MAX_MARCH_STEPS}.0)));
    let seg = len / f32(n);
    var k = 0;
#if SKIP_EMPTY
    var walk = cellWalkStart(u.cameraPosition, dir, t.x);
    let maxCells = u.gridCells.x + u.gridCells.y + u.gridCells.z + 3;
    for (var c = 0; c < maxCells && k < n && maxValue < 1.0; c++) {
      let below = cellMaxValue(walk) <= maxValue;
      let tExit = cellWalkStep(&walk);
      let tEnd = select(tExit, 3.0e38, tExit >= t.y);
      if (below) { k = latticeIndexAt(tEnd, t.x, seg, offset, k, n); continue; }
      for (; k < n; k++) {
        let s = t.x + (f32(k) + offset) * seg;
        if (s >= tEnd) { break; }
        maxValue = max(maxValue, sampleVolume(u.cameraPosition + dir * s));
      }
    }
    if (maxValue >= 1.0) { k = n; }
#endif
    for (; k < n; k++) {
      let s = t.x + (f32(k) + offset) * seg;
#if VPT_CHANNELS
      maxValue = max(maxValue, sampleChannels(u.cameraPosition + dir * s));
#else
      maxValue = max(maxValue, sampleVolume(u.cameraPosition + dir * s));
#endif
#if VPT_LABELS
      let id = labelIdAt(u.cameraPosition + dir * s);
      let la = labelEntry(id).a;
      if (la > labelA || (la == labelA && la > 0.0 && id < labelId)) {
        labelA = la;
        labelId = id;
      }
#endif
    }
  }
  var o: VptOut;
#if VPT_CHANNELS
  o.out0 = select(vec4f(-1.0), maxValue, coverage > 0.0);
#else
#if VPT_DEPTH_LIMIT
  coverage = maxValue;
#endif
  o.out0 = vec4f(maxValue, 0.0, 0.0, coverage);
#if VPT_LABELS
  o.out0 = vec4f(maxValue, labelA, f32(labelId), coverage);
#endif
#if VPT_SLICE_PLANE
  if (onPlane) {
    let c = slicePlaneColor(u.cameraPosition + dir * tPlane);
    o.out0 = vec4f(maxValue, c.r, c.g, -1.0 - c.b);
  }
#endif
#endif
  return o;
}
`;

export const integrate = /* wgsl */ `
@fragment fn fs_main(@builtin(position) fragCoord: vec4f) -> VptOut {
  let p = vptPixel(fragCoord);
  let f = textureLoad(frame0, p, 0);
  var o: VptOut;
  if (u.iteration == 0u) { o.out0 = f; return o; }
  let a = textureLoad(accum0, p, 0);
#if VPT_CHANNELS
  o.out0 = max(a, f);
#else
#if VPT_SLICE_PLANE
  if (f.a < 0.0) { o.out0 = vec4f(max(a.r, f.r), f.gba); return o; }
#endif
  let w = 1.0 / f32(u.iteration + 1u);
  o.out0 = vec4f(max(a.r, f.r), 0.0, 0.0, a.a + (f.a - a.a) * w);
#if VPT_LABELS
  let take = f.g > a.g || (f.g == a.g && f.g > 0.0 && f.b < a.b);
  o.out0 = vec4f(max(a.r, f.r), select(a.g, f.g, take), select(a.b, f.b, take), a.a + (f.a - a.a) * w);
#endif
#endif
  return o;
}
`;

export const render = /* wgsl */ `
#if VPT_CHANNELS
fn mipChannel(value: f32, row: i32) -> vec3f {
  let x = clamp(value, 0.0, 1.0) * f32(u.tfSize - 1);
  let x0 = floor(x);
  let i0 = i32(x0);
  let i1 = min(i0 + 1, u.tfSize - 1);
  let a = textureLoad(transferFunction, vec2i(i0, row), 0);
  let t = a + (textureLoad(transferFunction, vec2i(i1, row), 0) - a) * (x - x0);
  return t.a * t.rgb;
}
#endif
@fragment fn fs_main(@builtin(position) fragCoord: vec4f) -> VptOut {
  let a = textureLoad(accum0, vptPixel(fragCoord), 0);
  var o: VptOut;
#if VPT_CHANNELS
  if (a.x < 0.0) { o.out0 = vec4f(0.0); return o; }
  var rgb = vec3f(0.0);
  for (var k = 0; k < VPT_CHANNELS; k++) { rgb += mipChannel(a[k], k); }
  var coverage = 1.0;
#if VPT_DEPTH_LIMIT
  coverage = clamp(max(max(a.x, a.y), max(a.z, a.w)), 0.0, 1.0);
#endif
  o.out0 = vec4f(rgb, coverage);
#else
  o.out0 = vec4f(a.r, a.r, a.r, a.a);
#if VPT_LABELS
  if (a.a >= 0.0 && a.g > 0.0) {
    let id = i32(a.b + 0.5);
    let size = vec2i(textureDimensions(labelTable, 0));
    let c = textureLoad(labelTable, vec2i(id % size.x, id / size.x), 0).rgb;
    let w = clamp(a.g, 0.0, 1.0);
    o.out0 = vec4f(vec3f(a.r) + (c - vec3f(a.r)) * w, max(a.a, w));
  }
#endif
#if VPT_SLICE_PLANE
  if (a.a < 0.0) { o.out0 = vec4f(vec3f(a.r) + (1.0 - a.r) * vec3f(a.g, a.b, -1.0 - a.a), 1.0); }
#endif
#endif
  return o;
}
`;
