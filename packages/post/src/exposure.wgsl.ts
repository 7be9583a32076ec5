// Exposure: scale linear radiance by 2^exposure (photographic stops). The host packs the
// factor, so the kernel does one multiply and both backends round it the same way. The input
// is first clamped to ±u.limit = EXPOSURE_OUTPUT_MAX / 2^exposure, so the product stays
// within ±EXPOSURE_OUTPUT_MAX: chained steps never overflow to Inf (which the tone mappers
// would turn into NaN), and no Inf is ever computed (WGSL may assume there is none).
export const EXPOSURE = /* wgsl */ `
@fragment fn fs_main(@builtin(position) fragCoord: vec4f) -> VptOut {
  let p = textureLoad(inputImage, vptPixel(fragCoord), 0);
  var o: VptOut;
  o.out0 = vec4f(clamp(p.rgb, vec3f(-u.limit), vec3f(u.limit)) * u.scale, p.a);
  return o;
}
`;
