import { GLSL_DEPTH_LIMIT } from '@vpt/core';

// Volumetric path tracing (Kajiya 1986, "The Rendering Equation"; Pharr, Jakob, Humphreys, PBR 4th ed., ch. 14 "Light Transport II: Volume Rendering"): free
// flights by delta tracking, Henyey–Greenstein phase sampling, next-event estimation to the
// directional lights and the environment combined with phase sampling by multiple importance
// sampling (Veach & Guibas 1995), Russian roulette on the path throughput. Real collisions
// multiply the throughput by the RGB albedo (extinction is grey), so coloured albedo needs no
// max(rgb) scattering probability. Preprocessed with the feature flags of features.ts.
// VPT_DEPTH_LIMIT (an opaque surface on a shared context, RenderContext.setDepthLimit): the
// surface is an opaque boundary for camera rays; a camera ray that reaches it (or leaves the box)
// without a real collision adds nothing and keeps alpha 0, so E[a] = 1 − T and rgb + (1 − a) ·
// surface composites the surface attenuated by the volume's transmittance, without bias.

export const path = /* glsl */ `
#if VPT_DEPTH_LIMIT
${GLSL_DEPTH_LIMIT}
#endif
float maxComponent(vec3 v) { return max(max(v.x, v.y), v.z); }
// Non-finite components become 0 (tested on the bits: compilers may assume NaN never occurs).
float finiteOr0(float x) { return (floatBitsToUint(x) & 0x7f800000u) == 0x7f800000u ? 0.0 : x; }
vec3 finiteOrZero(vec3 v) { return vec3(finiteOr0(v.x), finiteOr0(v.y), finiteOr0(v.z)); }

#if ENV_SAMPLING == 2 && MIS_POWER
float misWeight(float a, float b) { return misPower(a, b); }
#elif ENV_SAMPLING == 2
float misWeight(float a, float b) { return misBalance(a, b); }
#endif

// Environment radiance along d (rgb) and the light-sampling pdf of d (a).
vec4 environmentAlong(vec3 d) {
#if ENV_MAP
  return environmentLookup(d);
#else
  return vec4(u.background.rgb, VPT_INV_4PI);
#endif
}

// Radiance a path receives when it leaves the medium along d after depth real scattering events,
// phasePdf being the pdf of the phase sample that chose d.
vec3 escapedRadiance(vec3 d, int depth, float phasePdf) {
  if (depth == 0) return environmentAlong(d).rgb;
#if ENV_LIGHT && ENV_SAMPLING == 0
  return environmentAlong(d).rgb;
#elif ENV_LIGHT && ENV_SAMPLING == 2
  vec4 e = environmentAlong(d);
  return e.rgb * misWeight(phasePdf, e.a);
#else
  return vec3(0.0);
#endif
}

// Next-event estimation at x for a path arriving along w: the directional lights (delta lights,
// phase sampling cannot hit them) and one light sample of the environment.
// The sample dimensions (core's SAMPLE_DIMS) of the next environment light sample; -1: the PCG stream.
int lightDim = -1;
vec3 directLight(vec3 x, vec3 w, inout uint rng) {
  vec3 Ld = vec3(0.0);
#if LIGHT_COUNT > 0
  for (int i = 0; i < LIGHT_COUNT; i++) {
#if GENERIC
    if (i >= u.lightCount) break;
#endif
    vec3 l = u.lightDirection[i].xyz;
    float ph = hgPhase(u.phaseG, dot(w, l));
#if VPT_CLIP
    vec2 tb = keptInterval(x, l);
#else
    vec2 tb = intersectBox(x, l, u.boxMin, u.boxMax);
#endif
    float T = tb.x < tb.y ? transmittance(x, l, tb.x, tb.y, rng) : 1.0;
    Ld += u.lightIrradiance[i].rgb * (ph * T);
  }
#endif
#if ENV_LIGHT && ENV_SAMPLING != 0
  float xi1 = rngDim(rng, lightDim);
  float xi2 = rngDim(rng, lightDim < 0 ? -1 : lightDim + 1);
  lightDim = -1;
#if ENV_MAP
  EnvSample e = sampleEnvironment(xi1, xi2);
  vec3 wl = e.direction;
  float pl = e.pdf;
  vec3 Le = e.radiance;
#else
  vec3 wl = sampleUniformSphere(xi1, xi2);
  float pl = VPT_INV_4PI;
  vec3 Le = u.background.rgb;
#endif
  if (pl > 0.0) {
    float ph = hgPhase(u.phaseG, dot(w, wl));
#if VPT_CLIP
    vec2 tb = keptInterval(x, wl);
#else
    vec2 tb = intersectBox(x, wl, u.boxMin, u.boxMax);
#endif
    float T = tb.x < tb.y ? transmittance(x, wl, tb.x, tb.y, rng) : 1.0;
#if ENV_SAMPLING == 2
    float wMis = misWeight(pl, ph);
#else
    float wMis = 1.0;
#endif
    Ld += Le * (ph * T * wMis / pl);
  }
#endif
  return Ld;
}

void main() {
  ivec2 pixel = vptPixel();
  uint rng = rngInit(pixel, u.iteration + u.sampleBase, u.seed);
  sampleDimsInit(pixel);
  // Blue noise (BLUE_NOISE) serves the jitter, the camera ray's first free flight and the first light sample.
  flightDim = 2;
  lightDim = 3;
  vec3 dir = jitteredCameraRayDims(pixel, vptTargetSize(), rng);
  vec3 pos = u.cameraPosition;
#if VPT_CLIP
  vec2 tb = keptInterval(pos, dir);
#else
  vec2 tb = intersectBox(pos, dir, u.boxMin, u.boxMax);
#endif
#if VPT_DEPTH_LIMIT
  tb.y = min(tb.y, depthLimitAlong(pixel, dir));
#endif
#if VPT_SLICE_PLANE
  // The slice plane is an opaque surface for camera rays (scene/slice-plane.ts): the flight ends there.
  float tPlane = slicePlaneHit(pos, dir);
  bool onPlane = tPlane > 0.0 && tPlane <= tb.y;
  if (onPlane) tb.y = tPlane;
#endif
#if VPT_GUIDES
  // Denoiser guides at the first real collision (zeros where the camera ray has none).
  vec4 guide0 = vec4(0.0);
  vec4 guide1 = vec4(0.0);
#endif
#if DEBUG_OUTPUT == 1
  float Tcam = tb.x < tb.y ? transmittance(pos, dir, tb.x, tb.y, rng) : 1.0;
  vpt_out0 = vec4(Tcam, Tcam, Tcam, 1.0);
#else
  vec3 L = vec3(0.0);
  vec3 beta = vec3(1.0);
  float alpha = 0.0;
  int depth = 0;
  float phasePdf = 0.0;
  while (trackingSteps < MAX_TRACKING_STEPS) {
    Collision c = Collision(false, 0.0, vec3(0.0));
    if (tb.x < tb.y) c = freeFlight(pos, dir, tb.x, tb.y, rng);
    if (!c.hit) {
#if VPT_SLICE_PLANE
      // A camera ray that reaches the plane sees its colour, emitted and unlit, and ends (alpha 1).
      if (depth == 0 && onPlane) { L += slicePlaneColor(pos + dir * tPlane); alpha = 1.0; break; }
#endif
#if VPT_DEPTH_LIMIT
      if (depth == 0) break;
#endif
      L += beta * escapedRadiance(dir, depth, phasePdf);
      break;
    }
    if (depth == 0) alpha = 1.0;
    pos = pos + dir * c.t;
#if VPT_GUIDES
    if (depth == 0) { guide0 = guideNormalDepth(pos, c.t); guide1 = guideAlbedo(c.albedo); }
#endif
    beta *= c.albedo;
    depth++;
    if (maxComponent(beta) <= 0.0) break;
#if LIGHT_SAMPLES > 1
    // Single scattering: the mean of LIGHT_SAMPLES in-scattering estimates at the one event (the
    // first LIGHT_SAMPLES − 1 here, the last below), as pbrt's light sample counts (PBR 3rd ed.,
    // §14.3.1); the camera ray's walk is shared by them.
#if SINGLE_SCATTERING
    bool severalSamples = true;
#else
    bool severalSamples = u.maxDepth == 1; // the generic kernel: single scattering is maxDepth 1
#endif
    if (severalSamples) beta *= 1.0 / float(LIGHT_SAMPLES);
    for (int k = 1; k < LIGHT_SAMPLES && severalSamples; k++) {
      L += beta * directLight(pos, dir, rng);
#if ENV_LIGHT && ENV_SAMPLING != 1
      float xk1 = rngNext(rng);
      float xk2 = rngNext(rng);
      vec4 pk = sampleHG(dir, u.phaseG, xk1, xk2);
#if VPT_CLIP
      vec2 tk = keptInterval(pos, pk.xyz);
#else
      vec2 tk = intersectBox(pos, pk.xyz, u.boxMin, u.boxMax);
#endif
      float Tk = tk.x < tk.y ? transmittance(pos, pk.xyz, tk.x, tk.y, rng) : 1.0;
      L += beta * escapedRadiance(pk.xyz, depth, pk.w) * Tk;
#endif
    }
#endif
    L += beta * directLight(pos, dir, rng);
    float xi1 = rngNext(rng);
    float xi2 = rngNext(rng);
    vec4 ps = sampleHG(dir, u.phaseG, xi1, xi2);
    phasePdf = ps.w;
#if SINGLE_SCATTERING
    bool last = true;
#else
    bool last = u.maxDepth > 0 && depth >= u.maxDepth;
#endif
    if (last) {
#if ENV_LIGHT && ENV_SAMPLING != 1
      // The phase-sampled direction reaches the environment with the ray's transmittance.
#if VPT_CLIP
      vec2 tn = keptInterval(pos, ps.xyz);
#else
      vec2 tn = intersectBox(pos, ps.xyz, u.boxMin, u.boxMax);
#endif
      float Tn = tn.x < tn.y ? transmittance(pos, ps.xyz, tn.x, tn.y, rng) : 1.0;
      L += beta * escapedRadiance(ps.xyz, depth, phasePdf) * Tn;
#endif
      break;
    }
#if !SINGLE_SCATTERING
    if (depth >= u.rouletteDepth) {
      float q = min(maxComponent(beta), 1.0);
      if (rngNext(rng) >= q) break;
      beta /= q;
    }
    dir = ps.xyz;
#if VPT_CLIP
    tb = keptInterval(pos, dir);
#else
    tb = intersectBox(pos, dir, u.boxMin, u.boxMax);
#endif
#endif
  }
#if DEBUG_OUTPUT == 2
  vpt_out0 = vec4(float(mediumLookups), float(cellVisits), float(depth), 1.0);
#else
  vpt_out0 = vec4(finiteOrZero(L), alpha);
#endif
#endif
#if VPT_GUIDES
  vpt_out1 = guide0;
  vpt_out2 = guide1;
#endif
}
`;
