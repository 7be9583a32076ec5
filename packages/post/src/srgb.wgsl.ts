// sRGB OETF, IEC 61966-2-1:1999: linear toe below 0.0031308, 1.055 x^(1/2.4) - 0.055 above.
// Constants are single literals (1/2.4 written out) so no compiler folds them differently.
export const SRGB_ENCODE = /* wgsl */ `
fn srgbEncode(x: f32) -> f32 {
  let c = clamp(x, 0.0, 1.0);
  if (c <= 0.0031308) { return 12.92 * c; }
  return 1.055 * pow(c, 0.41666666666666667) - 0.055;
}

@fragment fn fs_main(@builtin(position) fragCoord: vec4f) -> VptOut {
  let p = textureLoad(inputImage, vptPixel(fragCoord), 0);
  var o: VptOut;
  o.out0 = vec4f(srgbEncode(p.r), srgbEncode(p.g), srgbEncode(p.b), p.a);
  return o;
}
`;
