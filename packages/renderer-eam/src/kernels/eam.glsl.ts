// Emission-absorption (Max 1995, "Optical models for direct volume rendering", eq. 4-5)
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
  if (t.x < t.y) {
    float offset = rngNext(rng);
    float len = t.y - t.x;
    int n = max(1, int(ceil(len / u.stepSize)));
    float seg = len / float(n);
    for (int k = 0; k < n; k++) {
      float s = t.x + (float(k) + offset) * seg;
      vec4 tf = transferLookup(sampleVolume(u.cameraPosition + dir * s));
      float alpha = 1.0 - exp(-(u.densityScale * tf.a) * seg);
      color += (transmittance * alpha) * tf.rgb;
      transmittance *= 1.0 - alpha;
      if (transmittance < u.cutoff) { transmittance = 0.0; break; }
    }
  }
  vpt_out0 = vec4(color + transmittance * u.background.rgb, 1.0 - transmittance);
}
`;

// Running mean: acc_n = acc_{n-1} + (x_n - acc_{n-1}) / (n + 1), stable over very long runs.
export const integrate = /* glsl */ `
void main() {
  ivec2 p = vptPixel();
  vec4 f = texelFetch(frame0, p, 0);
  if (u.iteration == 0u) { vpt_out0 = f; return; }
  vec4 a = texelFetch(accum0, p, 0);
  float w = 1.0 / float(u.iteration + 1u);
  vpt_out0 = a + (f - a) * w;
}
`;

export const render = /* glsl */ `
void main() {
  vpt_out0 = texelFetch(accum0, vptPixel(), 0);
}
`;
