import { MAX_MARCH_STEPS } from '@vpt/core';

// Emission-absorption (Max 1995, "Optical models for direct volume rendering", IEEE TVCG 1(2), the emission + absorption model)
// by a stratified, randomly offset ray march; alpha = 1 - exp(-sigma_t * segment length).

export const generate = /* wgsl */ `
@fragment fn fs_main(@builtin(position) fragCoord: vec4f) -> VptOut {
  let pixel = vptPixel(fragCoord);
  var rng = rngInit(pixel, u.iteration, u.seed);
  let dir = jitteredCameraRay(pixel, vptTargetSize(), &rng);
  let t = intersectBox(u.cameraPosition, dir, u.boxMin, u.boxMax);
  var color = vec3f(0.0);
  var transmittance = 1.0;
#if VPT_GUIDES
  // Denoiser guides at the mean termination depth: segments weighted by T·alpha, their share of the pixel.
  var guideWeight = 0.0;
  var guideDepth = 0.0;
#endif
  if (t.x < t.y) {
    let offset = rngNext(&rng);
    let len = t.y - t.x;
    let n = max(1, i32(min(ceil(len / u.stepSize), ${MAX_MARCH_STEPS}.0)));
    let seg = len / f32(n);
    for (var k = 0; k < n; k++) {
      let s = t.x + (f32(k) + offset) * seg;
      let tf = transferAt(u.cameraPosition + dir * s);
      let alpha = 1.0 - exp(-(u.densityScale * tf.a) * seg);
      color += (transmittance * alpha) * tf.rgb;
#if VPT_GUIDES
      guideWeight += transmittance * alpha;
      guideDepth += (transmittance * alpha) * s;
#endif
      transmittance *= 1.0 - alpha;
      if (transmittance < u.cutoff) { transmittance = 0.0; break; }
    }
  }
  var o: VptOut;
  o.out0 = vec4f(color + transmittance * u.background.rgb, 1.0 - transmittance);
#if VPT_GUIDES
  if (guideWeight > 0.0) {
    let tg = guideDepth / guideWeight;
    let pg = u.cameraPosition + dir * tg;
    o.out1 = guideNormalDepth(pg, tg);
    o.out2 = guideAlbedo(transferAt(pg).rgb);
  }
#endif
  return o;
}
`;
