// Exposure: scale linear radiance by 2^exposure (photographic stops). The host packs the
// factor, so the kernel does one multiply and both backends round it the same way.
export const EXPOSURE = /* glsl */ `
void main() {
  vec4 p = texelFetch(inputImage, vptPixel(), 0);
  vpt_out0 = vec4(p.rgb * u.scale, p.a);
}
`;
