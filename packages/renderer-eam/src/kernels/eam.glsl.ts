import { GLSL_CELL_WALK, GLSL_DEPTH_LIMIT, MAX_MARCH_STEPS } from '@vpt/core';
import { GLSL_SAMPLE_DIMS } from '@vpt/core/blue-noise';

// Emission-absorption (Max 1995, "Optical models for direct volume rendering", IEEE TVCG 1(2), the emission + absorption model)
// by a stratified, randomly offset ray march; alpha = 1 - exp(-sigma_t * segment length),
// so a homogeneous medium yields exactly c·(1 - exp(-sigma_t·L)).
// SKIP_EMPTY (empty-space skipping through the majorant grid, core's cell walk): a cell whose
// opacity bound is 0 holds only samples with alpha = 0, which add exactly 0 colour and leave the
// transmittance as it is, so the march jumps over its samples and the image keeps its bits.
// VPT_DEPTH_LIMIT (an opaque surface on a shared context, RenderContext.setDepthLimit): the march
// ends at the surface and the background is left out, so rgb + (1 − a) · surface composites it.
// BLUE_NOISE (sampler 'blue-noise', core's SAMPLE_DIMS): the pixel jitter and the march offset are
// blue-noise-rotated rank-1 dimensions 0-2; 'pcg' draws them from the PCG stream as before.

export const generate = /* glsl */ `
${GLSL_SAMPLE_DIMS}
#if SKIP_EMPTY
${GLSL_CELL_WALK}
#endif
#if VPT_DEPTH_LIMIT
${GLSL_DEPTH_LIMIT}
#endif
// One sample of the march at distance s; false once the transmittance fell below the cutoff.
// guide: the denoiser's (sum of T·alpha, sum of T·alpha·s), only accumulated under VPT_GUIDES.
bool eamSample(vec3 dir, float s, float seg, inout vec3 color, inout float transmittance, inout vec2 guide) {
  vec4 tf = transferAt(u.cameraPosition + dir * s);
  float alpha = 1.0 - exp(-(u.densityScale * tf.a) * seg);
  color += (transmittance * alpha) * tf.rgb;
#if VPT_GUIDES
  guide += (transmittance * alpha) * vec2(1.0, s);
#endif
  transmittance *= 1.0 - alpha;
  if (transmittance < u.cutoff) { transmittance = 0.0; return false; }
  return true;
}
void main() {
  ivec2 pixel = vptPixel();
  uint rng = rngInit(pixel, u.iteration + u.sampleBase, u.seed);
  sampleDimsInit(pixel);
  vec3 dir = jitteredCameraRayDims(pixel, vptTargetSize(), rng);
#if VPT_CLIP
  vec2 t = keptInterval(u.cameraPosition, dir);
#else
  vec2 t = intersectBox(u.cameraPosition, dir, u.boxMin, u.boxMax);
#endif
#if VPT_DEPTH_LIMIT
  t.y = min(t.y, depthLimitAlong(pixel, dir));
#endif
#if VPT_SLICE_PLANE
  // The slice plane is opaque: the ray ends there (scene/slice-plane.ts).
  float tPlane = slicePlaneHit(u.cameraPosition, dir);
  bool onPlane = tPlane > 0.0 && tPlane <= t.y;
  if (onPlane) t.y = tPlane;
#endif
  vec3 color = vec3(0.0);
  float transmittance = 1.0;
  // Denoiser guides at the mean termination depth: segments weighted by T·alpha, their share of the pixel.
  vec2 guide = vec2(0.0);
  if (t.x < t.y) {
    float offset = rngDim(rng, 2);
    float len = t.y - t.x;
    int n = max(1, int(min(ceil(len / u.stepSize), ${MAX_MARCH_STEPS}.0)));
    float seg = len / float(n);
    int k = 0;
    bool going = true;
#if SKIP_EMPTY
    CellWalk walk = cellWalkStart(u.cameraPosition, dir, t.x);
    int maxCells = u.gridCells.x + u.gridCells.y + u.gridCells.z + 3;
    for (int c = 0; c < maxCells && k < n && going; c++) {
      bool empty = texelFetch(majorantGrid, cellWalkTexel(walk), 0).r == 0.0;
      float tExit = cellWalkStep(walk);
      float tEnd = tExit >= t.y ? 3.0e38 : tExit;
      if (empty) { k = latticeIndexAt(tEnd, t.x, seg, offset, k, n); continue; }
      for (; k < n && going; k++) {
        float s = t.x + (float(k) + offset) * seg;
        if (s >= tEnd) break;
        going = eamSample(dir, s, seg, color, transmittance, guide);
      }
    }
#endif
    for (; k < n && going; k++) going = eamSample(dir, t.x + (float(k) + offset) * seg, seg, color, transmittance, guide);
  }
#if VPT_SLICE_PLANE
  // The opaque, unlit plane behind what is in front: front radiance + transmittance × its colour.
  if (onPlane) {
    vpt_out0 = vec4(color + transmittance * slicePlaneColor(u.cameraPosition + dir * tPlane), 1.0);
  } else {
#endif
#if VPT_DEPTH_LIMIT
  vpt_out0 = vec4(color, 1.0 - transmittance);
#else
  vpt_out0 = vec4(color + transmittance * u.background.rgb, 1.0 - transmittance);
#endif
#if VPT_SLICE_PLANE
  }
#endif
#if VPT_GUIDES
  vpt_out1 = vec4(0.0);
  vpt_out2 = vec4(0.0);
  if (guide.x > 0.0) {
    float tg = guide.y / guide.x;
    vec3 pg = u.cameraPosition + dir * tg;
    vpt_out1 = guideNormalDepth(pg, tg);
    vpt_out2 = guideAlbedo(transferAt(pg).rgb);
  }
#endif
}
`;
