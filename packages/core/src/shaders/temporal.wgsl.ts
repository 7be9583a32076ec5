// Temporal reuse (WGSL; the twin is temporal.glsl.ts, composed in temporal.ts): the previous view's
// image reprojected through the depth guide and blended with the new samples, as SVGF's temporal
// accumulation (Schied et al. 2017, HPG, Sec. 4.1: backprojection, depth/normal consistency tests,
// bilinear taps over the consistent samples, history clamped in length).

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
  if (u.historyScale > 0.0) {
    let film = (vec2f(p) + 0.5) / vec2f(size);
    let dir = temporalRay(film, u.newForward, u.newRight, u.newUp, u.newTanHalfFovy, u.newAspect);
    // A hit's world point, or a miss's direction (a point at infinity).
    var d = dir;
    if (hit > 0.0) { d = u.newPosition + dir * depth - u.oldPosition; }
    let z = dot(d, u.oldForward);
    if (z > 1e-6) {
      let expected = length(d);
      let ofilm = vec2f(
        0.5 + 0.5 * dot(d, u.oldRight) / (z * u.oldTanHalfFovy * u.oldAspect),
        0.5 - 0.5 * dot(d, u.oldUp) / (z * u.oldTanHalfFovy));
      let osize = vec2i(textureDimensions(historyImage));
      let q = ofilm * vec2f(osize) - 0.5;
      let q0 = floor(q);
      let fr = q - q0;
      for (var k = 0; k < 4; k++) {
        let o = vec2i(k & 1, k >> 1u);
        let t = vec2i(q0) + o;
        if (t.x < 0 || t.y < 0 || t.x >= osize.x || t.y >= osize.y) { continue; }
        let bw = select(1.0 - fr.x, fr.x, o.x == 1) * select(1.0 - fr.y, fr.y, o.y == 1);
        if (bw <= 0.0) { continue; }
        let hc = textureLoad(historyImage, t, 0);
        let hg = textureLoad(historyGuide, t, 0);
        let hs = textureLoad(historyState, t, 0);
        if (temporalBad(hc) || temporalBad(hg) || temporalBad(hs)) { continue; }
        var ok: bool;
        if (hit > 0.0) {
          ok = hs.x > 0.0 && abs(hg.w - expected) <= u.depthTolerance * expected;
          let nn = length(normal) * length(hg.xyz);
          if (ok && nn > 1e-12) { ok = dot(normal, hg.xyz) >= u.normalCos * nn; }
        } else {
          ok = hs.x <= 0.5;
        }
        if (!ok) { continue; }
        histColor += bw * hc;
        histGuide += bw * vec4f(hg.xyz, depth + (hg.w - expected));
        histSamples += bw * hs.y;
        histHit += bw * hs.x;
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
