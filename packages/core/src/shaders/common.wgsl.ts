import { SLICE_ATLAS } from './slice-atlas.wgsl.js';

/**
 * Shared WGSL chunks: twins of common.glsl.ts, same arithmetic in the same order.
 * Expects `u` (scene uniforms) and textures `volume` (texture_3d) and `transferFunction`.
 */

/** PCG hash (Jarzynski & Olano 2020, "Hash Functions for GPU Rendering", JCGT 9(3), its pcg) and a uniform float stream. */
export const RNG = /* wgsl */ `
fn pcgHash(v: u32) -> u32 {
  let state = v * 747796405u + 2891336453u;
  let word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
  return (word >> 22u) ^ word;
}
fn rngInit(pixel: vec2i, iteration: u32, seed: u32) -> u32 {
  return pcgHash(u32(pixel.x) + pcgHash(u32(pixel.y) + pcgHash(iteration + pcgHash(seed))));
}
fn rngNext(state: ptr<function, u32>) -> f32 {
  *state = pcgHash(*state);
  return f32(*state >> 8u) * (1.0 / 16777216.0);
}
`;

/** Ray-box slab intersection (Kay & Kajiya 1986); returns (tNear, tFar), empty when tNear >= tFar. */
export const RAY = /* wgsl */ `
fn safeInverse(d: vec3f) -> vec3f {
  let s = vec3f(select(1.0, -1.0, d.x < 0.0), select(1.0, -1.0, d.y < 0.0), select(1.0, -1.0, d.z < 0.0));
  let m = max(abs(d), vec3f(1e-20));
  return s / m;
}
fn intersectBox(origin: vec3f, dir: vec3f, boxMin: vec3f, boxMax: vec3f) -> vec2f {
  let inv = safeInverse(dir);
  let t0 = (boxMin - origin) * inv;
  let t1 = (boxMax - origin) * inv;
  let tmin = min(t0, t1);
  let tmax = max(t0, t1);
  let tNear = max(max(tmin.x, tmin.y), max(tmin.z, 0.0));
  let tFar = min(min(tmax.x, tmax.y), tmax.z);
  return vec2f(tNear, tFar);
}
fn cameraRayDirection(film: vec2f) -> vec3f {
  let sx = (2.0 * film.x - 1.0) * u.tanHalfFovy * u.aspect;
  let sy = (1.0 - 2.0 * film.y) * u.tanHalfFovy;
  return normalize(u.cameraForward + u.cameraRight * sx + u.cameraUp * sy);
}
fn jitteredCameraRay(pixel: vec2i, size: vec2i, rng: ptr<function, u32>) -> vec3f {
  let jx = rngNext(rng);
  let jy = rngNext(rng);
  let film = vec2f((f32(pixel.x) + jx) / f32(size.x), (f32(pixel.y) + jy) / f32(size.y));
  return cameraRayDirection(film);
}
fn centreCameraRay(pixel: vec2i, size: vec2i) -> vec3f {
  return cameraRayDirection((vec2f(pixel) + 0.5) / vec2f(size));
}
`;

/** Clipping: twin of common.glsl.ts CLIP (see there), only in variants compiled with CLIP. */
export const CLIP = /* wgsl */ `
// (tNear, tFar) cut to the kept region: the box by its slabs (Kay & Kajiya 1986), then each plane as one
// parametric half-space clip (Cyrus & Beck 1978); empty when tNear >= tFar.
fn clipRayInterval(origin: vec3f, dir: vec3f, tNear: f32, tFar: f32) -> vec2f {
  let b = intersectBox(origin, dir, u.clipBoxMin, u.clipBoxMax);
  var t0 = max(tNear, b.x);
  var t1 = min(tFar, b.y);
  for (var i = 0; i < u.clipPlaneCount; i++) {
    let pl = u.clipPlanes[i];
    let denom = dot(pl.xyz, dir);
    let num = pl.w - dot(pl.xyz, origin);
    if (denom > 0.0) {
      t1 = min(t1, num / denom);
    } else if (denom < 0.0) {
      t0 = max(t0, num / denom);
    } else if (num < 0.0) {
      t1 = -1.0; // parallel to the plane and on its removed side
    }
  }
  return vec2f(t0, t1);
}
// The ray's interval in the volume box cut to the kept region: where the medium is (vacuum elsewhere).
fn keptInterval(origin: vec3f, dir: vec3f) -> vec2f {
  let t = intersectBox(origin, dir, u.boxMin, u.boxMax);
  return clipRayInterval(origin, dir, t.x, t.y);
}
// Whether the point is cut away: outside the crop box or beyond a plane.
fn isClipped(p: vec3f) -> bool {
  if (any(p < u.clipBoxMin) || any(p > u.clipBoxMax)) { return true; }
  for (var i = 0; i < u.clipPlaneCount; i++) {
    if (dot(u.clipPlanes[i].xyz, p) > u.clipPlanes[i].w) { return true; }
  }
  return false;
}
`;

/** Twin of DEPTH_LIMIT in common.glsl.ts (the surface behind a pixel; see there). */
export const DEPTH_LIMIT = /* wgsl */ `
fn depthLimitAlong(pixel: vec2i, dir: vec3f) -> f32 {
  let size = vptTargetSize();
  let d = textureLoad(meshDepth, vec2i(pixel.x, size.y - 1 - pixel.y), 0).r;
  let forward = u.depthA / (2.0 * d - 1.0 + u.depthB);
  return forward / dot(dir, u.cameraForward);
}
`;

/** Volume sampling: twins of common.glsl.ts (see there): value mapping, exact and hardware filters. */
export const LERP = /* wgsl */ `
fn lerp1(a: f32, b: f32, t: f32) -> f32 { return a + (b - a) * t; }
fn lerp4(a: vec4f, b: vec4f, t: f32) -> vec4f { return a + (b - a) * t; }
fn volumeValue(texel: f32) -> f32 { return clamp(texel * u.valueScale + u.valueOffset, 0.0, 1.0); }
`;
export const EXACT_FILTER = /* wgsl */ `
fn sampleVolumeTexel(p: vec3f) -> f32 {
  let tc = (p - u.boxMin) / (u.boxMax - u.boxMin);
  let dims = u.volumeDims.xyz;
  let g = tc * vec3f(dims) - 0.5;
  let g0 = floor(g);
  let f = g - g0;
  let i0 = clamp(vec3i(g0), vec3i(0), dims - 1);
  let i1 = clamp(vec3i(g0) + 1, vec3i(0), dims - 1);
  let c000 = textureLoad(volume, vec3i(i0.x, i0.y, i0.z), 0).r;
  let c100 = textureLoad(volume, vec3i(i1.x, i0.y, i0.z), 0).r;
  let c010 = textureLoad(volume, vec3i(i0.x, i1.y, i0.z), 0).r;
  let c110 = textureLoad(volume, vec3i(i1.x, i1.y, i0.z), 0).r;
  let c001 = textureLoad(volume, vec3i(i0.x, i0.y, i1.z), 0).r;
  let c101 = textureLoad(volume, vec3i(i1.x, i0.y, i1.z), 0).r;
  let c011 = textureLoad(volume, vec3i(i0.x, i1.y, i1.z), 0).r;
  let c111 = textureLoad(volume, vec3i(i1.x, i1.y, i1.z), 0).r;
  let c00 = lerp1(c000, c100, f.x);
  let c10 = lerp1(c010, c110, f.x);
  let c01 = lerp1(c001, c101, f.x);
  let c11 = lerp1(c011, c111, f.x);
  return lerp1(lerp1(c00, c10, f.y), lerp1(c01, c11, f.y), f.z);
}
`;
export const HARDWARE_FILTER = /* wgsl */ `
fn sampleVolumeTexel(p: vec3f) -> f32 {
  return textureSampleLevel(volume, vptLinearSampler, (p - u.boxMin) / (u.boxMax - u.boxMin), 0.0).r;
}
`;
/** The bricked volume: twins of BRICK_LOOKUP and the bricked filters of common.glsl.ts (see there). */
export const BRICK_LOOKUP = /* wgsl */ `
struct VptBrick { x: vec3f, first: vec3i, shift: vec3i, dims: vec3i, size: i32, constant: f32, isConstant: bool };
// Beyer, Hadwiger, Pfister 2015, CGF 34(8), §5: page-table virtual texturing with one-voxel aprons.
fn brickAt(p: vec3f) -> VptBrick {
  var r: VptBrick;
  let B = f32(u.volumeDims.w);
  r.size = u.volumeDims.w;
  let x0 = (p - u.boxMin) / (u.boxMax - u.boxMin) * vec3f(u.volumeDims.xyz);
  let b0 = clamp(vec3i(floor(x0 / B)), vec3i(0), vec3i(textureDimensions(pageTable)) - 1);
  let e = textureLoad(pageTable, b0, 0);
  r.isConstant = e.w < 0.0;
  r.constant = e.x;
  let level = max(i32(e.w), 0);
  r.dims = u.volumeDims.xyz;
  r.first = b0 * r.size - 1;
  r.x = x0;
  if (level > 0) {
    let s = textureLoad(brickLevels, vec2i(0, level), 0).xyz;
    let o = textureLoad(brickLevels, vec2i(1, level), 0).xyz;
    r.dims = vec3i(textureLoad(brickLevels, vec2i(2, level), 0).xyz);
    let bricks = (r.dims + r.size - 1) / r.size;
    let bl = clamp(vec3i(floor(((vec3f(b0) + 0.5) * B * s + o) / B)), vec3i(0), bricks - 1);
    r.first = bl * r.size - 1;
    r.x = x0 * s + o;
  }
  r.shift = vec3i(e.xyz) - r.first;
  return r;
}
`;
export const BRICKED_EXACT_FILTER = /* wgsl */ `
fn brickTexels(b: VptBrick, i: vec3i) -> vec4f {
  let c = clamp(clamp(i, vec3i(0), b.dims - 1), b.first, b.first + b.size + 1);
  return textureLoad(volume, c + b.shift, 0);
}
fn sampleBrickTexels(p: vec3f) -> vec4f {
  let b = brickAt(p);
  if (b.isConstant) { return vec4f(b.constant); }
  let g = b.x - 0.5;
  let g0 = floor(g);
  let f = g - g0;
  let i0 = vec3i(g0);
  let i1 = vec3i(g0) + 1;
  let c000 = brickTexels(b, vec3i(i0.x, i0.y, i0.z));
  let c100 = brickTexels(b, vec3i(i1.x, i0.y, i0.z));
  let c010 = brickTexels(b, vec3i(i0.x, i1.y, i0.z));
  let c110 = brickTexels(b, vec3i(i1.x, i1.y, i0.z));
  let c001 = brickTexels(b, vec3i(i0.x, i0.y, i1.z));
  let c101 = brickTexels(b, vec3i(i1.x, i0.y, i1.z));
  let c011 = brickTexels(b, vec3i(i0.x, i1.y, i1.z));
  let c111 = brickTexels(b, vec3i(i1.x, i1.y, i1.z));
  let c00 = lerp4(c000, c100, f.x);
  let c10 = lerp4(c010, c110, f.x);
  let c01 = lerp4(c001, c101, f.x);
  let c11 = lerp4(c011, c111, f.x);
  return lerp4(lerp4(c00, c10, f.y), lerp4(c01, c11, f.y), f.z);
}
`;
export const BRICKED_HARDWARE_FILTER = /* wgsl */ `
fn sampleBrickTexels(p: vec3f) -> vec4f {
  let b = brickAt(p);
  if (b.isConstant) { return vec4f(b.constant); }
  let lo = vec3f(b.first) + 0.5;
  let x = clamp(b.x, lo, lo + f32(b.size + 1));
  return textureSampleLevel(volume, vptLinearSampler, (x + vec3f(b.shift)) / vec3f(textureDimensions(volume)), 0.0);
}
`;
export const BRICKED_SCALAR = /* wgsl */ `
fn sampleVolumeTexel(p: vec3f) -> f32 { return sampleBrickTexels(p).x; }
`;
export const BRICKED_CHANNELS = /* wgsl */ `
fn sampleChannelTexels(p: vec3f) -> vec4f { return sampleBrickTexels(p); }
`;
/** A channel scene: twins of the CHANNEL_* chunks of common.glsl.ts (see there). */
export const CHANNEL_EXACT_FILTER = /* wgsl */ `
fn sampleChannelTexels(p: vec3f) -> vec4f {
  let tc = (p - u.boxMin) / (u.boxMax - u.boxMin);
  let dims = u.volumeDims.xyz;
  let g = tc * vec3f(dims) - 0.5;
  let g0 = floor(g);
  let f = g - g0;
  let i0 = clamp(vec3i(g0), vec3i(0), dims - 1);
  let i1 = clamp(vec3i(g0) + 1, vec3i(0), dims - 1);
  let c000 = textureLoad(volume, vec3i(i0.x, i0.y, i0.z), 0);
  let c100 = textureLoad(volume, vec3i(i1.x, i0.y, i0.z), 0);
  let c010 = textureLoad(volume, vec3i(i0.x, i1.y, i0.z), 0);
  let c110 = textureLoad(volume, vec3i(i1.x, i1.y, i0.z), 0);
  let c001 = textureLoad(volume, vec3i(i0.x, i0.y, i1.z), 0);
  let c101 = textureLoad(volume, vec3i(i1.x, i0.y, i1.z), 0);
  let c011 = textureLoad(volume, vec3i(i0.x, i1.y, i1.z), 0);
  let c111 = textureLoad(volume, vec3i(i1.x, i1.y, i1.z), 0);
  let c00 = lerp4(c000, c100, f.x);
  let c10 = lerp4(c010, c110, f.x);
  let c01 = lerp4(c001, c101, f.x);
  let c11 = lerp4(c011, c111, f.x);
  return lerp4(lerp4(c00, c10, f.y), lerp4(c01, c11, f.y), f.z);
}
`;
export const CHANNEL_HARDWARE_FILTER = /* wgsl */ `
fn sampleChannelTexels(p: vec3f) -> vec4f {
  return textureSampleLevel(volume, vptLinearSampler, (p - u.boxMin) / (u.boxMax - u.boxMin), 0.0);
}
`;
export const CHANNEL_SAMPLE = /* wgsl */ `
fn sampleChannels(p: vec3f) -> vec4f {
  return clamp(sampleChannelTexels(p) * u.channelScale + u.channelOffset, vec4f(0.0), vec4f(1.0));
}
fn sampleVolumeTexel(p: vec3f) -> f32 { return sampleChannelTexels(p).x; }
`;
// Novák et al. 2018, CGF 37(2), Sec. 2: a mixture's sigma_t is the sum, its albedo the sigma-weighted mean.
export const CHANNEL_TRANSFER = /* wgsl */ `
fn channelLookup(value: f32, row: i32) -> vec4f {
  let x = clamp(value, 0.0, 1.0) * f32(u.tfSize - 1);
  let x0 = floor(x);
  let i0 = i32(x0);
  let i1 = min(i0 + 1, u.tfSize - 1);
  return lerp4(textureLoad(transferFunction, vec2i(i0, row), 0), textureLoad(transferFunction, vec2i(i1, row), 0), x - x0);
}
#if LABELS
fn imageTransferAt(p: vec3f) -> vec4f {
#else
fn transferAt(p: vec3f) -> vec4f {
#endif
  let v = sampleChannels(p);
  let t0 = channelLookup(v.x, 0);
  var sigma = t0.a;
#if CHANNELS >= 2
  let t1 = channelLookup(v.y, 1);
  sigma += t1.a;
#endif
#if CHANNELS >= 3
  let t2 = channelLookup(v.z, 2);
  sigma += t2.a;
#endif
#if CHANNELS >= 4
  let t3 = channelLookup(v.w, 3);
  sigma += t3.a;
#endif
  let even = 1.0 / f32(u.tfHeight);
  var rgb = select(even, t0.a / sigma, sigma > 0.0) * t0.rgb;
#if CHANNELS >= 2
  rgb += select(even, t1.a / sigma, sigma > 0.0) * t1.rgb;
#endif
#if CHANNELS >= 3
  rgb += select(even, t2.a / sigma, sigma > 0.0) * t2.rgb;
#endif
#if CHANNELS >= 4
  rgb += select(even, t3.a / sigma, sigma > 0.0) * t3.rgb;
#endif
  return vec4f(rgb, sigma);
}
`;
export const SAMPLE_AND_LOOKUP = /* wgsl */ `
fn sampleVolume(p: vec3f) -> f32 { return volumeValue(sampleVolumeTexel(p)); }
fn transferLookup(value: f32) -> vec4f {
  let x = clamp(value, 0.0, 1.0) * f32(u.tfSize - 1);
  let x0 = floor(x);
  let i0 = i32(x0);
  let i1 = min(i0 + 1, u.tfSize - 1);
  return lerp4(textureLoad(transferFunction, vec2i(i0, 0), 0), textureLoad(transferFunction, vec2i(i1, 0), 0), x - x0);
}
`;

/** transferAt for a 1D transfer function (see common.glsl.ts). */
export const TRANSFER_1D = /* wgsl */ `
#if LABELS
fn imageTransferAt(p: vec3f) -> vec4f {
#else
fn transferAt(p: vec3f) -> vec4f {
#endif
  return transferLookup(sampleVolume(p));
}
`;

/** Gradient magnitude from the slice atlas, trilinear, and normalized (twin of GLSL_GRADIENT). */
export const GRADIENT = /* wgsl */ `
fn gradientTexel(v: vec3i) -> f32 {
  return textureLoad(gradientMagnitude, atlasTexel(v, u.volumeDims.xyz, u.gradientAtlasColumns), 0).r;
}
fn sampleGradientMagnitude(p: vec3f) -> f32 {
  let tc = (p - u.boxMin) / (u.boxMax - u.boxMin);
  let dims = u.volumeDims.xyz;
  let g = tc * vec3f(dims) - 0.5;
  let g0 = floor(g);
  let f = g - g0;
  let i0 = clamp(vec3i(g0), vec3i(0), dims - 1);
  let i1 = clamp(vec3i(g0) + 1, vec3i(0), dims - 1);
  let c000 = gradientTexel(vec3i(i0.x, i0.y, i0.z));
  let c100 = gradientTexel(vec3i(i1.x, i0.y, i0.z));
  let c010 = gradientTexel(vec3i(i0.x, i1.y, i0.z));
  let c110 = gradientTexel(vec3i(i1.x, i1.y, i0.z));
  let c001 = gradientTexel(vec3i(i0.x, i0.y, i1.z));
  let c101 = gradientTexel(vec3i(i1.x, i0.y, i1.z));
  let c011 = gradientTexel(vec3i(i0.x, i1.y, i1.z));
  let c111 = gradientTexel(vec3i(i1.x, i1.y, i1.z));
  let c00 = lerp1(c000, c100, f.x);
  let c10 = lerp1(c010, c110, f.x);
  let c01 = lerp1(c001, c101, f.x);
  let c11 = lerp1(c011, c111, f.x);
  return lerp1(lerp1(c00, c10, f.y), lerp1(c01, c11, f.y), f.z);
}
fn normalizedGradientAt(p: vec3f) -> f32 {
  let gmax = select(textureLoad(gradientMax, vec2i(0, 0), 0).r, u.tfGradientMax, u.tfGradientMax > 0.0);
  return select(0.0, min(sampleGradientMagnitude(p) / gmax, 1.0), gmax > 0.0);
}
`;

/** transferAt for a 2D (value x normalized gradient magnitude) transfer function (Kniss, Kindlmann, Hansen 2002; twin of GLSL_TRANSFER_2D). */
export const TRANSFER_2D = /* wgsl */ `
fn transferLookup2D(value: f32, gradient: f32) -> vec4f {
  let x = clamp(value, 0.0, 1.0) * f32(u.tfSize - 1);
  let y = clamp(gradient, 0.0, 1.0) * f32(u.tfHeight - 1);
  let x0 = floor(x);
  let y0 = floor(y);
  let i0 = i32(x0);
  let i1 = min(i0 + 1, u.tfSize - 1);
  let j0 = i32(y0);
  let j1 = min(j0 + 1, u.tfHeight - 1);
  let a = lerp4(textureLoad(transferFunction, vec2i(i0, j0), 0), textureLoad(transferFunction, vec2i(i1, j0), 0), x - x0);
  let b = lerp4(textureLoad(transferFunction, vec2i(i0, j1), 0), textureLoad(transferFunction, vec2i(i1, j1), 0), x - x0);
  return lerp4(a, b, y - y0);
}
#if LABELS
fn imageTransferAt(p: vec3f) -> vec4f {
#else
fn transferAt(p: vec3f) -> vec4f {
#endif
  return transferLookup2D(sampleVolume(p), normalizedGradientAt(p));
}
`;

/** Twin of SLICE_PLANE in common.glsl.ts (a scene's slice plane as an opaque unlit surface; see there). */
export const SLICE_PLANE = /* wgsl */ `
fn slicePlaneHit(o: vec3f, d: vec3f) -> f32 {
  let denom = dot(d, u.slicePlaneNormal);
  let t = select(-1.0, (u.slicePlaneOffset - dot(o, u.slicePlaneNormal)) / denom, abs(denom) > 1e-12);
  let p = o + d * t;
  var hit = t > 0.0 && all(p >= u.boxMin) && all(p <= u.boxMax);
#if CLIP
  hit = hit && !isClipped(p);
#endif
  return select(-1.0, t, hit);
}
fn slicePlaneTexel(p: vec3f) -> f32 {
#if SLICE_PLANE_NEAREST
  let dims = u.volumeDims.xyz;
  let tc = (p - u.boxMin) / (u.boxMax - u.boxMin);
  let i = clamp(vec3i(floor(tc * vec3f(dims))), vec3i(0), dims - 1);
#if BRICKED
  return sampleVolumeTexel(u.boxMin + (vec3f(i) + 0.5) / vec3f(dims) * (u.boxMax - u.boxMin));
#else
  return textureLoad(volume, i, 0).r;
#endif
#else
  return sampleVolumeTexel(p);
#endif
}
#if LABELS
fn slicePlaneImageColor(p: vec3f) -> vec3f {
#else
fn slicePlaneColor(p: vec3f) -> vec3f {
#endif
  let n = slicePlaneTexel(p) * u.valueScale + u.valueOffset;
  let w = clamp(n * u.slicePlaneWindow.x + u.slicePlaneWindow.y, 0.0, 1.0);
#if SLICE_PLANE_TABLE
  let count = i32(textureDimensions(slicePlaneColormap).x);
  let x = w * f32(count - 1);
  let x0 = floor(x);
  let i0 = i32(x0);
  let i1 = min(i0 + 1, count - 1);
  return lerp4(textureLoad(slicePlaneColormap, vec2i(i0, 0), 0), textureLoad(slicePlaneColormap, vec2i(i1, 0), 0), x - x0).rgb;
#else
  return vec3f(w);
#endif
}
`;

/** Where commonChunks puts the label chunk (a line the preprocessor cuts when LABELS is off). */
export const LABELS_PLACEHOLDER = '// VPT_LABELS_CHUNK';

/**
 * The shared chunks of a generate pass, variants marked by `#if` lines that commonChunks()
 * (common.ts) resolves with the core preprocessor: the gradient helpers only when the
 * gradient textures are bound, and the transferAt() of a 1D or 2D transfer function.
 */
export const GENERATE_CHUNKS = [
  RNG,
  RAY,
  '#if CLIP',
  CLIP,
  '#endif',
  SLICE_ATLAS,
  LERP,
  '#if CHANNELS',
  '#if BRICKED',
  BRICK_LOOKUP,
  '#if HARDWARE_FILTER',
  BRICKED_HARDWARE_FILTER,
  '#else',
  BRICKED_EXACT_FILTER,
  '#endif',
  BRICKED_CHANNELS,
  '#elif HARDWARE_FILTER',
  CHANNEL_HARDWARE_FILTER,
  '#else',
  CHANNEL_EXACT_FILTER,
  '#endif',
  CHANNEL_SAMPLE,
  '#elif BRICKED',
  BRICK_LOOKUP,
  '#if HARDWARE_FILTER',
  BRICKED_HARDWARE_FILTER,
  '#else',
  BRICKED_EXACT_FILTER,
  '#endif',
  BRICKED_SCALAR,
  '#elif HARDWARE_FILTER',
  HARDWARE_FILTER,
  '#else',
  EXACT_FILTER,
  '#endif',
  SAMPLE_AND_LOOKUP,
  '#if GRADIENT',
  GRADIENT,
  '#endif',
  '#if CHANNELS',
  CHANNEL_TRANSFER,
  '#elif TF_2D',
  TRANSFER_2D,
  '#else',
  TRANSFER_1D,
  '#endif',
  '#if SLICE_PLANE',
  SLICE_PLANE,
  '#endif',
  '#if LABELS',
  // The label chunk (shaders/labels.*.ts) is put here by commonChunks when labels are enabled (scene/label-support.ts).
  LABELS_PLACEHOLDER,
  '#endif',
].join('\n');

/** The chunks of the integrate and render passes: texture-free RNG and rays. */
export const PASS_CHUNKS = RNG + RAY;
