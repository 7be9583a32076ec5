// sRGB OETF, IEC 61966-2-1:1999: linear toe below 0.0031308, 1.055 x^(1/2.4) - 0.055 above.
// Constants are single literals (1/2.4 written out) so no compiler folds them differently.
export const SRGB_ENCODE = /* glsl */ `
float srgbEncode(float x) {
  float c = clamp(x, 0.0, 1.0);
  if (c <= 0.0031308) return 12.92 * c;
  return 1.055 * pow(c, 0.41666666666666667) - 0.055;
}

void main() {
  vec4 p = texelFetch(inputImage, vptPixel(), 0);
  vpt_out0 = vec4(srgbEncode(p.r), srgbEncode(p.g), srgbEncode(p.b), p.a);
}
`;
