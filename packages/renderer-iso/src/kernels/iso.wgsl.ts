import { WGSL_CELL_WALK, WGSL_DEPTH_LIMIT, MAX_MARCH_STEPS } from '@vpt/core';
import { WGSL_ENVIRONMENT_MAP, WGSL_SAMPLING } from '@vpt/core/sampling';
import { WGSL_SAMPLE_DIMS } from '@vpt/core/blue-noise';

// Monte Carlo isosurface rendering (Lesar et al. 2018, the ISO renderer) with stochastic
// transparency (Enderton et al. 2010): twin of iso.glsl.ts, same arithmetic in the same
// order. Compile-time switches are `#if` lines, resolved for both languages by core's preprocessor.

const ISO_COMMON = /* wgsl */ `
${WGSL_SAMPLE_DIMS}
const ISO_REFINE_STEPS: i32 = 10;

#if SKIP_EMPTY
${WGSL_CELL_WALK}
fn isoCellCrossable(texel: vec2i) -> bool {
  let r = textureLoad(majorantRanges, texel, 0).rg;
  let lo = min(volumeValue(r.x), volumeValue(r.y)) - 1e-5;
  let hi = max(volumeValue(r.x), volumeValue(r.y)) + 1e-5;
  for (var k = 0; k < ISO_COUNT; k++) {
    if (u.isoSurface[k].a > 0.0 && lo < u.isoValues[k] && u.isoValues[k] <= hi) { return true; }
  }
  return false;
}
struct IsoCells { walk: CellWalk, tEnd: f32, crossable: bool };
fn isoCellsStart(o: vec3f, d: vec3f, t0: f32) -> IsoCells { return IsoCells(cellWalkStart(o, d, t0), -1.0, true); }
fn isoNextSample(c: ptr<function, IsoCells>, t: f32, t0: f32, t1: f32, seg: f32, offset: f32, i: i32, n: i32) -> i32 {
  let maxCells = u.gridCells.x + u.gridCells.y + u.gridCells.z + 3;
  for (var g = 0; g < maxCells && t >= (*c).tEnd; g++) {
    (*c).crossable = isoCellCrossable(cellWalkTexel((*c).walk));
    let e = cellWalkStep(&(*c).walk);
    (*c).tEnd = select(e, 3.0e38, e >= t1);
  }
  if ((*c).crossable || t >= (*c).tEnd) { return i + 1; }
  return max(i + 1, latticeIndexAt((*c).tEnd, t0, seg, offset, i + 1, n + 1));
}
#endif

fn isoValuesAt(p: vec3f) -> vec4f {
#if VPT_CHANNELS
  return sampleChannels(p);
#else
  return vec4f(sampleVolume(p));
#endif
}
#if VPT_LABELS
const ISO_LABEL_SURFACE = 4;
#endif
fn isoFieldAt(p: vec3f, k: i32) -> f32 {
#if VPT_LABELS
  if (k == ISO_LABEL_SURFACE) { return labelMask(p); }
#endif
  return isoValuesAt(p)[k];
}
fn isoRefine(o: vec3f, d: vec3f, ta0: f32, fa0: f32, tb0: f32, iso: f32, k: i32) -> f32 {
  var ta = ta0;
  var fa = fa0;
  var tb = tb0;
  for (var i = 0; i < ISO_REFINE_STEPS; i++) {
    let tm = 0.5 * (ta + tb);
    let fm = isoFieldAt(o + d * tm, k) - iso;
    if ((fm >= 0.0) == (fa >= 0.0)) { ta = tm; fa = fm; } else { tb = tm; }
  }
  return 0.5 * (ta + tb);
}

fn isoTrace(o: vec3f, d: vec3f, t0: f32, t1: f32, rng: ptr<function, u32>) -> vec4f {
  let offset = rngDim(rng, 2);
  let n = max(1, i32(min(ceil((t1 - t0) / u.stepSize), ${MAX_MARCH_STEPS}.0)));
  let seg = (t1 - t0) / f32(n);
  var tPrev = t0;
  var vPrev = isoValuesAt(o + d * t0);
#if VPT_LABELS
  var mPrev = labelMask(o + d * t0);
#endif
  var r = vec4f(-1.0);
#if SKIP_EMPTY
  var cells = isoCellsStart(o, d, t0);
#endif
  for (var i = 0; i <= n; i++) {
    let t = min(t0 + (f32(i) + offset) * seg, t1);
    let v = isoValuesAt(o + d * t);
    for (var k = 0; k < ISO_COUNT; k++) {
      let iso = u.isoValues[k];
      let alpha = u.isoSurface[k].a;
      if ((vPrev[k] >= iso) != (v[k] >= iso) && alpha > 0.0) {
        let tc = isoRefine(o, d, tPrev, vPrev[k] - iso, t, iso, k);
        if (r.z < 0.0 || tc < r.z) { r.z = tc; r.w = f32(k); }
        var opaque = true;
        if (alpha < 1.0) { opaque = rngNext(rng) < alpha; }
        if (opaque && (r.x < 0.0 || tc < r.x)) { r.x = tc; r.y = f32(k); }
      }
    }
#if VPT_LABELS
    let m = labelMask(o + d * t);
    if ((mPrev >= 0.5) != (m >= 0.5)) {
      let tc = isoRefine(o, d, tPrev, mPrev - 0.5, t, 0.5, ISO_LABEL_SURFACE);
      if (r.z < 0.0 || tc < r.z) { r.z = tc; r.w = f32(ISO_LABEL_SURFACE); }
      if (r.x < 0.0 || tc < r.x) { r.x = tc; r.y = f32(ISO_LABEL_SURFACE); }
    }
    mPrev = m;
#endif
    if (r.x >= 0.0) { return r; }
    tPrev = t;
    vPrev = v;
#if SKIP_EMPTY
    let next = isoNextSample(&cells, t, t0, t1, seg, offset, i, n);
    if (next > i + 1 && next <= n) {
      tPrev = min(t0 + (f32(next - 1) + offset) * seg, t1);
      vPrev = isoValuesAt(o + d * tPrev);
    }
    i = next - 1;
#endif
  }
  return r;
}

fn isoVisibility(o: vec3f, d: vec3f, maxDist: f32, rng: ptr<function, u32>) -> f32 {
#if VPT_CLIP
  let tb = keptInterval(o, d);
#else
  let tb = intersectBox(o, d, u.boxMin, u.boxMax);
#endif
  let t1 = min(tb.y, maxDist);
  if (!(tb.x < t1)) { return 1.0; }
  let t0 = tb.x;
  let offset = rngNext(rng);
  let n = max(1, i32(min(ceil((t1 - t0) / u.stepSize), ${MAX_MARCH_STEPS}.0)));
  let seg = (t1 - t0) / f32(n);
  var vPrev = isoValuesAt(o + d * t0);
#if VPT_LABELS
  var mPrev = labelMask(o + d * t0);
#endif
#if SKIP_EMPTY
  var cells = isoCellsStart(o, d, t0);
#endif
  for (var i = 0; i <= n; i++) {
    let t = min(t0 + (f32(i) + offset) * seg, t1);
    let v = isoValuesAt(o + d * t);
    for (var k = 0; k < ISO_COUNT; k++) {
      let iso = u.isoValues[k];
      let alpha = u.isoSurface[k].a;
      if ((vPrev[k] >= iso) != (v[k] >= iso) && alpha > 0.0) {
        if (alpha >= 1.0) { return 0.0; }
        if (rngNext(rng) < alpha) { return 0.0; }
      }
    }
#if VPT_LABELS
    let m = labelMask(o + d * t);
    if ((mPrev >= 0.5) != (m >= 0.5)) { return 0.0; }
    mPrev = m;
#endif
    vPrev = v;
#if SKIP_EMPTY
    let next = isoNextSample(&cells, t, t0, t1, seg, offset, i, n);
    if (next > i + 1 && next <= n) { vPrev = isoValuesAt(o + d * min(t0 + (f32(next - 1) + offset) * seg, t1)); }
    i = next - 1;
#endif
  }
  return 1.0;
}

fn isoNormal(p: vec3f, d: vec3f, k: i32) -> vec3f {
  let h = u.gradientStep;
  let gx = (isoFieldAt(p + vec3f(h.x, 0.0, 0.0), k) - isoFieldAt(p - vec3f(h.x, 0.0, 0.0), k)) / (2.0 * h.x);
  let gy = (isoFieldAt(p + vec3f(0.0, h.y, 0.0), k) - isoFieldAt(p - vec3f(0.0, h.y, 0.0), k)) / (2.0 * h.y);
  let gz = (isoFieldAt(p + vec3f(0.0, 0.0, h.z), k) - isoFieldAt(p - vec3f(0.0, 0.0, h.z), k)) / (2.0 * h.z);
  let g = vec3f(gx, gy, gz);
  if (!(dot(g, g) > 1e-30)) { return -d; }
  let n = normalize(g);
  return select(n, -n, dot(n, d) > 0.0);
}

fn isoAlbedo(k: i32, p: vec3f, n: vec3f) -> vec3f {
#if VPT_LABELS
  if (k == ISO_LABEL_SURFACE) {
    let inner = labelAt(p - n * u.gradientStep);
    return select(labelAt(p).rgb, inner.rgb, inner.a > 0.0);
  }
#endif
  return u.isoSurface[k].rgb;
}

fn isoBrdf(n: vec3f, wi: vec3f, wo: vec3f, albedo: vec3f) -> vec3f {
  let hs = wi + wo;
  var lobe = 0.0;
  let h2 = dot(hs, hs);
  if (h2 > 1e-12) {
    let nh = max(dot(n, hs / sqrt(h2)), 0.0);
    lobe = (u.shininess + 8.0) * (1.0 / (8.0 * VPT_PI)) * exp2(u.shininess * log2(max(nh, 1e-8)));
  }
  return albedo * ((1.0 - u.specular) / VPT_PI) + vec3f(u.specular * lobe);
}

fn isoEnvironment(d: vec3f) -> vec3f {
#if ISO_ENV == 2
  return environmentLookup(d).rgb;
#else
  return u.background.rgb;
#endif
}

fn isoShade(p: vec3f, n: vec3f, wo: vec3f, albedo: vec3f, rng: ptr<function, u32>) -> vec3f {
  var radiance = vec3f(0.0);
  let origin = p + n * u.rayEpsilon;
  for (var l = 0; l < ISO_LIGHTS; l++) {
    let ld = u.isoLightDirection[l];
    var wi = ld.xyz;
#if ISO_SOFT_LIGHTS
    let c1 = rngNext(rng);
    let c2 = rngNext(rng);
    let cosT = 1.0 - c1 * (1.0 - ld.w);
    let sinT = sqrt(max((1.0 - cosT) * (1.0 + cosT), 0.0));
    wi = directionAround(ld.xyz, cosT, sinT, 2.0 * VPT_PI * c2);
#endif
    let cosI = dot(n, wi);
    if (cosI > 0.0) {
      var vis = 1.0;
#if ISO_SHADOWS
      vis = isoVisibility(origin, wi, 1e30, rng);
#endif
      radiance += u.isoLightIrradiance[l].rgb * (cosI * vis) * isoBrdf(n, wi, wo, albedo);
    }
  }
#if ISO_ENV > 0
  let e1 = rngDim(rng, 3);
  let e2 = rngDim(rng, 4);
  let cosC = sqrt(1.0 - e1);
  let wc = directionAround(n, cosC, sqrt(e1), 2.0 * VPT_PI * e2);
  var visC = 1.0;
#if ISO_AO
  visC = isoVisibility(origin, wc, u.aoRadius, rng);
#endif
  // f L cos / pdf with pdf = cos / pi: the cosine cancels.
#if ISO_ENV == 2
  let envC = environmentLookup(wc);
  let pdfC = cosC * (1.0 / VPT_PI);
  let wC = select(0.0, pdfC / (pdfC + envC.a), pdfC > 0.0);
  radiance += envC.rgb * (visC * VPT_PI * wC) * isoBrdf(n, wc, wo, albedo);
  let s1 = rngNext(rng);
  let s2 = rngNext(rng);
  let es = sampleEnvironment(s1, s2);
  let cosE = dot(n, es.direction);
  if (cosE > 0.0 && es.pdf > 0.0) {
    var visE = 1.0;
#if ISO_AO
    visE = isoVisibility(origin, es.direction, u.aoRadius, rng);
#endif
    let pdfCE = cosE * (1.0 / VPT_PI);
    let wE = es.pdf / (es.pdf + pdfCE);
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
  WGSL_SAMPLING +
  '\n#if ISO_ENV == 2\n' +
  WGSL_ENVIRONMENT_MAP +
  '\n#endif\n#if VPT_DEPTH_LIMIT\n' +
  WGSL_DEPTH_LIMIT +
  '\n#endif\n' +
  ISO_COMMON +
  /* wgsl */ `
@fragment fn fs_main(@builtin(position) fragCoord: vec4f) -> VptOut {
  let pixel = vptPixel(fragCoord);
  let size = vptTargetSize();
  var rng = rngInit(pixel, u.iteration + u.sampleBase, u.seed);
  sampleDimsInit(pixel);
#if ISO_JITTER
  let dir = jitteredCameraRayDims(pixel, size, &rng);
#else
  let dir = cameraRayDirection(vec2f((f32(pixel.x) + 0.5) / f32(size.x), (f32(pixel.y) + 0.5) / f32(size.y)));
#endif
  let o = u.cameraPosition;
#if VPT_CLIP
  var tb = keptInterval(o, dir);
#else
  var tb = intersectBox(o, dir, u.boxMin, u.boxMax);
#endif
#if VPT_DEPTH_LIMIT
  tb.y = min(tb.y, depthLimitAlong(pixel, dir));
#endif
#if VPT_SLICE_PLANE
  // The slice plane is opaque: the ray ends there (scene/slice-plane.ts).
  let tPlane = slicePlaneHit(o, dir);
  let onPlane = tPlane > 0.0 && tPlane <= tb.y;
  if (onPlane) { tb.y = tPlane; }
#endif
  var hit = vec4f(-1.0);
  if (tb.x < tb.y) { hit = isoTrace(o, dir, tb.x, tb.y, &rng); }
#if VPT_DEPTH_LIMIT
  var color = vec4f(0.0);
#else
  var color = vec4f(isoEnvironment(dir), 0.0);
#endif
#if VPT_SLICE_PLANE
  if (onPlane) { color = vec4f(slicePlaneColor(o + dir * tPlane), 1.0); }
#endif
  var nearest = vec4f(-1.0, 0.0, 0.0, 0.0);
  if (hit.z >= 0.0) {
    let nz = isoNormal(o + dir * hit.z, dir, i32(hit.w));
    nearest = vec4f(hit.z, nz);
    if (hit.x >= 0.0) {
      let k = i32(hit.y);
      var n = nz;
      if (hit.x != hit.z || hit.y != hit.w) { n = isoNormal(o + dir * hit.x, dir, k); }
      color = vec4f(isoShade(o + dir * hit.x, n, -dir, isoAlbedo(k, o + dir * hit.x, n), &rng), 1.0);
    }
  }
  var res: VptOut;
#if VPT_GUIDES
  // Denoiser guides at the shaded surface: its normal, depth and diffuse colour.
  if (hit.x >= 0.0) {
    var ng = nearest.yzw;
    if (hit.x != hit.z || hit.y != hit.w) { ng = isoNormal(o + dir * hit.x, dir, i32(hit.y)); }
    res.out2 = vec4f(ng, hit.x);
    res.out3 = guideAlbedo(isoAlbedo(i32(hit.y), o + dir * hit.x, ng));
  }
#endif
  res.out0 = color;
  res.out1 = nearest;
  return res;
}
`;

export const integrate = /* wgsl */ `
@fragment fn fs_main(@builtin(position) fragCoord: vec4f) -> VptOut {
  let p = vptPixel(fragCoord);
  let f0 = textureLoad(frame0, p, 0);
  let f1 = textureLoad(frame1, p, 0);
  var o: VptOut;
  if (u.iteration == 0u) { o.out0 = f0; o.out1 = f1; return o; }
  let a0 = textureLoad(accum0, p, 0);
  let a1 = textureLoad(accum1, p, 0);
  let w = 1.0 / f32(u.iteration + 1u);
  o.out0 = a0 + (f0 - a0) * w;
  let nearer = f1.x >= 0.0 && (a1.x < 0.0 || f1.x < a1.x);
  o.out1 = select(a1, f1, nearer);
  return o;
}
`;

export const render = /* wgsl */ `
@fragment fn fs_main(@builtin(position) fragCoord: vec4f) -> VptOut {
  let p = vptPixel(fragCoord);
  var o: VptOut;
#if ISO_OUTPUT == 0
  o.out0 = textureLoad(accum0, p, 0);
#else
  let a = textureLoad(accum1, p, 0);
#if ISO_OUTPUT == 1
  o.out0 = select(vec4f(0.0), vec4f(a.x, a.x, a.x, 1.0), a.x >= 0.0);
#else
  o.out0 = select(vec4f(0.0), vec4f(a.yzw, 1.0), a.x >= 0.0);
#endif
#endif
  return o;
}
`;
