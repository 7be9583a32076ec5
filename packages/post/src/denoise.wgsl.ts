// Edge-avoiding à-trous wavelet filter (Dammertz, Sewtz, Hanika, Lensch 2010, HPG, Sec. 3: c_{i+1}(p) =
// Σ_k h(k) w(p, q) c_i(q), q = p + 2^i k, B3-spline h) with SVGF's variance-guided weights (Schied et al.
// 2017, HPG, Sec. 4.4, Eq. 3-5: w_z, w_n, w_l with σ_l scaled by the 3x3-filtered standard deviation, and the
// variance filtered along, Var_{i+1} = Σ w² Var_i / (Σ w)²). One draw per level i; the twin is
// denoise.glsl.ts, the CPU twin denoiseRef in denoise-reference.ts.
export const DENOISE = /* wgsl */ `
fn denoiseLuminance(c: vec3f) -> f32 { return dot(c, vec3f(0.2126, 0.7152, 0.0722)); }

// Variance of the mean luminance at q: (E[l²] − E[l]²)/(n − 1) from the accumulated moments.
fn momentVariance(q: vec2i) -> f32 {
  let m = textureLoad(guideMoments, q, 0);
  return max(m.y - m.x * m.x, 0.0) / max(m.z - 1.0, 1.0);
}

// The luminance variance at q that level i filters: the moments' at level 0, after a single sample the
// 3x3 spatial variance of the luminance, later the previous level's filtered variance (inputState.x).
fn levelVariance(q: vec2i, size: vec2i) -> f32 {
  if (u.stepWidth > 1) { return textureLoad(inputState, q, 0).x; }
  if (textureLoad(guideMoments, q, 0).z >= 2.0) { return momentVariance(q); }
  var s1 = 0.0;
  var s2 = 0.0;
  for (var dy = -1; dy <= 1; dy++) {
    for (var dx = -1; dx <= 1; dx++) {
      let l = denoiseLuminance(textureLoad(inputImage, clamp(q + vec2i(dx, dy), vec2i(0), size - 1), 0).rgb);
      s1 += l;
      s2 += l * l;
    }
  }
  return max(s2 / 9.0 - (s1 / 9.0) * (s1 / 9.0), 0.0);
}

// The depth guide: mean depth over the samples that hit (0 where none did), from the two guide texels.
fn depthOf(normalDepth: vec4f, albedoHit: vec4f) -> f32 {
  if (albedoHit.a > 0.0) { return normalDepth.w / albedoHit.a; }
  return 0.0;
}
fn guideDepth(q: vec2i) -> f32 {
  return depthOf(textureLoad(guideNormalDepth, q, 0), textureLoad(guideAlbedo, q, 0));
}

@fragment fn fs_main(@builtin(position) fragCoord: vec4f) -> VptOut {
  let p = vptPixel(fragCoord);
  let size = vptTargetSize();
  let c = textureLoad(inputImage, p, 0);
  var o: VptOut;
  if (u.passThrough != 0) { o.out0 = c; o.out1 = vec4f(0.0); return o; }
  // σ_l's standard deviation: the level's variance under a 3x3 binomial filter (SVGF's g3x3).
  var vr = 0.0;
  var wsum = 0.0;
  for (var dy = -1; dy <= 1; dy++) {
    for (var dx = -1; dx <= 1; dx++) {
      let g = f32((2 - abs(dx)) * (2 - abs(dy)));
      vr += g * levelVariance(clamp(p + vec2i(dx, dy), vec2i(0), size - 1), size);
      wsum += g;
    }
  }
  vr = vr / wsum;
  let sigmaL = u.colorSigma * u.sigmaScale * sqrt(vr) + 1e-10;
  let lp = denoiseLuminance(c.rgb);
  let ndp = textureLoad(guideNormalDepth, p, 0);
  let ap = textureLoad(guideAlbedo, p, 0);
  let np = length(ndp.xyz);
  let zp = depthOf(ndp, ap);
  // Screen-space depth gradient (central differences) for w_z's |∇z·(p − q)|.
  let dz = vec2f(
    guideDepth(clamp(p + vec2i(1, 0), vec2i(0), size - 1)) - guideDepth(clamp(p - vec2i(1, 0), vec2i(0), size - 1)),
    guideDepth(clamp(p + vec2i(0, 1), vec2i(0), size - 1)) - guideDepth(clamp(p - vec2i(0, 1), vec2i(0), size - 1))) * 0.5;
  var sum = vec4f(0.0);
  var weights = 0.0;
  var varSum = 0.0;
  for (var ky = -2; ky <= 2; ky++) {
    for (var kx = -2; kx <= 2; kx++) {
      let q = p + vec2i(kx, ky) * u.stepWidth;
      if (q.x < 0 || q.y < 0 || q.x >= size.x || q.y >= size.y) { continue; }
      let h = b3Tap(abs(kx)) * b3Tap(abs(ky));
      let cq = textureLoad(inputImage, q, 0);
      let wl = exp(-abs(denoiseLuminance(cq.rgb) - lp) / sigmaL);
      let ndq = textureLoad(guideNormalDepth, q, 0);
      let aq = textureLoad(guideAlbedo, q, 0);
      let zq = depthOf(ndq, aq);
      let wz = exp(-abs(zq - zp) / (u.depthSigma * abs(dot(dz, vec2f(q - p))) + u.depthEpsilon));
      let nq = length(ndq.xyz);
      var wn = 1.0;
      if (np > 1e-3 && nq > 1e-3) {
        let d = dot(ndp.xyz, ndq.xyz) / (np * nq);
        if (d > 0.0) { wn = pow(min(d, 1.0), u.normalSigma); } else { wn = 0.0; }
      }
      let da = aq - ap;
      let wa = exp(-dot(da, da) / (u.albedoSigma * u.albedoSigma));
      let w = h * wl * wz * wn * wa;
      sum += w * cq;
      weights += w;
      varSum += w * w * levelVariance(q, size);
    }
  }
  // Fade as the estimate converges: the level's change is scaled by the relative standard error of the
  // pixel's mean over fadeError (capped at 1), which falls as 1/sqrt(n), so a converged image is kept.
  let m = textureLoad(guideMoments, p, 0);
  var fade = 1.0;
  if (m.z >= 2.0) { fade = min(sqrt(momentVariance(p)) / (u.fadeError * max(abs(m.x), 1e-6)), 1.0); }
  o.out0 = c + (sum / weights - c) * fade;
  o.out1 = vec4f(varSum / (weights * weights), 0.0, 0.0, 0.0);
  return o;
}
`;

/** The B3-spline taps (1/16, 1/4, 3/8, 1/4, 1/16) by |offset|, prepended to DENOISE. */
export const B3_TAPS = /* wgsl */ `
fn b3Tap(k: i32) -> f32 { if (k == 0) { return 0.375; } if (k == 1) { return 0.25; } return 0.0625; }
`;
