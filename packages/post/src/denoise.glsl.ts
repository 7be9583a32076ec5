// Edge-avoiding à-trous wavelet filter (Dammertz, Sewtz, Hanika, Lensch 2010, HPG, Sec. 3: c_{i+1}(p) =
// Σ_k h(k) w(p, q) c_i(q), q = p + 2^i k, B3-spline h) with SVGF's variance-guided weights (Schied et al.
// 2017, HPG, Sec. 4.4, Eq. 3-5: w_z, w_n, w_l with σ_l scaled by the 3x3-filtered standard deviation, and the
// variance filtered along, Var_{i+1} = Σ w² Var_i / (Σ w)²). One draw per level i; the twin is
// denoise.wgsl.ts, the CPU twin denoiseRef in denoise-reference.ts.
export const DENOISE = /* glsl */ `
float denoiseLuminance(vec3 c) { return dot(c, vec3(0.2126, 0.7152, 0.0722)); }

// Variance of the mean luminance at q: (E[l²] − E[l]²)/(n − 1) from the accumulated moments.
float momentVariance(ivec2 q) {
  vec4 m = texelFetch(guideMoments, q, 0);
  return max(m.y - m.x * m.x, 0.0) / max(m.z - 1.0, 1.0);
}

// The luminance variance at q that level i filters: the moments' at level 0, after a single sample the
// 3x3 spatial variance of the luminance, later the previous level's filtered variance (inputState.x).
float levelVariance(ivec2 q, ivec2 size) {
  if (u.stepWidth > 1) return texelFetch(inputState, q, 0).x;
  if (texelFetch(guideMoments, q, 0).z >= 2.0) return momentVariance(q);
  float s1 = 0.0;
  float s2 = 0.0;
  for (int dy = -1; dy <= 1; dy++) {
    for (int dx = -1; dx <= 1; dx++) {
      float l = denoiseLuminance(texelFetch(inputImage, clamp(q + ivec2(dx, dy), ivec2(0), size - 1), 0).rgb);
      s1 += l;
      s2 += l * l;
    }
  }
  return max(s2 / 9.0 - (s1 / 9.0) * (s1 / 9.0), 0.0);
}

// The depth guide: mean depth over the samples that hit (0 where none did), from the two guide texels.
float depthOf(vec4 normalDepth, vec4 albedoHit) {
  return albedoHit.a > 0.0 ? normalDepth.w / albedoHit.a : 0.0;
}
float guideDepth(ivec2 q) {
  return depthOf(texelFetch(guideNormalDepth, q, 0), texelFetch(guideAlbedo, q, 0));
}

void main() {
  ivec2 p = vptPixel();
  ivec2 size = vptTargetSize();
  vec4 c = texelFetch(inputImage, p, 0);
  if (u.passThrough != 0) { vpt_out0 = c; vpt_out1 = vec4(0.0); return; }
  // σ_l's standard deviation: the level's variance under a 3x3 binomial filter (SVGF's g3x3).
  float vr = 0.0;
  float wsum = 0.0;
  for (int dy = -1; dy <= 1; dy++) {
    for (int dx = -1; dx <= 1; dx++) {
      float g = float((2 - abs(dx)) * (2 - abs(dy)));
      vr += g * levelVariance(clamp(p + ivec2(dx, dy), ivec2(0), size - 1), size);
      wsum += g;
    }
  }
  vr = vr / wsum;
  float sigmaL = u.colorSigma * u.sigmaScale * sqrt(vr) + 1e-10;
  float lp = denoiseLuminance(c.rgb);
  vec4 ndp = texelFetch(guideNormalDepth, p, 0);
  vec4 ap = texelFetch(guideAlbedo, p, 0);
  float np = length(ndp.xyz);
  float zp = depthOf(ndp, ap);
  // Screen-space depth gradient (central differences) for w_z's |∇z·(p − q)|.
  vec2 dz = vec2(
    guideDepth(clamp(p + ivec2(1, 0), ivec2(0), size - 1)) - guideDepth(clamp(p - ivec2(1, 0), ivec2(0), size - 1)),
    guideDepth(clamp(p + ivec2(0, 1), ivec2(0), size - 1)) - guideDepth(clamp(p - ivec2(0, 1), ivec2(0), size - 1))) * 0.5;
  vec4 sum = vec4(0.0);
  float weights = 0.0;
  float varSum = 0.0;
  for (int ky = -2; ky <= 2; ky++) {
    for (int kx = -2; kx <= 2; kx++) {
      ivec2 q = p + ivec2(kx, ky) * u.stepWidth;
      if (q.x < 0 || q.y < 0 || q.x >= size.x || q.y >= size.y) continue;
      float h = b3Tap(abs(kx)) * b3Tap(abs(ky));
      vec4 cq = texelFetch(inputImage, q, 0);
      float wl = exp(-abs(denoiseLuminance(cq.rgb) - lp) / sigmaL);
      vec4 ndq = texelFetch(guideNormalDepth, q, 0);
      vec4 aq = texelFetch(guideAlbedo, q, 0);
      float zq = depthOf(ndq, aq);
      float wz = exp(-abs(zq - zp) / (u.depthSigma * abs(dot(dz, vec2(q - p))) + u.depthEpsilon));
      float nq = length(ndq.xyz);
      float wn = 1.0;
      if (np > 1e-3 && nq > 1e-3) {
        float d = dot(ndp.xyz, ndq.xyz) / (np * nq);
        wn = d > 0.0 ? pow(min(d, 1.0), u.normalSigma) : 0.0;
      }
      vec4 da = aq - ap;
      float wa = exp(-dot(da, da) / (u.albedoSigma * u.albedoSigma));
      float w = h * wl * wz * wn * wa;
      sum += w * cq;
      weights += w;
      varSum += w * w * levelVariance(q, size);
    }
  }
  // Fade as the estimate converges: the level's change is scaled by the relative standard error of the
  // pixel's mean over fadeError (capped at 1), which falls as 1/sqrt(n), so a converged image is kept.
  vec4 m = texelFetch(guideMoments, p, 0);
  float fade = m.z >= 2.0 ? min(sqrt(momentVariance(p)) / (u.fadeError * max(abs(m.x), 1e-6)), 1.0) : 1.0;
  vpt_out0 = c + (sum / weights - c) * fade;
  vpt_out1 = vec4(varSum / (weights * weights), 0.0, 0.0, 0.0);
}
`;

/** The B3-spline taps (1/16, 1/4, 3/8, 1/4, 1/16) by |offset|, prepended to DENOISE. */
export const B3_TAPS = /* glsl */ `
float b3Tap(int k) { return k == 0 ? 0.375 : (k == 1 ? 0.25 : 0.0625); }
`;
