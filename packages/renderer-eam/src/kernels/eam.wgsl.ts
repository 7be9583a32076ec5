import { MAX_MARCH_STEPS, WGSL_CELL_WALK, WGSL_DEPTH_LIMIT } from '@vpt/core';
import { WGSL_SAMPLE_DIMS } from '@vpt/core/blue-noise';

// Emission-absorption (Max 1995, "Optical models for direct volume rendering", IEEE TVCG 1(2), the emission + absorption model)
// by a stratified, randomly offset ray march; alpha = 1 - exp(-sigma_t * segment length).
// Twin of eam.glsl.ts (SKIP_EMPTY: cells whose opacity bound is 0 are jumped over, bit for bit).

export const generate = /* wgsl */ `
${WGSL_SAMPLE_DIMS}
#if SKIP_EMPTY
${WGSL_CELL_WALK}
#endif
#if VPT_DEPTH_LIMIT
${WGSL_DEPTH_LIMIT}
#endif
fn eamSample(
  dir: vec3f, s: f32, seg: f32, color: ptr<function, vec3f>, transmittance: ptr<function, f32>, guide: ptr<function, vec2f>,
) -> bool {
  let tf = transferAt(u.cameraPosition + dir * s);
  let alpha = 1.0 - exp(-(u.densityScale * tf.a) * seg);
  *color += (*transmittance * alpha) * tf.rgb;
#if VPT_GUIDES
  *guide += (*transmittance * alpha) * vec2f(1.0, s);
#endif
  *transmittance *= 1.0 - alpha;
  if (*transmittance < u.cutoff) { *transmittance = 0.0; return false; }
  return true;
}
@fragment fn fs_main(@builtin(position) fragCoord: vec4f) -> VptOut {
  let pixel = vptPixel(fragCoord);
  var rng = rngInit(pixel, u.iteration + u.sampleBase, u.seed);
  sampleDimsInit(pixel);
  let dir = jitteredCameraRayDims(pixel, vptTargetSize(), &rng);
#if VPT_CLIP
  var t = keptInterval(u.cameraPosition, dir);
#else
  var t = intersectBox(u.cameraPosition, dir, u.boxMin, u.boxMax);
#endif
#if VPT_DEPTH_LIMIT
  t.y = min(t.y, depthLimitAlong(pixel, dir));
#endif
#if VPT_SLICE_PLANE
  // The slice plane is opaque: the ray ends there (scene/slice-plane.ts).
  let tPlane = slicePlaneHit(u.cameraPosition, dir);
  let onPlane = tPlane > 0.0 && tPlane <= t.y;
  if (onPlane) { t.y = tPlane; }
#endif
  var color = vec3f(0.0);
  var transmittance = 1.0;
  // Denoiser guides at the mean termination depth: segments weighted by T·alpha, their share of the pixel.
  var guide = vec2f(0.0);
  if (t.x < t.y) {
    let offset = rngDim(&rng, 2);
    let len = t.y - t.x;
    let n = max(1, i32(min(ceil(len / u.stepSize), ${MAX_MARCH_STEPS}.0)));
    let seg = len / f32(n);
    var k = 0;
    var going = true;
#if SKIP_EMPTY
    var walk = cellWalkStart(u.cameraPosition, dir, t.x);
    let maxCells = u.gridCells.x + u.gridCells.y + u.gridCells.z + 3;
    for (var c = 0; c < maxCells && k < n && going; c++) {
      let empty = textureLoad(majorantGrid, cellWalkTexel(walk), 0).r == 0.0;
      let tExit = cellWalkStep(&walk);
      let tEnd = select(tExit, 3.0e38, tExit >= t.y);
      if (empty) { k = latticeIndexAt(tEnd, t.x, seg, offset, k, n); continue; }
      for (; k < n && going; k++) {
        let s = t.x + (f32(k) + offset) * seg;
        if (s >= tEnd) { break; }
        going = eamSample(dir, s, seg, &color, &transmittance, &guide);
      }
    }
#endif
    for (; k < n && going; k++) { going = eamSample(dir, t.x + (f32(k) + offset) * seg, seg, &color, &transmittance, &guide); }
  }
  var o: VptOut;
#if VPT_SLICE_PLANE
  if (onPlane) {
    o.out0 = vec4f(color + transmittance * slicePlaneColor(u.cameraPosition + dir * tPlane), 1.0);
  } else {
#endif
#if VPT_DEPTH_LIMIT
  o.out0 = vec4f(color, 1.0 - transmittance);
#else
  o.out0 = vec4f(color + transmittance * u.background.rgb, 1.0 - transmittance);
#endif
#if VPT_SLICE_PLANE
  }
#endif
#if VPT_GUIDES
  if (guide.x > 0.0) {
    let tg = guide.y / guide.x;
    let pg = u.cameraPosition + dir * tg;
    o.out1 = guideNormalDepth(pg, tg);
    o.out2 = guideAlbedo(transferAt(pg).rgb);
  }
#endif
  return o;
}
`;
