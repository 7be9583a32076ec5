// Temporal reuse (WGSL; the twin is temporal.glsl.ts, composed in temporal.ts): the previous view's
// image reprojected through the depth guide and blended with the new samples, as SVGF's temporal
// accumulation (Schied et al. 2017, HPG, Sec. 4.1: backprojection, depth/normal consistency tests,
// bilinear taps over the consistent samples, history clamped in length); the colour resampled by
// Catmull-Rom (Keys 1981, a = −0.5, as TAA does: Jimenez 2016, "Filmic SMAA") clamped to the bilinear
// taps' range.

/** One full-screen pass per displayed image; see the GLSL twin's comment. */
export const TEMPORAL_RESOLVE = /* wgsl */ `
// The ray of film point (x, y) in [0,1]^2 (y down) of a camera given by its basis (common's cameraRayDirection).
fn temporalRay(film: vec2f, forward: vec3f, right: vec3f, up: vec3f, tanHalf: f32, aspect: f32) -> vec3f {
  let sx = (2.0 * film.x - 1.0) * tanHalf * aspect;
  let sy = (1.0 - 2.0 * film.y) * tanHalf;
  return normalize(forward + right * sx + up * sy);
}
// Non-finite (Inf or NaN) by the exponent bits, which no compiler folds away.
fn temporalBad(v: vec4f) -> bool {
  let e = bitcast<vec4u>(v) & vec4u(0x7f800000u);
  return any(e == vec4u(0x7f800000u));
}
fn temporalHitDepth(normalDepth: vec4f, albedoHit: vec4f) -> f32 {
  if (albedoHit.a > 0.0) { return normalDepth.w / albedoHit.a; }
  return 0.0;
}
// The Catmull-Rom weights of the taps at −1, 0, 1, 2 for the fraction f (they sum to 1).
fn temporalCatmullRom(f: f32) -> vec4f {
  return vec4f(
    f * (-0.5 + f * (1.0 - 0.5 * f)),
    1.0 + f * f * (-2.5 + 1.5 * f),
    f * (0.5 + f * (2.0 - 1.5 * f)),
    f * f * (-0.5 + 0.5 * f));
}
struct TemporalTap { ok: bool, hc: vec4f, hg: vec4f, hs: vec4f }
// Whether history texel t may stand for the new pixel (finite, and the hit/miss, depth and normal
// tests), with its colour, guide and state.
fn temporalTap(t: vec2i, osize: vec2i, hit: f32, expected: f32, normal: vec3f) -> TemporalTap {
  var r = TemporalTap(false, vec4f(0.0), vec4f(0.0), vec4f(0.0));
  if (t.x < 0 || t.y < 0 || t.x >= osize.x || t.y >= osize.y) { return r; }
  r.hc = textureLoad(historyImage, t, 0);
  r.hg = textureLoad(historyGuide, t, 0);
  r.hs = textureLoad(historyState, t, 0);
  if (temporalBad(r.hc) || temporalBad(r.hg) || temporalBad(r.hs)) { return r; }
  var ok: bool;
  if (hit > 0.0) {
    ok = r.hs.x > 0.0 && abs(r.hg.w - expected) <= u.depthTolerance * expected;
    let nn = length(normal) * length(r.hg.xyz);
    if (ok && nn > 1e-12) { ok = dot(normal, r.hg.xyz) >= u.normalCos * nn; }
  } else {
    ok = r.hs.x <= 0.5;
  }
  r.ok = ok;
  return r;
}

@fragment fn fs_main(@builtin(position) fragCoord: vec4f) -> VptOut {
  let p = vptPixel(fragCoord);
  let size = vptTargetSize();
  let cur = textureLoad(current, p, 0);
  let nd = textureLoad(guideNormalDepth, p, 0);
  let ah = textureLoad(guideAlbedo, p, 0);
  let hit = ah.a;
  let depth = temporalHitDepth(nd, ah);
  var normal = vec3f(0.0);
  if (hit > 0.0) { normal = nd.xyz / hit; }
  let n = f32(u.samples);
  var histColor = vec4f(0.0);
  var histGuide = vec4f(0.0);
  var histSamples = 0.0;
  var histHit = 0.0;
  var wsum = 0.0;
  // For the Catmull-Rom: whether every weighted bilinear tap passed, their colours and range.
  var allTaps = false;
  var inner = array<vec4f, 4>(vec4f(0.0), vec4f(0.0), vec4f(0.0), vec4f(0.0));
  var lo = vec4f(0.0);
  var hi = vec4f(0.0);
  var q0 = vec2f(0.0);
  var fr = vec2f(0.0);
  var osize = vec2i(0);
  var expected = 0.0;
  if (u.historyScale > 0.0) {
    let film = (vec2f(p) + 0.5) / vec2f(size);
    let dir = temporalRay(film, u.newForward, u.newRight, u.newUp, u.newTanHalfFovy, u.newAspect);
    // A hit's world point, or a miss's direction (a point at infinity).
    var d = dir;
    if (hit > 0.0) { d = u.newPosition + dir * depth - u.oldPosition; }
    let z = dot(d, u.oldForward);
    if (z > 1e-6) {
      expected = length(d);
      let ofilm = vec2f(
        0.5 + 0.5 * dot(d, u.oldRight) / (z * u.oldTanHalfFovy * u.oldAspect),
        0.5 - 0.5 * dot(d, u.oldUp) / (z * u.oldTanHalfFovy));
      osize = vec2i(textureDimensions(historyImage));
      let q = ofilm * vec2f(osize) - 0.5;
      q0 = floor(q);
      fr = q - q0;
      allTaps = true;
      lo = vec4f(3.0e38);
      hi = vec4f(-3.0e38);
      for (var k = 0; k < 4; k++) {
        let o = vec2i(k & 1, k >> 1u);
        let t = vec2i(q0) + o;
        let bw = select(1.0 - fr.x, fr.x, o.x == 1) * select(1.0 - fr.y, fr.y, o.y == 1);
        if (bw <= 0.0) { continue; }
        let tap = temporalTap(t, osize, hit, expected, normal);
        if (!tap.ok) {
          allTaps = false;
          continue;
        }
        inner[k] = tap.hc;
        lo = min(lo, tap.hc);
        hi = max(hi, tap.hc);
        histColor += bw * tap.hc;
        histGuide += bw * vec4f(tap.hg.xyz, depth + (tap.hg.w - expected));
        histSamples += bw * tap.hs.y;
        histHit += bw * tap.hs.x;
        wsum += bw;
      }
    }
  }
  var w = 0.0;
  if (wsum > 0.01) {
    histColor /= wsum;
    histGuide /= wsum;
    histSamples /= wsum;
    histHit /= wsum;
    w = min(histSamples, u.maxHistory) * u.historyScale;
    // u.footprintWeight 1: a footprint the tests cut (wsum < 1) is an edge whose passed taps are a
    // neighbour's: the history counts by the share that passed.
    if (u.footprintWeight > 0.0) { w *= min(wsum, 1.0); }
    if (u.historyFilter == 1u && allTaps) {
      // A zero-weight inner tap was not tested: the bilinear colour stands in (its weight is 0 too).
      for (var k = 0; k < 4; k++) {
        let o = vec2i(k & 1, k >> 1u);
        let bw = select(1.0 - fr.x, fr.x, o.x == 1) * select(1.0 - fr.y, fr.y, o.y == 1);
        if (bw <= 0.0) { inner[k] = histColor; }
      }
      let wx = temporalCatmullRom(fr.x);
      let wy = temporalCatmullRom(fr.y);
      var c = vec4f(0.0);
      for (var j = 0; j < 4; j++) {
        var row = vec4f(0.0);
        for (var i = 0; i < 4; i++) {
          if (wx[i] * wy[j] == 0.0) { continue; }
          let ci = clamp(vec2i(i, j) - 1, vec2i(0), vec2i(1));
          var hc = inner[ci.x + 2 * ci.y];
          if (i == 0 || i == 3 || j == 0 || j == 3) {
            let tap = temporalTap(vec2i(q0) + vec2i(i, j) - 1, osize, hit, expected, normal);
            if (tap.ok) { hc = tap.hc; }
          }
          row += wx[i] * hc;
        }
        c += wy[j] * row;
      }
      if (!temporalBad(c)) { histColor = clamp(c, lo, hi); }
    }
  }
  var r: VptOut;
  if (w <= 0.0) {
    r.out0 = cur;
    r.out1 = vec4f(normal, depth);
    r.out2 = vec4f(hit, n, 0.0, 0.0);
    return r;
  }
  let a = w / (n + w);
  r.out0 = cur + (histColor - cur) * a;
  let g = vec4f(normal, depth);
  // A miss keeps the history's normal and depth only where the history hit.
  r.out1 = vec4f(0.0);
  if (hit > 0.0) { r.out1 = g + (histGuide - g) * a; }
  r.out2 = vec4f(hit + (histHit - hit) * a, n + w, 0.0, 0.0);
  return r;
}
`;
