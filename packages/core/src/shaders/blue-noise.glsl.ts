/**
 * The first dimensions of a path (blue-noise.ts says which and why), GLSL; twin in
 * blue-noise.wgsl.ts. Included by the renderer kernels, whose features() set BLUE_NOISE for
 * `sampler: 'blue-noise'` (the `blueNoise` rank mask is then bound); without it rngDim is the
 * PCG stream's next draw, so a 'pcg' variant consumes exactly the numbers it did before. The
 * BLUE_NOISE body (blue-noise-dims.glsl.ts) lives in the lazily loaded blue-noise module, so the
 * viewer's entry does not carry it; RenderContext substitutes it for the placeholder line.
 */
export const SAMPLE_DIMS = /* glsl */ `
// The pixel whose dimensions rngDim draws; sampleDimsInit(pixel) first, in main.
ivec2 vptDimPixel;
void sampleDimsInit(ivec2 pixel) {
  vptDimPixel = pixel;
}
#if BLUE_NOISE
// The blue-noise rngDim: put here from the lazy blue-noise module (withBlueNoise, blue-noise.ts).
// VPT_BLUE_NOISE_CHUNK
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
