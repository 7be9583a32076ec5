/**
 * The first dimensions of a path (blue-noise.ts says which and why), GLSL; twin in
 * blue-noise.wgsl.ts. Included by the renderer kernels, whose features() set BLUE_NOISE for
 * `sampler: 'blue-noise'` (the `blueNoise` rank mask is then bound); without it rngDim is the
 * PCG stream's next draw, so a 'pcg' variant consumes exactly the numbers it did before.
 */
export const SAMPLE_DIMS = /* glsl */ `
// The pixel whose dimensions rngDim draws; sampleDimsInit(pixel) first, in main.
ivec2 vptDimPixel;
void sampleDimsInit(ivec2 pixel) {
  vptDimPixel = pixel;
}
#if BLUE_NOISE
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
  uint x = (r << 20u) + (1u << 19u) + (u.iteration + u.sampleBase) * sampleDimAlpha(dim) + pcgHash(h);
  return float(x >> 8u) * (1.0 / 16777216.0);
}
// Dimension dim >= 0 from blue noise; dim = -1: the PCG stream's next draw.
float rngDim(inout uint state, int dim) {
  if (dim < 0) return rngNext(state);
  return blueNoiseDim(vptDimPixel, dim);
}
#else
float rngDim(inout uint state, int dim) {
  return rngNext(state);
}
#endif
// jitteredCameraRay (common) with the jitter from dimensions 0 and 1.
vec3 jitteredCameraRayDims(ivec2 pixel, ivec2 size, inout uint rng) {
  float jx = rngDim(rng, 0);
  float jy = rngDim(rng, 1);
  vec2 film = vec2((float(pixel.x) + jx) / float(size.x), (float(pixel.y) + jy) / float(size.y));
  return cameraRayDirection(film);
}
`;
