import { ACES_INPUT_MAX, TONE_MAP_DEFINE, TONE_MAP_OPERATOR_ID as ID } from './tone-mapping-operators.js';

// Tone mapping, one operator per compiled variant: the core preprocessor keeps the branch of
// the TONEMAP_OPERATOR flag (tone-mapping.ts). Same structure and operation order as
// tone-mapping.glsl.ts; every constant is one literal. Radiance is non-negative; negative
// noise is clamped to 0 before any curve.
export const TONE_MAP = /* wgsl */ `
#if ${TONE_MAP_DEFINE} == ${ID.clamp}
// Clamp: no curve, values above 1 clip.
fn toneMap(c: vec3f) -> vec3f {
  return min(c, vec3f(1.0));
}
#elif ${TONE_MAP_DEFINE} == ${ID.reinhard}
// Reinhard per channel, c / (1 + c) (Reinhard et al. 2002, "Photographic Tone Reproduction for Digital Images"), as in Lesar, Bohak, Marolt, Web3D 2018.
fn toneMap(c: vec3f) -> vec3f {
  return c / (1.0 + c);
}
#elif ${TONE_MAP_DEFINE} == ${ID.aces}
// ACES filmic fit, K. Narkowicz, "ACES Filmic Tone Mapping Curve" (2016), pre-exposed: 1 -> ~0.8.
fn toneMap(c: vec3f) -> vec3f {
  let x = min(c, vec3f(${ACES_INPUT_MAX.toFixed(1)}));
  return clamp((x * (2.51 * x + 0.03)) / (x * (2.43 * x + 0.59) + 0.14), vec3f(0.0), vec3f(1.0));
}
#elif ${TONE_MAP_DEFINE} == ${ID['pbr-neutral']}
// Khronos PBR Neutral, reference implementation (KhronosGroup/ToneMapping, PBR_Neutral/pbrNeutral.glsl):
// startCompression 0.76 = 0.8 - 0.04, d = 0.24, d*d = 0.0576, desaturation 0.15.
fn toneMap(color: vec3f) -> vec3f {
  let x = min(color.r, min(color.g, color.b));
  let offset = select(0.04, x - 6.25 * x * x, x < 0.08);
  var c = color - vec3f(offset);
  let peak = max(c.r, max(c.g, c.b));
  if (peak < 0.76) { return c; }
  let newPeak = 1.0 - 0.0576 / (peak + 0.24 - 0.76);
  c = c * (newPeak / peak);
  let g = 1.0 - 1.0 / (0.15 * (peak - newPeak) + 1.0);
  // mix(c, vec3f(newPeak), g) written out, so both languages round it alike.
  return c * (1.0 - g) + vec3f(newPeak * g);
}
#endif

@fragment fn fs_main(@builtin(position) fragCoord: vec4f) -> VptOut {
  let p = textureLoad(inputImage, vptPixel(fragCoord), 0);
  var o: VptOut;
  o.out0 = vec4f(toneMap(max(p.rgb, vec3f(0.0))), p.a);
  return o;
}
`;
