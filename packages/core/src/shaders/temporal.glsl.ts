// Temporal reuse (GLSL; the twin is temporal.wgsl.ts, composed in temporal.ts): the previous view's
// image reprojected through the depth guide and blended with the new samples, as SVGF's temporal
// accumulation (Schied et al. 2017, HPG, Sec. 4.1: backprojection, depth/normal consistency tests,
// bilinear taps over the consistent samples, history clamped in length); the colour resampled by
// Catmull-Rom (Keys 1981, a = −0.5, as TAA does: Jimenez 2016, "Filmic SMAA") clamped to the bilinear
// taps' range.

/**
 * One full-screen pass per displayed image. Inputs: `current` (the renderer's HDR mean of
 * u.samples new samples), `guideNormalDepth` / `guideAlbedo` (their guide means), the previous
 * resolve's outputs `historyImage`, `historyGuide` (normal, hit depth along the old camera's ray),
 * `historyState` (hit share, samples, 0, 0), at the old view's size. Outputs the same three for
 * this view. A new pixel's world point is its camera ray at its mean hit depth (at infinity
 * for a miss), projected into the old camera; each of the four bilinear taps counts only where
 * it is finite, hit/miss agrees, the depth agrees within u.depthTolerance (relative) and the
 * normals within u.normalCos. The history then weighs w = min(its samples, u.maxHistory) ·
 * u.historyScale (the view change's decay and the fade with new samples, set by the context),
 * and out = (n · current + w · history) / (n + w); w = 0 returns `current` unchanged.
 * u.historyFilter 1: where all four bilinear taps with weight pass, the history's colour is the
 * 4×4 Catmull-Rom sum instead (each outer tap under the same tests, else its nearest inner tap's
 * colour), clamped per channel to the inner taps' min/max, so it never rings past them and only
 * tested, finite texels enter it; the guide, hit share and samples stay bilinear.
 * u.footprintWeight 1 (the context sets it where the normal test is off): w is also scaled by the
 * share of the footprint that passed (wsum).
 */
export const TEMPORAL_RESOLVE = /* glsl */ `
// The ray of film point (x, y) in [0,1]^2 (y down) of a camera given by its basis (common's cameraRayDirection).
vec3 temporalRay(vec2 film, vec3 forward, vec3 right, vec3 up, float tanHalf, float aspect) {
  float sx = (2.0 * film.x - 1.0) * tanHalf * aspect;
  float sy = (1.0 - 2.0 * film.y) * tanHalf;
  return normalize(forward + right * sx + up * sy);
}
// Non-finite (Inf or NaN) by the exponent bits, which no compiler folds away.
bool temporalBad(vec4 v) {
  uvec4 e = floatBitsToUint(v) & uvec4(0x7f800000u);
  return any(equal(e, uvec4(0x7f800000u)));
}
float temporalHitDepth(vec4 normalDepth, vec4 albedoHit) {
  return albedoHit.a > 0.0 ? normalDepth.w / albedoHit.a : 0.0;
}
// The Catmull-Rom weights of the taps at −1, 0, 1, 2 for the fraction f (they sum to 1).
vec4 temporalCatmullRom(float f) {
  return vec4(
    f * (-0.5 + f * (1.0 - 0.5 * f)),
    1.0 + f * f * (-2.5 + 1.5 * f),
    f * (0.5 + f * (2.0 - 1.5 * f)),
    f * f * (-0.5 + 0.5 * f));
}
// Whether history texel t may stand for the new pixel (finite, and the hit/miss, depth and normal
// tests); its colour, guide and state in hc, hg, hs.
bool temporalTap(ivec2 t, ivec2 osize, float hit, float expected, vec3 normal, out vec4 hc, out vec4 hg, out vec4 hs) {
  hc = vec4(0.0);
  hg = vec4(0.0);
  hs = vec4(0.0);
  if (t.x < 0 || t.y < 0 || t.x >= osize.x || t.y >= osize.y) return false;
  hc = texelFetch(historyImage, t, 0);
  hg = texelFetch(historyGuide, t, 0);
  hs = texelFetch(historyState, t, 0);
  if (temporalBad(hc) || temporalBad(hg) || temporalBad(hs)) return false;
  bool ok;
  if (hit > 0.0) {
    ok = hs.x > 0.0 && abs(hg.w - expected) <= u.depthTolerance * expected;
    float nn = length(normal) * length(hg.xyz);
    if (ok && nn > 1e-12) ok = dot(normal, hg.xyz) >= u.normalCos * nn;
  } else {
    ok = hs.x <= 0.5;
  }
  return ok;
}

void main() {
  ivec2 p = vptPixel();
  ivec2 size = vptTargetSize();
  vec4 cur = texelFetch(current, p, 0);
  vec4 nd = texelFetch(guideNormalDepth, p, 0);
  vec4 ah = texelFetch(guideAlbedo, p, 0);
  float hit = ah.a;
  float depth = temporalHitDepth(nd, ah);
  vec3 normal = hit > 0.0 ? nd.xyz / hit : vec3(0.0);
  float n = float(u.samples);
  vec4 histColor = vec4(0.0);
  vec4 histGuide = vec4(0.0);
  float histSamples = 0.0;
  float histHit = 0.0;
  float wsum = 0.0;
  // For the Catmull-Rom: whether every weighted bilinear tap passed, their colours and range.
  bool allTaps = false;
  vec4 inner[4] = vec4[4](vec4(0.0), vec4(0.0), vec4(0.0), vec4(0.0));
  vec4 lo = vec4(0.0), hi = vec4(0.0);
  vec2 q0 = vec2(0.0), fr = vec2(0.0);
  ivec2 osize = ivec2(0);
  float expected = 0.0;
  if (u.historyScale > 0.0) {
    vec2 film = (vec2(p) + 0.5) / vec2(size);
    vec3 dir = temporalRay(film, u.newForward, u.newRight, u.newUp, u.newTanHalfFovy, u.newAspect);
    // A hit's world point, or a miss's direction (a point at infinity).
    vec3 d = hit > 0.0 ? u.newPosition + dir * depth - u.oldPosition : dir;
    float z = dot(d, u.oldForward);
    if (z > 1e-6) {
      expected = length(d);
      vec2 ofilm = vec2(
        0.5 + 0.5 * dot(d, u.oldRight) / (z * u.oldTanHalfFovy * u.oldAspect),
        0.5 - 0.5 * dot(d, u.oldUp) / (z * u.oldTanHalfFovy));
      osize = textureSize(historyImage, 0);
      vec2 q = ofilm * vec2(osize) - 0.5;
      q0 = floor(q);
      fr = q - q0;
      allTaps = true;
      lo = vec4(3.0e38);
      hi = vec4(-3.0e38);
      for (int k = 0; k < 4; k++) {
        ivec2 o = ivec2(k & 1, k >> 1);
        ivec2 t = ivec2(q0) + o;
        float bw = (o.x == 1 ? fr.x : 1.0 - fr.x) * (o.y == 1 ? fr.y : 1.0 - fr.y);
        if (bw <= 0.0) continue;
        vec4 hc, hg, hs;
        if (!temporalTap(t, osize, hit, expected, normal, hc, hg, hs)) {
          allTaps = false;
          continue;
        }
        inner[k] = hc;
        lo = min(lo, hc);
        hi = max(hi, hc);
        histColor += bw * hc;
        histGuide += bw * vec4(hg.xyz, depth + (hg.w - expected));
        histSamples += bw * hs.y;
        histHit += bw * hs.x;
        wsum += bw;
      }
    }
  }
  float w = 0.0;
  if (wsum > 0.01) {
    histColor /= wsum;
    histGuide /= wsum;
    histSamples /= wsum;
    histHit /= wsum;
    w = min(histSamples, u.maxHistory) * u.historyScale;
    // u.footprintWeight 1: a footprint the tests cut (wsum < 1) is an edge whose passed taps are a
    // neighbour's: the history counts by the share that passed.
    if (u.footprintWeight > 0.0) w *= min(wsum, 1.0);
    if (u.historyFilter == 1u && allTaps) {
      // A zero-weight inner tap was not tested: the bilinear colour stands in (its weight is 0 too).
      for (int k = 0; k < 4; k++) {
        ivec2 o = ivec2(k & 1, k >> 1);
        float bw = (o.x == 1 ? fr.x : 1.0 - fr.x) * (o.y == 1 ? fr.y : 1.0 - fr.y);
        if (bw <= 0.0) inner[k] = histColor;
      }
      vec4 wx = temporalCatmullRom(fr.x), wy = temporalCatmullRom(fr.y);
      vec4 c = vec4(0.0);
      for (int j = 0; j < 4; j++) {
        vec4 row = vec4(0.0);
        for (int i = 0; i < 4; i++) {
          if (wx[i] * wy[j] == 0.0) continue;
          ivec2 ci = clamp(ivec2(i, j) - 1, ivec2(0), ivec2(1));
          vec4 hc = inner[ci.x + 2 * ci.y];
          if (i == 0 || i == 3 || j == 0 || j == 3) {
            vec4 oc, og, os;
            if (temporalTap(ivec2(q0) + ivec2(i, j) - 1, osize, hit, expected, normal, oc, og, os)) hc = oc;
          }
          row += wx[i] * hc;
        }
        c += wy[j] * row;
      }
      if (!temporalBad(c)) histColor = clamp(c, lo, hi);
    }
  }
  if (w <= 0.0) {
    vpt_out0 = cur;
    vpt_out1 = vec4(normal, depth);
    vpt_out2 = vec4(hit, n, 0.0, 0.0);
    return;
  }
  float a = w / (n + w);
  vpt_out0 = cur + (histColor - cur) * a;
  vec4 g = vec4(normal, depth);
  // A miss keeps the history's normal and depth only where the history hit.
  vpt_out1 = hit > 0.0 ? g + (histGuide - g) * a : vec4(0.0);
  vpt_out2 = vec4(hit + (histHit - hit) * a, n + w, 0.0, 0.0);
}
`;
