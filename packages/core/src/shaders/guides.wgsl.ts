// Denoiser guides (WGSL; the twin is guides.glsl.ts, composed in guides.ts). A renderer's generate
// kernel writes two extra outputs under `#if VPT_GUIDES` at the point that stands for its pixel
// (MCRT: first real collision; ISO: the surface hit; EAM: the mean termination depth), and the
// context averages them over iterations (GUIDE_INTEGRATE) for the denoise post step.

/** Generate-pass helpers: the guide vectors at a world point p at distance t along the camera ray. */
export const GUIDES = /* wgsl */ `
// Normal guide: the normalised volume gradient by central differences one voxel apart, pointing
// down the gradient (from dense to clear); 0 where the field is flat.
fn guideNormalDepth(p: vec3f, t: f32) -> vec4f {
  let h = (u.boxMax - u.boxMin) / vec3f(u.volumeDims.xyz);
  let g = vec3f(
    sampleVolume(p + vec3f(h.x, 0.0, 0.0)) - sampleVolume(p - vec3f(h.x, 0.0, 0.0)),
    sampleVolume(p + vec3f(0.0, h.y, 0.0)) - sampleVolume(p - vec3f(0.0, h.y, 0.0)),
    sampleVolume(p + vec3f(0.0, 0.0, h.z)) - sampleVolume(p - vec3f(0.0, 0.0, h.z))) / (2.0 * h);
  let len = length(g);
  var n = vec3f(0.0);
  if (len > 1e-20) { n = -g / len; }
  return vec4f(n, t);
}
// Albedo guide: the colour at the point, clamped to [0, 1]; a = 1 marks a hit (misses write 0).
fn guideAlbedo(albedo: vec3f) -> vec4f {
  return vec4f(clamp(albedo, vec3f(0.0), vec3f(1.0)), 1.0);
}
`;

/**
 * Running means of the guides and of the radiance's luminance moments (SVGF, Schied et al.
 * 2017, Sec. 4.2: per-pixel variance from the first and second moments):
 * out0 = mean(normal, depth), out1 = mean(albedo, hit), out2 = (mean l, mean l², n, 0).
 * Misses contribute zeros. GUIDE_FRAMES: the renderer writes guide frames; else only the moments.
 */
export const GUIDE_INTEGRATE = /* wgsl */ `
@fragment fn fs_main(@builtin(position) fragCoord: vec4f) -> VptOut {
  let p = vptPixel(fragCoord);
  let l = dot(textureLoad(radiance, p, 0).rgb, vec3f(0.2126, 0.7152, 0.0722));
#if GUIDE_FRAMES
  let f0 = textureLoad(guideFrame0, p, 0);
  let f1 = textureLoad(guideFrame1, p, 0);
#else
  let f0 = vec4f(0.0);
  let f1 = vec4f(0.0);
#endif
  let f2 = vec4f(l, l * l, f32(u.iteration + 1u), 0.0);
  var o: VptOut;
  if (u.iteration == 0u) { o.out0 = f0; o.out1 = f1; o.out2 = f2; return o; }
  let w = 1.0 / f32(u.iteration + 1u);
  let a0 = textureLoad(guideAccum0, p, 0);
  let a1 = textureLoad(guideAccum1, p, 0);
  let a2 = textureLoad(guideAccum2, p, 0);
  o.out0 = a0 + (f0 - a0) * w;
  o.out1 = a1 + (f1 - a1) * w;
  o.out2 = vec4f(a2.xy + (f2.xy - a2.xy) * w, f2.z, 0.0);
  return o;
}
`;
