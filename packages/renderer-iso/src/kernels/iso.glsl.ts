import { GLSL_CELL_WALK, GLSL_DEPTH_LIMIT, MAX_MARCH_STEPS } from '@vpt/core';
import { GLSL_ENVIRONMENT_MAP, GLSL_SAMPLING } from '@vpt/core/sampling';
import { GLSL_SAMPLE_DIMS } from '@vpt/core/blue-noise';

// Monte Carlo isosurface rendering (Lesar et al. 2018, "Real-Time Interactive Platform-
// Agnostic Volumetric Path Tracing in WebGL 2.0", the ISO renderer): each iteration finds
// the first crossing of an iso value along a jittered camera ray (bisection refinement),
// and the accumulation keeps the nearest hit and its normal. Shading is estimated per
// iteration at the hit (one stochastic shadow ray per light, one ambient-occlusion ray,
// and one environment importance sample with MIS for lat-long maps) and averaged, so the
// image converges to soft shadows. Surfaces with opacity < 1 use stochastic transparency
// (Enderton et al. 2010): every crossing, by camera and shadow rays alike, is opaque with
// probability alpha_k, independently, so the mean is alpha-compositing in depth order.
// One march for scalar and channel scenes (isoValuesAt: surface k reads component k); VPT_LABELS
// adds the visible labels' mask as one more opaque surface at its 0.5 level (core's scene/labels.ts).
// BLUE_NOISE (sampler 'blue-noise', core's SAMPLE_DIMS): the pixel jitter, the camera march's offset
// and the cosine-weighted environment (AO) sample are blue-noise-rotated rank-1 dimensions 0-4.

/** Helpers shared by the generate kernel (twin of iso.wgsl.ts). */
const ISO_COMMON = /* glsl */ `
${GLSL_SAMPLE_DIMS}
const int ISO_REFINE_STEPS = 10;

#if SKIP_EMPTY
${GLSL_CELL_WALK}
// Empty-space skipping through the majorant grid's per-cell value ranges: a cell none of whose
// visible iso values lies inside its range (padded against the filter's rounding) holds no
// crossing, so the samples after the first one in it lie on that one's side of every surface.
bool isoCellCrossable(ivec2 texel) {
  vec2 r = texelFetch(majorantRanges, texel, 0).rg;
  float lo = min(volumeValue(r.x), volumeValue(r.y)) - 1e-5;
  float hi = max(volumeValue(r.x), volumeValue(r.y)) + 1e-5;
  for (int k = 0; k < ISO_COUNT; k++) {
    if (u.isoSurface[k].a > 0.0 && lo < u.isoValues[k] && u.isoValues[k] <= hi) { return true; }
  }
  return false;
}
struct IsoCells { CellWalk walk; float tEnd; bool crossable; };
IsoCells isoCellsStart(vec3 o, vec3 d, float t0) { return IsoCells(cellWalkStart(o, d, t0), -1.0, true); }
// The index of the next sample of the march t0 + (j + offset)·seg after sample i at t: i + 1, or past the end of
// t's cell when no surface can cross it (the caller re-samples the one before).
int isoNextSample(inout IsoCells c, float t, float t0, float t1, float seg, float offset, int i, int n) {
  int maxCells = u.gridCells.x + u.gridCells.y + u.gridCells.z + 3;
  for (int g = 0; g < maxCells && t >= c.tEnd; g++) {
    c.crossable = isoCellCrossable(cellWalkTexel(c.walk));
    float e = cellWalkStep(c.walk);
    c.tEnd = e >= t1 ? 3.0e38 : e;
  }
  if (c.crossable || t >= c.tEnd) { return i + 1; }
  return max(i + 1, latticeIndexAt(c.tEnd, t0, seg, offset, i + 1, n + 1));
}
#endif

// The values the surfaces lie on at p: surface k reads component k (a channel scene: drawn
// channel k; a scalar one: the volume's value in every component). One march serves both.
vec4 isoValuesAt(vec3 p) {
#if VPT_CHANNELS
  return sampleChannels(p);
#else
  return vec4(sampleVolume(p));
#endif
}
#if VPT_LABELS
// A scene's labels (core's scene/labels.ts) as one more surface, ISO_LABEL_SURFACE: the 0.5
// level of the trilinear filter of the visible labels' binary mask (labelMask: nearest reads of
// the 8 neighbours, so ids are never blended, only inside/outside), opaque, in the label's colour.
const int ISO_LABEL_SURFACE = 4;
#endif
// Surface k's field at p.
float isoFieldAt(vec3 p, int k) {
#if VPT_LABELS
  if (k == ISO_LABEL_SURFACE) { return labelMask(p); }
#endif
  return isoValuesAt(p)[k];
}
// Bisection on f(t) = field_k(o + t d) - iso between ta (f = fa) and tb, which bracket a crossing.
float isoRefine(vec3 o, vec3 d, float ta, float fa, float tb, float iso, int k) {
  for (int i = 0; i < ISO_REFINE_STEPS; i++) {
    float tm = 0.5 * (ta + tb);
    float fm = isoFieldAt(o + d * tm, k) - iso;
    if ((fm >= 0.0) == (fa >= 0.0)) { ta = tm; fa = fm; } else { tb = tm; }
  }
  return 0.5 * (ta + tb);
}

// March the camera ray over [t0, t1] (randomly offset steps). x: t of the first crossing made
// opaque by stochastic transparency (-1: none), y: its surface; z, w: the first crossing of
// any visible surface, whatever the coin said (the depth buffer).
vec4 isoTrace(vec3 o, vec3 d, float t0, float t1, inout uint rng) {
  float offset = rngDim(rng, 2);
  int n = max(1, int(min(ceil((t1 - t0) / u.stepSize), ${MAX_MARCH_STEPS}.0)));
  float seg = (t1 - t0) / float(n);
  float tPrev = t0;
  vec4 vPrev = isoValuesAt(o + d * t0);
#if VPT_LABELS
  float mPrev = labelMask(o + d * t0);
#endif
  vec4 r = vec4(-1.0);
#if SKIP_EMPTY
  IsoCells cells = isoCellsStart(o, d, t0);
#endif
  for (int i = 0; i <= n; i++) {
    float t = min(t0 + (float(i) + offset) * seg, t1);
    vec4 v = isoValuesAt(o + d * t);
    for (int k = 0; k < ISO_COUNT; k++) {
      float iso = u.isoValues[k];
      float alpha = u.isoSurface[k].a;
      if ((vPrev[k] >= iso) != (v[k] >= iso) && alpha > 0.0) {
        float tc = isoRefine(o, d, tPrev, vPrev[k] - iso, t, iso, k);
        if (r.z < 0.0 || tc < r.z) { r.z = tc; r.w = float(k); }
        bool opaque = true;
        if (alpha < 1.0) { opaque = rngNext(rng) < alpha; }
        if (opaque && (r.x < 0.0 || tc < r.x)) { r.x = tc; r.y = float(k); }
      }
    }
#if VPT_LABELS
    float m = labelMask(o + d * t);
    if ((mPrev >= 0.5) != (m >= 0.5)) {
      float tc = isoRefine(o, d, tPrev, mPrev - 0.5, t, 0.5, ISO_LABEL_SURFACE);
      if (r.z < 0.0 || tc < r.z) { r.z = tc; r.w = float(ISO_LABEL_SURFACE); }
      if (r.x < 0.0 || tc < r.x) { r.x = tc; r.y = float(ISO_LABEL_SURFACE); }
    }
    mPrev = m;
#endif
    if (r.x >= 0.0) { return r; }
    tPrev = t;
    vPrev = v;
#if SKIP_EMPTY
    int next = isoNextSample(cells, t, t0, t1, seg, offset, i, n);
    if (next > i + 1 && next <= n) {
      tPrev = min(t0 + (float(next - 1) + offset) * seg, t1);
      vPrev = isoValuesAt(o + d * tPrev);
    }
    i = next - 1;
#endif
  }
  return r;
}

// 1 when the ray o + s d, 0 < s <= maxDist, crosses no surface that stochastic transparency
// makes opaque, else 0 (a shadow or ambient-occlusion ray).
float isoVisibility(vec3 o, vec3 d, float maxDist, inout uint rng) {
#if VPT_CLIP
  vec2 tb = keptInterval(o, d);
#else
  vec2 tb = intersectBox(o, d, u.boxMin, u.boxMax);
#endif
  float t1 = min(tb.y, maxDist);
  if (!(tb.x < t1)) { return 1.0; }
  float t0 = tb.x;
  float offset = rngNext(rng);
  int n = max(1, int(min(ceil((t1 - t0) / u.stepSize), ${MAX_MARCH_STEPS}.0)));
  float seg = (t1 - t0) / float(n);
  vec4 vPrev = isoValuesAt(o + d * t0);
#if VPT_LABELS
  float mPrev = labelMask(o + d * t0);
#endif
#if SKIP_EMPTY
  IsoCells cells = isoCellsStart(o, d, t0);
#endif
  for (int i = 0; i <= n; i++) {
    float t = min(t0 + (float(i) + offset) * seg, t1);
    vec4 v = isoValuesAt(o + d * t);
    for (int k = 0; k < ISO_COUNT; k++) {
      float iso = u.isoValues[k];
      float alpha = u.isoSurface[k].a;
      if ((vPrev[k] >= iso) != (v[k] >= iso) && alpha > 0.0) {
        if (alpha >= 1.0) { return 0.0; }
        if (rngNext(rng) < alpha) { return 0.0; }
      }
    }
#if VPT_LABELS
    float m = labelMask(o + d * t);
    if ((mPrev >= 0.5) != (m >= 0.5)) { return 0.0; }
    mPrev = m;
#endif
    vPrev = v;
#if SKIP_EMPTY
    int next = isoNextSample(cells, t, t0, t1, seg, offset, i, n);
    if (next > i + 1 && next <= n) { vPrev = isoValuesAt(o + d * min(t0 + (float(next - 1) + offset) * seg, t1)); }
    i = next - 1;
#endif
  }
  return 1.0;
}

// Unit normal from central differences of surface k's trilinear field (one voxel apart), turned
// toward the viewer (surfaces are two-sided); -d where the gradient vanishes.
vec3 isoNormal(vec3 p, vec3 d, int k) {
  vec3 h = u.gradientStep;
  float gx = (isoFieldAt(p + vec3(h.x, 0.0, 0.0), k) - isoFieldAt(p - vec3(h.x, 0.0, 0.0), k)) / (2.0 * h.x);
  float gy = (isoFieldAt(p + vec3(0.0, h.y, 0.0), k) - isoFieldAt(p - vec3(0.0, h.y, 0.0), k)) / (2.0 * h.y);
  float gz = (isoFieldAt(p + vec3(0.0, 0.0, h.z), k) - isoFieldAt(p - vec3(0.0, 0.0, h.z), k)) / (2.0 * h.z);
  vec3 g = vec3(gx, gy, gz);
  if (!(dot(g, g) > 1e-30)) { return -d; }
  vec3 n = normalize(g);
  return dot(n, d) > 0.0 ? -n : n;
}

// Surface k's colour at p (normal n, toward the viewer): the label surface takes the label of the
// voxel one step inside (n points out of the label where the camera is outside), else the one at p.
vec3 isoAlbedo(int k, vec3 p, vec3 n) {
#if VPT_LABELS
  if (k == ISO_LABEL_SURFACE) {
    vec4 inner = labelAt(p - n * u.gradientStep);
    return inner.a > 0.0 ? inner.rgb : labelAt(p).rgb;
  }
#endif
  return u.isoSurface[k].rgb;
}

// Lambert plus the energy-normalized Blinn-Phong lobe (s + 8)/(8 pi) (n.h)^s (Akenine-Moller,
// Haines & Hoffman, Real-Time Rendering 3rd ed., 2008, ch. 7 "Advanced Shading"), mixed by u.specular.
vec3 isoBrdf(vec3 n, vec3 wi, vec3 wo, vec3 albedo) {
  vec3 hs = wi + wo;
  float lobe = 0.0;
  float h2 = dot(hs, hs);
  if (h2 > 1e-12) {
    float nh = max(dot(n, hs / sqrt(h2)), 0.0);
    lobe = (u.shininess + 8.0) * (1.0 / (8.0 * VPT_PI)) * exp2(u.shininess * log2(max(nh, 1e-8)));
  }
  return albedo * ((1.0 - u.specular) / VPT_PI) + vec3(u.specular * lobe);
}

// Radiance of the environment seen along d (the background where no surface is hit).
vec3 isoEnvironment(vec3 d) {
#if ISO_ENV == 2
  return environmentLookup(d).rgb;
#else
  return u.background.rgb;
#endif
}

// One-sample estimate of the radiance leaving p toward wo (Kajiya's rendering equation,
// direct lighting only): directional lights with a shadow ray each (a light of angular
// radius > 0 is sampled uniformly over its cone), and the environment through one
// cosine-weighted ambient-occlusion ray, plus, for a lat-long map, one importance sample
// combined by the balance heuristic (Veach & Guibas 1995).
vec3 isoShade(vec3 p, vec3 n, vec3 wo, vec3 albedo, inout uint rng) {
  vec3 radiance = vec3(0.0);
  vec3 origin = p + n * u.rayEpsilon;
  for (int l = 0; l < ISO_LIGHTS; l++) {
    vec4 ld = u.isoLightDirection[l];
    vec3 wi = ld.xyz;
#if ISO_SOFT_LIGHTS
    float c1 = rngNext(rng);
    float c2 = rngNext(rng);
    float cosT = 1.0 - c1 * (1.0 - ld.w);
    float sinT = sqrt(max((1.0 - cosT) * (1.0 + cosT), 0.0));
    wi = directionAround(ld.xyz, cosT, sinT, 2.0 * VPT_PI * c2);
#endif
    float cosI = dot(n, wi);
    if (cosI > 0.0) {
      float vis = 1.0;
#if ISO_SHADOWS
      vis = isoVisibility(origin, wi, 1e30, rng);
#endif
      radiance += u.isoLightIrradiance[l].rgb * (cosI * vis) * isoBrdf(n, wi, wo, albedo);
    }
  }
#if ISO_ENV > 0
  float e1 = rngDim(rng, 3);
  float e2 = rngDim(rng, 4);
  float cosC = sqrt(1.0 - e1);
  vec3 wc = directionAround(n, cosC, sqrt(e1), 2.0 * VPT_PI * e2);
  float visC = 1.0;
#if ISO_AO
  visC = isoVisibility(origin, wc, u.aoRadius, rng);
#endif
  // f L cos / pdf with pdf = cos / pi: the cosine cancels.
#if ISO_ENV == 2
  vec4 envC = environmentLookup(wc);
  float pdfC = cosC * (1.0 / VPT_PI);
  float wC = pdfC > 0.0 ? pdfC / (pdfC + envC.a) : 0.0;
  radiance += envC.rgb * (visC * VPT_PI * wC) * isoBrdf(n, wc, wo, albedo);
  float s1 = rngNext(rng);
  float s2 = rngNext(rng);
  EnvSample es = sampleEnvironment(s1, s2);
  float cosE = dot(n, es.direction);
  if (cosE > 0.0 && es.pdf > 0.0) {
    float visE = 1.0;
#if ISO_AO
    visE = isoVisibility(origin, es.direction, u.aoRadius, rng);
#endif
    float pdfCE = cosE * (1.0 / VPT_PI);
    float wE = es.pdf / (es.pdf + pdfCE);
    radiance += es.radiance * (visE * cosE * wE / es.pdf) * isoBrdf(n, es.direction, wo, albedo);
  }
#else
  radiance += u.background.rgb * (visC * VPT_PI) * isoBrdf(n, wc, wo, albedo);
#endif
#endif
  return radiance;
}
`;

// The environment-map chunk names the envMap textures, bound for a lat-long map only.
export const generate =
  GLSL_SAMPLING +
  '\n#if ISO_ENV == 2\n' +
  GLSL_ENVIRONMENT_MAP +
  '\n#endif\n#if VPT_DEPTH_LIMIT\n' +
  GLSL_DEPTH_LIMIT +
  '\n#endif\n' +
  ISO_COMMON +
  /* glsl */ `
// out0: shaded radiance of this sample (a = 1 where a surface was hit, else the environment, a = 0).
// out1: the first visible crossing: (t along the unit camera ray, viewer-facing normal), t = -1 for none.
void main() {
  ivec2 pixel = vptPixel();
  ivec2 size = vptTargetSize();
  uint rng = rngInit(pixel, u.iteration + u.sampleBase, u.seed);
  sampleDimsInit(pixel);
#if ISO_JITTER
  vec3 dir = jitteredCameraRayDims(pixel, size, rng);
#else
  vec3 dir = cameraRayDirection(vec2((float(pixel.x) + 0.5) / float(size.x), (float(pixel.y) + 0.5) / float(size.y)));
#endif
  vec3 o = u.cameraPosition;
#if VPT_CLIP
  vec2 tb = keptInterval(o, dir);
#else
  vec2 tb = intersectBox(o, dir, u.boxMin, u.boxMax);
#endif
#if VPT_DEPTH_LIMIT
  tb.y = min(tb.y, depthLimitAlong(pixel, dir));
#endif
#if VPT_SLICE_PLANE
  // The slice plane is opaque: the ray ends there (scene/slice-plane.ts).
  float tPlane = slicePlaneHit(o, dir);
  bool onPlane = tPlane > 0.0 && tPlane <= tb.y;
  if (onPlane) tb.y = tPlane;
#endif
  vec4 hit = vec4(-1.0);
  if (tb.x < tb.y) { hit = isoTrace(o, dir, tb.x, tb.y, rng); }
#if VPT_DEPTH_LIMIT
  // Composited over a scene (RenderContext.setDepthLimit): no environment where no surface is hit.
  vec4 color = vec4(0.0);
#else
  vec4 color = vec4(isoEnvironment(dir), 0.0);
#endif
#if VPT_SLICE_PLANE
  // Unlit: where no surface in front is shaded, the ray sees the plane's colour.
  if (onPlane) color = vec4(slicePlaneColor(o + dir * tPlane), 1.0);
#endif
  vec4 nearest = vec4(-1.0, 0.0, 0.0, 0.0);
  if (hit.z >= 0.0) {
    vec3 nz = isoNormal(o + dir * hit.z, dir, int(hit.w));
    nearest = vec4(hit.z, nz);
    if (hit.x >= 0.0) {
      int k = int(hit.y);
      vec3 n = hit.x == hit.z && hit.y == hit.w ? nz : isoNormal(o + dir * hit.x, dir, k);
      vec3 albedo = isoAlbedo(k, o + dir * hit.x, n);
      color = vec4(isoShade(o + dir * hit.x, n, -dir, albedo, rng), 1.0);
#if VPT_GUIDES
      // Denoiser guides at the shaded surface: its normal, depth and diffuse colour.
      vpt_out2 = vec4(n, hit.x);
      vpt_out3 = guideAlbedo(albedo);
#endif
    }
  }
  vpt_out0 = color;
  vpt_out1 = nearest;
#if VPT_GUIDES
  if (hit.x < 0.0) { vpt_out2 = vec4(0.0); vpt_out3 = vec4(0.0); }
#endif
}
`;

// Running mean of the shaded samples; nearest hit by a depth test (t < 0: no surface yet).
export const integrate = /* glsl */ `
void main() {
  ivec2 p = vptPixel();
  vec4 f0 = texelFetch(frame0, p, 0);
  vec4 f1 = texelFetch(frame1, p, 0);
  if (u.iteration == 0u) { vpt_out0 = f0; vpt_out1 = f1; return; }
  vec4 a0 = texelFetch(accum0, p, 0);
  vec4 a1 = texelFetch(accum1, p, 0);
  float w = 1.0 / float(u.iteration + 1u);
  vpt_out0 = a0 + (f0 - a0) * w;
  bool nearer = f1.x >= 0.0 && (a1.x < 0.0 || f1.x < a1.x);
  vpt_out1 = nearer ? f1 : a1;
}
`;

// ISO_OUTPUT 0: the shaded image; 1: depth (t, t, t, 1); 2: normal (n, 1); (0, 0, 0, 0) where nothing was hit.
export const render = /* glsl */ `
void main() {
  ivec2 p = vptPixel();
#if ISO_OUTPUT == 0
  vpt_out0 = texelFetch(accum0, p, 0);
#else
  vec4 a = texelFetch(accum1, p, 0);
#if ISO_OUTPUT == 1
  vpt_out0 = a.x >= 0.0 ? vec4(a.x, a.x, a.x, 1.0) : vec4(0.0);
#else
  vpt_out0 = a.x >= 0.0 ? vec4(a.yzw, 1.0) : vec4(0.0);
#endif
#endif
}
`;
