/** Twin of blue-noise.glsl.ts (the first dimensions of a path; see there and blue-noise.ts). */
export const SAMPLE_DIMS = /* wgsl */ `
// The pixel whose dimensions rngDim draws; sampleDimsInit(pixel) first, in fs_main.
var<private> vptDimPixel: vec2i;
fn sampleDimsInit(pixel: vec2i) {
  vptDimPixel = pixel;
}
#if BLUE_NOISE
// The blue-noise rngDim: put here from the lazy blue-noise module (withBlueNoise, blue-noise.ts).
// VPT_BLUE_NOISE_CHUNK
#else
fn rngDim(state: ptr<function, u32>, dim: i32) -> f32 {
  return rngNext(state);
}
#endif
// jitteredCameraRay (common) with the jitter from dimensions 0 and 1.
fn jitteredCameraRayDims(pixel: vec2i, size: vec2i, rng: ptr<function, u32>) -> vec3f {
  let jx = rngDim(rng, 0);
  let jy = rngDim(rng, 1);
  let film = vec2f((f32(pixel.x) + jx) / f32(size.x), (f32(pixel.y) + jy) / f32(size.y));
  return cameraRayDirection(film);
}
`;
