import { WGSL_DEPTH_LIMIT } from '@vpt/core';

// Volumetric path tracing (Kajiya 1986; PBR 4th ed., ch. 14) with NEE + MIS (Veach & Guibas
// 1995) and throughput Russian roulette. Twin of path.glsl.ts: same arithmetic in the same order.

export const path = /* wgsl */ `
#if VPT_DEPTH_LIMIT
${WGSL_DEPTH_LIMIT}
#endif
fn maxComponent(v: vec3f) -> f32 { return max(max(v.x, v.y), v.z); }
fn finiteOr0(x: f32) -> f32 { return select(x, 0.0, (bitcast<u32>(x) & 0x7f800000u) == 0x7f800000u); }
fn finiteOrZero(v: vec3f) -> vec3f { return vec3f(finiteOr0(v.x), finiteOr0(v.y), finiteOr0(v.z)); }

#if ENV_SAMPLING == 2 && MIS_POWER
fn misWeight(a: f32, b: f32) -> f32 { return misPower(a, b); }
#elif ENV_SAMPLING == 2
fn misWeight(a: f32, b: f32) -> f32 { return misBalance(a, b); }
#endif

fn environmentAlong(d: vec3f) -> vec4f {
#if ENV_MAP
  return environmentLookup(d);
#else
  return vec4f(u.background.rgb, VPT_INV_4PI);
#endif
}

fn escapedRadiance(d: vec3f, depth: i32, phasePdf: f32) -> vec3f {
  if (depth == 0) { return environmentAlong(d).rgb; }
#if ENV_LIGHT && ENV_SAMPLING == 0
  return environmentAlong(d).rgb;
#elif ENV_LIGHT && ENV_SAMPLING == 2
  let e = environmentAlong(d);
  return e.rgb * misWeight(phasePdf, e.a);
#else
  return vec3f(0.0);
#endif
}

// The sample dimensions (core's SAMPLE_DIMS) of the next environment light sample; -1: the PCG stream.
var<private> lightDim: i32 = -1;
fn directLight(x: vec3f, w: vec3f, rng: ptr<function, u32>) -> vec3f {
  var Ld = vec3f(0.0);
#if LIGHT_COUNT > 0
  for (var i = 0; i < LIGHT_COUNT; i++) {
#if GENERIC
    if (i >= u.lightCount) { break; }
#endif
    let l = u.lightDirection[i].xyz;
    let ph = hgPhase(u.phaseG, dot(w, l));
#if VPT_CLIP
    let tb = keptInterval(x, l);
#else
    let tb = intersectBox(x, l, u.boxMin, u.boxMax);
#endif
    var T = 1.0;
    if (tb.x < tb.y) { T = transmittance(x, l, tb.x, tb.y, rng); }
    Ld += u.lightIrradiance[i].rgb * (ph * T);
  }
#endif
#if ENV_LIGHT && ENV_SAMPLING != 0
  let xi1 = rngDim(rng, lightDim);
  let xi2 = rngDim(rng, select(lightDim + 1, -1, lightDim < 0));
  lightDim = -1;
#if ENV_MAP
  let e = sampleEnvironment(xi1, xi2);
  let wl = e.direction;
  let pl = e.pdf;
  let Le = e.radiance;
#else
  let wl = sampleUniformSphere(xi1, xi2);
  let pl = VPT_INV_4PI;
  let Le = u.background.rgb;
#endif
  if (pl > 0.0) {
    let ph = hgPhase(u.phaseG, dot(w, wl));
#if VPT_CLIP
    let tb = keptInterval(x, wl);
#else
    let tb = intersectBox(x, wl, u.boxMin, u.boxMax);
#endif
    var T = 1.0;
    if (tb.x < tb.y) { T = transmittance(x, wl, tb.x, tb.y, rng); }
#if ENV_SAMPLING == 2
    let wMis = misWeight(pl, ph);
#else
    let wMis = 1.0;
#endif
    Ld += Le * (ph * T * wMis / pl);
  }
#endif
  return Ld;
}

@fragment fn fs_main(@builtin(position) fragCoord: vec4f) -> VptOut {
  let pixel = vptPixel(fragCoord);
  var rng = rngInit(pixel, u.iteration + u.sampleBase, u.seed);
  sampleDimsInit(pixel);
  // Blue noise (BLUE_NOISE) serves the jitter, the camera ray's first free flight and the first light sample.
  flightDim = 2;
  lightDim = 3;
  var dir = jitteredCameraRayDims(pixel, vptTargetSize(), &rng);
  var pos = u.cameraPosition;
#if VPT_CLIP
  var tb = keptInterval(pos, dir);
#else
  var tb = intersectBox(pos, dir, u.boxMin, u.boxMax);
#endif
#if VPT_DEPTH_LIMIT
  tb.y = min(tb.y, depthLimitAlong(pixel, dir));
#endif
#if VPT_SLICE_PLANE
  let tPlane = slicePlaneHit(pos, dir);
  let onPlane = tPlane > 0.0 && tPlane <= tb.y;
  if (onPlane) { tb.y = tPlane; }
#endif
  var o: VptOut;
#if VPT_GUIDES
  // Denoiser guides at the first real collision (zeros where the camera ray has none).
  var guide0 = vec4f(0.0);
  var guide1 = vec4f(0.0);
#endif
#if DEBUG_OUTPUT == 1
  var Tcam = 1.0;
  if (tb.x < tb.y) { Tcam = transmittance(pos, dir, tb.x, tb.y, &rng); }
  o.out0 = vec4f(Tcam, Tcam, Tcam, 1.0);
#else
  var L = vec3f(0.0);
  var beta = vec3f(1.0);
  var alpha = 0.0;
  var depth = 0;
  var phasePdf = 0.0;
  while (trackingSteps < MAX_TRACKING_STEPS) {
    var c = Collision(false, 0.0, vec3f(0.0));
    if (tb.x < tb.y) { c = freeFlight(pos, dir, tb.x, tb.y, &rng); }
    if (!c.hit) {
#if VPT_SLICE_PLANE
      if (depth == 0 && onPlane) { L += slicePlaneColor(pos + dir * tPlane); alpha = 1.0; break; }
#endif
#if VPT_DEPTH_LIMIT
      if (depth == 0) { break; }
#endif
      L += beta * escapedRadiance(dir, depth, phasePdf);
      break;
    }
    if (depth == 0) { alpha = 1.0; }
    pos = pos + dir * c.t;
#if VPT_GUIDES
    if (depth == 0) { guide0 = guideNormalDepth(pos, c.t); guide1 = guideAlbedo(c.albedo); }
#endif
    beta *= c.albedo;
    depth++;
    if (maxComponent(beta) <= 0.0) { break; }
#if LIGHT_SAMPLES > 1
    // Single scattering: the mean of LIGHT_SAMPLES in-scattering estimates at the one event (the
    // first LIGHT_SAMPLES − 1 here, the last below), as pbrt's light sample counts (PBR 3rd ed.,
    // §14.3.1); the camera ray's walk is shared by them.
#if SINGLE_SCATTERING
    let severalSamples = true;
#else
    let severalSamples = u.maxDepth == 1; // the generic kernel: single scattering is maxDepth 1
#endif
    if (severalSamples) { beta *= 1.0 / f32(LIGHT_SAMPLES); }
    for (var k = 1; k < LIGHT_SAMPLES && severalSamples; k++) {
      L += beta * directLight(pos, dir, &rng);
#if ENV_LIGHT && ENV_SAMPLING != 1
      let xk1 = rngNext(&rng);
      let xk2 = rngNext(&rng);
      let pk = sampleHG(dir, u.phaseG, xk1, xk2);
#if VPT_CLIP
      let tk = keptInterval(pos, pk.xyz);
#else
      let tk = intersectBox(pos, pk.xyz, u.boxMin, u.boxMax);
#endif
      var Tk = 1.0;
      if (tk.x < tk.y) { Tk = transmittance(pos, pk.xyz, tk.x, tk.y, &rng); }
      L += beta * escapedRadiance(pk.xyz, depth, pk.w) * Tk;
#endif
    }
#endif
    L += beta * directLight(pos, dir, &rng);
    let xi1 = rngNext(&rng);
    let xi2 = rngNext(&rng);
    let ps = sampleHG(dir, u.phaseG, xi1, xi2);
    phasePdf = ps.w;
#if SINGLE_SCATTERING
    let last = true;
#else
    let last = u.maxDepth > 0 && depth >= u.maxDepth;
#endif
    if (last) {
#if ENV_LIGHT && ENV_SAMPLING != 1
#if VPT_CLIP
      let tn = keptInterval(pos, ps.xyz);
#else
      let tn = intersectBox(pos, ps.xyz, u.boxMin, u.boxMax);
#endif
      var Tn = 1.0;
      if (tn.x < tn.y) { Tn = transmittance(pos, ps.xyz, tn.x, tn.y, &rng); }
      L += beta * escapedRadiance(ps.xyz, depth, phasePdf) * Tn;
#endif
      break;
    }
#if !SINGLE_SCATTERING
    if (depth >= u.rouletteDepth) {
      let q = min(maxComponent(beta), 1.0);
      if (rngNext(&rng) >= q) { break; }
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
  o.out0 = vec4f(f32(mediumLookups), f32(cellVisits), f32(depth), 1.0);
#else
  o.out0 = vec4f(finiteOrZero(L), alpha);
#endif
#endif
#if VPT_GUIDES
  o.out1 = guide0;
  o.out2 = guide1;
#endif
  return o;
}
`;
