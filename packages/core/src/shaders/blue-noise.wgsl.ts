/** Twin of blue-noise.glsl.ts (the first dimensions of a path; see there and blue-noise.ts). */
export const SAMPLE_DIMS = /* wgsl */ `
// The pixel whose dimensions rngDim draws; sampleDimsInit(pixel) first, in fs_main.
var<private> vptDimPixel: vec2i;
fn sampleDimsInit(pixel: vec2i) {
  vptDimPixel = pixel;
}
#if BLUE_NOISE
// Kronecker sequence (R2 jitter, Roberts 2018; golden ratio; frac(sqrt 2, sqrt 3), Richtmyer) Cranley-Patterson rotated per pixel by a
// void-and-cluster mask (Georgiev & Fajardo 2016), x = frac(m(p + o_d) + i*alpha_d + U_d) in 0.32 fixed point.
fn sampleDimAlpha(dim: i32) -> u32 {
  if (dim == 2) { return 2654435769u; }
  if (dim == 3) { return 1779033704u; }
  if (dim == 4) { return 3144134278u; }
  return select(2447445413u, 3242174889u, dim == 0);
}
fn blueNoiseDim(pixel: vec2i, dim: i32) -> f32 {
  let h = pcgHash(u.seed + pcgHash(u32(dim) + 2654435769u));
  let q = (pixel + vec2i(i32(h & 63u), i32((h >> 6u) & 63u))) & vec2i(63);
  let r = u32(textureLoad(blueNoise, q, 0).r);
  let x = (r << 20u) + (1u << 19u) + (u.iteration + u.sampleBase) * sampleDimAlpha(dim) + pcgHash(h);
  return f32(x >> 8u) * (1.0 / 16777216.0);
}
// Dimension dim >= 0 from blue noise; dim = -1: the PCG stream's next draw.
fn rngDim(state: ptr<function, u32>, dim: i32) -> f32 {
  if (dim < 0) { return rngNext(state); }
  return blueNoiseDim(vptDimPixel, dim);
}
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
