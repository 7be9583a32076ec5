/**
 * The BLUE_NOISE body of blue-noise.glsl.ts's SAMPLE_DIMS (blueNoiseDim and the blue-noise rngDim), in
 * the lazily loaded blue-noise module (blue-noise-mask.ts): RenderContext puts it where the
 * `// VPT_BLUE_NOISE_CHUNK` line is (withBlueNoise in blue-noise.ts), so a bundle carries it
 * only in that lazy chunk.
 */
export const BLUE_NOISE_DIMS = /* glsl */ `
// Kronecker sequence (R2 jitter, Roberts 2018; golden ratio; frac(sqrt 2, sqrt 3), Richtmyer) Cranley-Patterson rotated per pixel by a
// void-and-cluster mask (Georgiev & Fajardo 2016), x = frac(m(p + o_d) + i*alpha_d + U_d) in 0.32 fixed point.
uint sampleDimAlpha(int dim) {
  if (dim == 2) return 2654435769u;
  if (dim == 3) return 1779033704u;
  if (dim == 4) return 3144134278u;
  return dim == 0 ? 3242174889u : 2447445413u;
}
float blueNoiseDim(ivec2 pixel, int dim) {
  uint h = pcgHash(u.seed + pcgHash(uint(dim) + 2654435769u));
  ivec2 q = (pixel + ivec2(int(h & 63u), int((h >> 6u) & 63u))) & 63;
  uint r = uint(texelFetch(blueNoise, q, 0).r);
  uint x = (r << 20u) + (1u << 19u) + u.iteration * sampleDimAlpha(dim) + pcgHash(h);
  return float(x >> 8u) * (1.0 / 16777216.0);
}
// Dimension dim >= 0 from blue noise; dim = -1: the PCG stream's next draw.
float rngDim(inout uint state, int dim) {
  if (dim < 0) return rngNext(state);
  return blueNoiseDim(vptDimPixel, dim);
}
`;
