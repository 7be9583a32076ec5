import { GLSL_CELL_WALK, GLSL_DEPTH_LIMIT, MAX_MARCH_STEPS } from '@vpt/core';
import { GLSL_SAMPLE_DIMS } from '@vpt/core/blue-noise';

// Monte Carlo maximum intensity projection (Lesar, Bohak, Marolt 2018, "Real-Time Interactive Platform-Agnostic Volumetric Path Tracing in WebGL 2.0", its MIP renderer): each
// iteration marches the pixel-centre ray with a random sample offset; the accumulation keeps the
// max, which converges to the maximum along that ray. (A maximum over jittered rays would be the
// maximum over the pixel's footprint, a dilated image that converges slowly at every edge.)
// SKIP_EMPTY (empty-space skipping through the majorant grid's value ranges, core's cell walk):
// a cell whose largest value cannot exceed the running maximum is jumped over, and the march
// ends once the maximum is 1 (the largest normalized value); the maximum keeps its bits.
// VPT_LABELS (a label volume, core's scene/labels.ts): the most opaque visible label on the samples is kept
// beside the maximum and its colour laid over the grey maximum with its opacity.
// VPT_CHANNELS (a channel scene): the maximum per channel (a miss is marked −1), each shown
// through its transfer function in its colour, the channels added (as microscopy viewers do).
// BLUE_NOISE (sampler 'blue-noise', core's SAMPLE_DIMS): the sample offset is the blue-noise-rotated
// golden-ratio dimension 2; 'pcg' draws it from the PCG stream as before.

export const generate = /* glsl */ `
${GLSL_SAMPLE_DIMS}
#if VPT_DEPTH_LIMIT
${GLSL_DEPTH_LIMIT}
#endif
#if SKIP_EMPTY
${GLSL_CELL_WALK}
// The largest normalized value a point of the current cell can have: its texel range mapped as
// sampleVolume maps a texel (an inverted range swaps the ends), padded against the filter's rounding.
float cellMaxValue(CellWalk walk) {
  vec2 r = texelFetch(majorantRanges, cellWalkTexel(walk), 0).rg;
  float m = max(volumeValue(r.x), volumeValue(r.y));
  return m > 0.0 ? m + 1e-5 : 0.0;
}
#endif
void main() {
  ivec2 pixel = vptPixel();
  uint rng = rngInit(pixel, u.iteration + u.sampleBase, u.seed);
  sampleDimsInit(pixel);
  vec3 dir = centreCameraRay(pixel, vptTargetSize());
#if VPT_CLIP
  vec2 t = keptInterval(u.cameraPosition, dir);
#else
  vec2 t = intersectBox(u.cameraPosition, dir, u.boxMin, u.boxMax);
#endif
#if VPT_DEPTH_LIMIT
  t.y = min(t.y, depthLimitAlong(pixel, dir));
#endif
#if VPT_CHANNELS
  vec4 maxValue = vec4(0.0);
#else
#if VPT_SLICE_PLANE
  // The slice plane is opaque: the ray ends there (scene/slice-plane.ts).
  float tPlane = slicePlaneHit(u.cameraPosition, dir);
  bool onPlane = tPlane > 0.0 && tPlane <= t.y;
  if (onPlane) t.y = tPlane;
#endif
  float maxValue = 0.0;
#endif
#if VPT_LABELS
  // The most opaque visible label the samples meet (ties: the smaller id, so the order of samples does not matter).
  float labelA = 0.0;
  int labelId = 0;
#endif
  float coverage = 0.0;
  if (t.x < t.y) {
    coverage = 1.0;
    float offset = rngDim(rng, 2);
    float len = t.y - t.x;
    int n = max(1, int(min(ceil(len / u.stepSize), ${MAX_MARCH_STEPS}.0)));
    float seg = len / float(n);
    int k = 0;
#if SKIP_EMPTY
    CellWalk walk = cellWalkStart(u.cameraPosition, dir, t.x);
    int maxCells = u.gridCells.x + u.gridCells.y + u.gridCells.z + 3;
    for (int c = 0; c < maxCells && k < n && maxValue < 1.0; c++) {
      bool below = cellMaxValue(walk) <= maxValue;
      float tExit = cellWalkStep(walk);
      float tEnd = tExit >= t.y ? 3.0e38 : tExit;
      if (below) { k = latticeIndexAt(tEnd, t.x, seg, offset, k, n); continue; }
      for (; k < n; k++) {
        float s = t.x + (float(k) + offset) * seg;
        if (s >= tEnd) break;
        maxValue = max(maxValue, sampleVolume(u.cameraPosition + dir * s));
      }
    }
    if (maxValue >= 1.0) k = n;
#endif
    for (; k < n; k++) {
      float s = t.x + (float(k) + offset) * seg;
#if VPT_CHANNELS
      maxValue = max(maxValue, sampleChannels(u.cameraPosition + dir * s));
#else
      maxValue = max(maxValue, sampleVolume(u.cameraPosition + dir * s));
#endif
#if VPT_LABELS
      int id = labelIdAt(u.cameraPosition + dir * s);
      float la = labelEntry(id).a;
      if (la > labelA || (la == labelA && la > 0.0 && id < labelId)) {
        labelA = la;
        labelId = id;
      }
#endif
    }
  }
#if VPT_CHANNELS
  // The pixel-centre ray is the same every iteration, so a miss is the same too.
  vpt_out0 = coverage > 0.0 ? maxValue : vec4(-1.0);
#else
#if VPT_DEPTH_LIMIT
  // Composited over a scene: the maximum is its own opacity, so what is behind shows where it is low.
  coverage = maxValue;
#endif
  vpt_out0 = vec4(maxValue, 0.0, 0.0, coverage);
#if VPT_LABELS
  // The label's opacity and id in g, b (exact in float32 up to 2^24).
  vpt_out0 = vec4(maxValue, labelA, float(labelId), coverage);
#endif
#if VPT_SLICE_PLANE
  // On the plane: its colour, the same every iteration (centre ray), in gba with a < 0 marking it
  // (b stored as -1 - b); coverage is 1 there.
  if (onPlane) {
    vec3 c = slicePlaneColor(u.cameraPosition + dir * tPlane);
    vpt_out0 = vec4(maxValue, c.r, c.g, -1.0 - c.b);
  }
#endif
#endif
}
`;

// Keep the running maximum of the value; coverage (whether the pixel-centre ray meets the box) is a running mean.
export const integrate = /* glsl */ `
void main() {
  ivec2 p = vptPixel();
  vec4 f = texelFetch(frame0, p, 0);
  if (u.iteration == 0u) { vpt_out0 = f; return; }
  vec4 a = texelFetch(accum0, p, 0);
#if VPT_CHANNELS
  vpt_out0 = max(a, f);
#else
#if VPT_SLICE_PLANE
  // A pixel on the slice plane keeps the plane's colour (gba) beside the running maximum.
  if (f.a < 0.0) { vpt_out0 = vec4(max(a.r, f.r), f.gba); return; }
#endif
  float w = 1.0 / float(u.iteration + 1u);
  vpt_out0 = vec4(max(a.r, f.r), 0.0, 0.0, a.a + (f.a - a.a) * w);
#if VPT_LABELS
  // The more opaque label of the two (ties: the smaller id).
  bool take = f.g > a.g || (f.g == a.g && f.g > 0.0 && f.b < a.b);
  vpt_out0 = vec4(max(a.r, f.r), take ? f.g : a.g, take ? f.b : a.b, a.a + (f.a - a.a) * w);
#endif
#endif
}
`;

export const render = /* glsl */ `
#if VPT_CHANNELS
// Channel k's maximum through row k of the TF texture (as transferLookup): opacity-weighted colour.
vec3 mipChannel(float value, int row) {
  float x = clamp(value, 0.0, 1.0) * float(u.tfSize - 1);
  float x0 = floor(x);
  int i0 = int(x0);
  int i1 = min(i0 + 1, u.tfSize - 1);
  vec4 a = texelFetch(transferFunction, ivec2(i0, row), 0);
  vec4 t = a + (texelFetch(transferFunction, ivec2(i1, row), 0) - a) * (x - x0);
  return t.a * t.rgb;
}
#endif
void main() {
  vec4 a = texelFetch(accum0, vptPixel(), 0);
#if VPT_CHANNELS
  if (a.x < 0.0) { vpt_out0 = vec4(0.0); return; }
  vec3 rgb = vec3(0.0);
  for (int k = 0; k < VPT_CHANNELS; k++) { rgb += mipChannel(a[k], k); }
  float coverage = 1.0;
#if VPT_DEPTH_LIMIT
  coverage = clamp(max(max(a.x, a.y), max(a.z, a.w)), 0.0, 1.0);
#endif
  vpt_out0 = vec4(rgb, coverage);
#else
  vpt_out0 = vec4(a.r, a.r, a.r, a.a);
#if VPT_LABELS
  // The label's colour over the grey maximum with its opacity (clamped to 1), from the label table.
  if (a.a >= 0.0 && a.g > 0.0) {
    int id = int(a.b + 0.5);
    ivec2 size = textureSize(labelTable, 0);
    vec3 c = texelFetch(labelTable, ivec2(id % size.x, id / size.x), 0).rgb;
    float w = clamp(a.g, 0.0, 1.0);
    vpt_out0 = vec4(vec3(a.r) + (c - vec3(a.r)) * w, max(a.a, w));
  }
#endif
#if VPT_SLICE_PLANE
  // The plane behind the maximum, which is its own opacity (as over a depth-limit surface): m + (1 - m) · plane.
  if (a.a < 0.0) vpt_out0 = vec4(vec3(a.r) + (1.0 - a.r) * vec3(a.g, a.b, -1.0 - a.a), 1.0);
#endif
#endif
}
`;
