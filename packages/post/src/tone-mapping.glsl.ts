import { ACES_INPUT_MAX, TONE_MAP_DEFINE, TONE_MAP_OPERATOR_ID as ID } from './tone-mapping-operators.js';

// Tone mapping, one operator per compiled variant: the core preprocessor keeps the branch of
// the TONEMAP_OPERATOR flag (tone-mapping.ts). Same structure and operation order as
// tone-mapping.wgsl.ts; every constant is one literal, so
// no compiler folds constant expressions in a different precision on one backend.
// Radiance is non-negative; negative noise is clamped to 0 before any curve.
export const TONE_MAP = /* glsl */ `
#if ${TONE_MAP_DEFINE} == ${ID.clamp}
// Clamp: no curve, values above 1 clip.
vec3 toneMap(vec3 c) {
  return min(c, vec3(1.0));
}
#elif ${TONE_MAP_DEFINE} == ${ID.reinhard}
// Reinhard per channel, c / (1 + c) (Reinhard et al. 2002, "Photographic Tone Reproduction for Digital Images"), as in Lesar, Bohak, Marolt, Web3D 2018.
vec3 toneMap(vec3 c) {
  return c / (1.0 + c);
}
#elif ${TONE_MAP_DEFINE} == ${ID.aces}
// ACES filmic fit, K. Narkowicz, "ACES Filmic Tone Mapping Curve" (2016), pre-exposed: 1 -> ~0.8.
vec3 toneMap(vec3 c) {
  vec3 x = min(c, vec3(${ACES_INPUT_MAX.toFixed(1)}));
  return clamp((x * (2.51 * x + 0.03)) / (x * (2.43 * x + 0.59) + 0.14), 0.0, 1.0);
}
#elif ${TONE_MAP_DEFINE} == ${ID['pbr-neutral']}
// Khronos PBR Neutral, reference implementation (KhronosGroup/ToneMapping, PBR_Neutral/pbrNeutral.glsl):
// startCompression 0.76 = 0.8 - 0.04, d = 0.24, d*d = 0.0576, desaturation 0.15.
vec3 toneMap(vec3 color) {
  float x = min(color.r, min(color.g, color.b));
  float offset = x < 0.08 ? x - 6.25 * x * x : 0.04;
  vec3 c = color - vec3(offset);
  float peak = max(c.r, max(c.g, c.b));
  if (peak < 0.76) return c;
  float newPeak = 1.0 - 0.0576 / (peak + 0.24 - 0.76);
  c = c * (newPeak / peak);
  float g = 1.0 - 1.0 / (0.15 * (peak - newPeak) + 1.0);
  // mix(c, vec3(newPeak), g) written out, so both languages round it alike.
  return c * (1.0 - g) + vec3(newPeak * g);
}
#endif

void main() {
  vec4 p = texelFetch(inputImage, vptPixel(), 0);
  vpt_out0 = vec4(toneMap(max(p.rgb, vec3(0.0))), p.a);
}
`;
