import { MAX_MARCH_STEPS } from '@vpt/core';

// Emission-absorption (Max 1995, "Optical models for direct volume rendering", IEEE TVCG 1(2), the emission + absorption model)
// by a stratified, randomly offset ray march; alpha = 1 - exp(-sigma_t * segment length),
// so a homogeneous medium yields exactly c·(1 - exp(-sigma_t·L)).

export const generate = /* glsl */ `
void main() {
  ivec2 pixel = vptPixel();
  uint rng = rngInit(pixel, u.iteration, u.seed);
  vec3 dir = jitteredCameraRay(pixel, vptTargetSize(), rng);
  vec2 t = intersectBox(u.cameraPosition, dir, u.boxMin, u.boxMax);
  vec3 color = vec3(0.0);
  float transmittance = 1.0;
#if VPT_GUIDES
  // Denoiser guides at the mean termination depth: segments weighted by T·alpha, their share of the pixel.
  float guideWeight = 0.0;
  float guideDepth = 0.0;
#endif
  if (t.x < t.y) {
    float offset = rngNext(rng);
    float len = t.y - t.x;
    int n = max(1, int(min(ceil(len / u.stepSize), ${MAX_MARCH_STEPS}.0)));
    float seg = len / float(n);
    for (int k = 0; k < n; k++) {
      float s = t.x + (float(k) + offset) * seg;
      vec4 tf = transferAt(u.cameraPosition + dir * s);
      float alpha = 1.0 - exp(-(u.densityScale * tf.a) * seg);
      color += (transmittance * alpha) * tf.rgb;
#if VPT_GUIDES
      guideWeight += transmittance * alpha;
      guideDepth += (transmittance * alpha) * s;
#endif
      transmittance *= 1.0 - alpha;
      if (transmittance < u.cutoff) { transmittance = 0.0; break; }
    }
  }
  vpt_out0 = vec4(color + transmittance * u.background.rgb, 1.0 - transmittance);
#if VPT_GUIDES
  vpt_out1 = vec4(0.0);
  vpt_out2 = vec4(0.0);
  if (guideWeight > 0.0) {
    float tg = guideDepth / guideWeight;
    vec3 pg = u.cameraPosition + dir * tg;
    vpt_out1 = guideNormalDepth(pg, tg);
    vpt_out2 = guideAlbedo(transferAt(pg).rgb);
  }
#endif
}
`;
