// Denoiser guides (GLSL; the twin is guides.wgsl.ts, composed in guides.ts). A renderer's generate
// kernel writes two extra outputs under `#if VPT_GUIDES` at the point that stands for its pixel
// (MCRT: first real collision; ISO: the surface hit; EAM: the mean termination depth), and the
// context averages them over iterations (GUIDE_INTEGRATE) for the denoise post step.

/** Generate-pass helpers: the guide vectors at a world point p at distance t along the camera ray. */
export const GUIDES = /* glsl */ `
// Normal guide: the normalised volume gradient by central differences one voxel apart, pointing
// down the gradient (from dense to clear); 0 where the field is flat.
vec4 guideNormalDepth(vec3 p, float t) {
  vec3 h = (u.boxMax - u.boxMin) / vec3(u.volumeDims.xyz);
  vec3 g = vec3(
    sampleVolume(p + vec3(h.x, 0.0, 0.0)) - sampleVolume(p - vec3(h.x, 0.0, 0.0)),
    sampleVolume(p + vec3(0.0, h.y, 0.0)) - sampleVolume(p - vec3(0.0, h.y, 0.0)),
    sampleVolume(p + vec3(0.0, 0.0, h.z)) - sampleVolume(p - vec3(0.0, 0.0, h.z))) / (2.0 * h);
  float len = length(g);
  return vec4(len > 1e-20 ? -g / len : vec3(0.0), t);
}
// Albedo guide: the colour at the point, clamped to [0, 1]; a = 1 marks a hit (misses write 0).
vec4 guideAlbedo(vec3 albedo) {
  return vec4(clamp(albedo, 0.0, 1.0), 1.0);
}
`;

/**
 * Running means of the guides and of the radiance's luminance moments (SVGF, Schied et al.
 * 2017, Sec. 4.2: per-pixel variance from the first and second moments):
 * out0 = mean(normal, depth), out1 = mean(albedo, hit), out2 = (mean l, mean l², n, 0).
 * Misses contribute zeros. GUIDE_FRAMES: the renderer writes guide frames; else only the moments.
 */
export const GUIDE_INTEGRATE = /* glsl */ `
void main() {
  ivec2 p = vptPixel();
  float l = dot(texelFetch(radiance, p, 0).rgb, vec3(0.2126, 0.7152, 0.0722));
#if GUIDE_FRAMES
  vec4 f0 = texelFetch(guideFrame0, p, 0);
  vec4 f1 = texelFetch(guideFrame1, p, 0);
#else
  vec4 f0 = vec4(0.0);
  vec4 f1 = vec4(0.0);
#endif
  vec4 f2 = vec4(l, l * l, float(u.iteration + 1u), 0.0);
  if (u.iteration == 0u) { vpt_out0 = f0; vpt_out1 = f1; vpt_out2 = f2; return; }
  float w = 1.0 / float(u.iteration + 1u);
  vec4 a0 = texelFetch(guideAccum0, p, 0);
  vec4 a1 = texelFetch(guideAccum1, p, 0);
  vec4 a2 = texelFetch(guideAccum2, p, 0);
  vpt_out0 = a0 + (f0 - a0) * w;
  vpt_out1 = a1 + (f1 - a1) * w;
  vpt_out2 = vec4(a2.xy + (f2.xy - a2.xy) * w, f2.z, 0.0);
}
`;
