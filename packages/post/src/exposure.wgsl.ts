// Exposure: scale linear radiance by 2^exposure (photographic stops). The host packs the
// factor, so the kernel does one multiply and both backends round it the same way.
export const EXPOSURE = /* wgsl */ `
@fragment fn fs_main(@builtin(position) fragCoord: vec4f) -> VptOut {
  let p = textureLoad(inputImage, vptPixel(fragCoord), 0);
  var o: VptOut;
  o.out0 = vec4f(p.rgb * u.scale, p.a);
  return o;
}
`;
