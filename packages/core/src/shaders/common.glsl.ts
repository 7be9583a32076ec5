/**
 * Shared GLSL ES 3.0 chunks. Every function here has a WGSL twin in common.wgsl.ts
 * with the same arithmetic in the same order, so both backends agree bit for bit on
 * SwiftShader. Expects the scene uniform block as `u` (scene-uniforms.ts) and, for
 * the volume/TF helpers, textures named `volume` (sampler3D) and `transferFunction`.
 */
import { SLICE_ATLAS } from './slice-atlas.glsl.js';

/** PCG hash (Jarzynski & Olano 2020, "Hash Functions for GPU Rendering", JCGT 9(3), its pcg) and a uniform float stream. */
export const RNG = /* glsl */ `
uint pcgHash(uint v) {
  uint state = v * 747796405u + 2891336453u;
  uint word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
  return (word >> 22u) ^ word;
}
// Seeded by (pixel, iteration, user seed): reproducible runs, decorrelated pixels.
uint rngInit(ivec2 pixel, uint iteration, uint seed) {
  return pcgHash(uint(pixel.x) + pcgHash(uint(pixel.y) + pcgHash(iteration + pcgHash(seed))));
}
// 24 high-quality bits -> [0, 1), exactly representable in float32.
float rngNext(inout uint state) {
  state = pcgHash(state);
  return float(state >> 8u) * (1.0 / 16777216.0);
}
`;

/** Ray-box slab intersection (Kay & Kajiya 1986); returns (tNear, tFar), empty when tNear >= tFar. */
export const RAY = /* glsl */ `
vec3 safeInverse(vec3 d) {
  // Avoid 0 * inf = NaN for axis-parallel rays: a tiny signed component is as good as zero.
  vec3 s = vec3(d.x < 0.0 ? -1.0 : 1.0, d.y < 0.0 ? -1.0 : 1.0, d.z < 0.0 ? -1.0 : 1.0);
  vec3 m = max(abs(d), vec3(1e-20));
  return s / m;
}
vec2 intersectBox(vec3 origin, vec3 dir, vec3 boxMin, vec3 boxMax) {
  vec3 inv = safeInverse(dir);
  vec3 t0 = (boxMin - origin) * inv;
  vec3 t1 = (boxMax - origin) * inv;
  vec3 tmin = min(t0, t1);
  vec3 tmax = max(t0, t1);
  float tNear = max(max(tmin.x, tmin.y), max(tmin.z, 0.0));
  float tFar = min(min(tmax.x, tmax.y), tmax.z);
  return vec2(tNear, tFar);
}
// Pinhole camera (docs/design.md): film point (x, y) in [0,1]^2, y down.
vec3 cameraRayDirection(vec2 film) {
  float sx = (2.0 * film.x - 1.0) * u.tanHalfFovy * u.aspect;
  float sy = (1.0 - 2.0 * film.y) * u.tanHalfFovy;
  return normalize(u.cameraForward + u.cameraRight * sx + u.cameraUp * sy);
}
// Box-filtered pixel: a uniformly jittered point inside the pixel.
vec3 jitteredCameraRay(ivec2 pixel, ivec2 size, inout uint rng) {
  float jx = rngNext(rng);
  float jy = rngNext(rng);
  vec2 film = vec2((float(pixel.x) + jx) / float(size.x), (float(pixel.y) + jy) / float(size.y));
  return cameraRayDirection(film);
}
// The ray through the pixel's centre (MIP: a maximum is not a mean, so it is not box-filtered).
vec3 centreCameraRay(ivec2 pixel, ivec2 size) {
  return cameraRayDirection((vec2(pixel) + 0.5) / vec2(size));
}
`;

/**
 * Clipping (scene/clip.ts), only in variants compiled with CLIP: the kept region is the crop
 * box and every half-space dot(n, p) <= d (unit n, uniforms u.clipPlanes / u.clipBoxMin /
 * u.clipBoxMax, CLIP_UNIFORM_FIELDS). It is convex, so a ray meets it in one interval.
 */
export const CLIP = /* glsl */ `
// (tNear, tFar) cut to the kept region: the box by its slabs (Kay & Kajiya 1986), then each plane as one
// parametric half-space clip (Cyrus & Beck 1978); empty when tNear >= tFar.
vec2 clipRayInterval(vec3 origin, vec3 dir, float tNear, float tFar) {
  vec2 b = intersectBox(origin, dir, u.clipBoxMin, u.clipBoxMax);
  float t0 = max(tNear, b.x);
  float t1 = min(tFar, b.y);
  for (int i = 0; i < u.clipPlaneCount; i++) {
    vec4 pl = u.clipPlanes[i];
    float denom = dot(pl.xyz, dir);
    float num = pl.w - dot(pl.xyz, origin);
    if (denom > 0.0) {
      t1 = min(t1, num / denom);
    } else if (denom < 0.0) {
      t0 = max(t0, num / denom);
    } else if (num < 0.0) {
      t1 = -1.0; // parallel to the plane and on its removed side
    }
  }
  return vec2(t0, t1);
}
// The ray's interval in the volume box cut to the kept region: where the medium is (vacuum elsewhere).
vec2 keptInterval(vec3 origin, vec3 dir) {
  vec2 t = intersectBox(origin, dir, u.boxMin, u.boxMax);
  return clipRayInterval(origin, dir, t.x, t.y);
}
// Whether the point is cut away: outside the crop box or beyond a plane.
bool isClipped(vec3 p) {
  if (any(lessThan(p, u.clipBoxMin)) || any(greaterThan(p, u.clipBoxMax))) { return true; }
  for (int i = 0; i < u.clipPlaneCount; i++) {
    if (dot(u.clipPlanes[i].xyz, p) > u.clipPlanes[i].w) { return true; }
  }
  return false;
}
`;

/**
 * The opaque surface behind a pixel (RenderContext.setDepthLimit, shared WebGL 2 contexts):
 * the distance along the camera ray dir at which it reaches the surface's depth, read from
 * \`meshDepth\` (window depth d, GL rows bottom-up) as forward distance a / (2d − 1 + b).
 * Renderers include it under \`#if VPT_DEPTH_LIMIT\` (the uniforms depthA, depthB exist then).
 */
export const DEPTH_LIMIT = /* glsl */ `
float depthLimitAlong(ivec2 pixel, vec3 dir) {
  ivec2 size = vptTargetSize();
  float d = texelFetch(meshDepth, ivec2(pixel.x, size.y - 1 - pixel.y), 0).r;
  float forward = u.depthA / (2.0 * d - 1.0 + u.depthB);
  return forward / dot(dir, u.cameraForward);
}
`;

/**
 * The volume value at a world point: cell-centred trilinear interpolation with clamp-to-edge
 * (GL LINEAR + CLAMP_TO_EDGE) of the stored texels, then the value mapping of
 * gpu/volume-format.ts, v = clamp(texel · u.valueScale + u.valueOffset, 0, 1) (value range,
 * inversion and the format's decoding in one affine map; it commutes with the filter).
 * `sampleVolumeTexel(p)` is the filtered texel: exact (8 texelFetches and lerps in full
 * float, EXACT_FILTER) or one hardware-filtered fetch (HARDWARE_FILTER).
 */
export const LERP = /* glsl */ `
float lerp1(float a, float b, float t) { return a + (b - a) * t; }
vec4 lerp4(vec4 a, vec4 b, float t) { return a + (b - a) * t; }
float volumeValue(float texel) { return clamp(texel * u.valueScale + u.valueOffset, 0.0, 1.0); }
`;
export const EXACT_FILTER = /* glsl */ `
float sampleVolumeTexel(vec3 p) {
  vec3 tc = (p - u.boxMin) / (u.boxMax - u.boxMin);
  ivec3 dims = u.volumeDims.xyz;
  vec3 g = tc * vec3(dims) - 0.5;
  vec3 g0 = floor(g);
  vec3 f = g - g0;
  ivec3 i0 = clamp(ivec3(g0), ivec3(0), dims - 1);
  ivec3 i1 = clamp(ivec3(g0) + 1, ivec3(0), dims - 1);
  float c000 = texelFetch(volume, ivec3(i0.x, i0.y, i0.z), 0).r;
  float c100 = texelFetch(volume, ivec3(i1.x, i0.y, i0.z), 0).r;
  float c010 = texelFetch(volume, ivec3(i0.x, i1.y, i0.z), 0).r;
  float c110 = texelFetch(volume, ivec3(i1.x, i1.y, i0.z), 0).r;
  float c001 = texelFetch(volume, ivec3(i0.x, i0.y, i1.z), 0).r;
  float c101 = texelFetch(volume, ivec3(i1.x, i0.y, i1.z), 0).r;
  float c011 = texelFetch(volume, ivec3(i0.x, i1.y, i1.z), 0).r;
  float c111 = texelFetch(volume, ivec3(i1.x, i1.y, i1.z), 0).r;
  float c00 = lerp1(c000, c100, f.x);
  float c10 = lerp1(c010, c110, f.x);
  float c01 = lerp1(c001, c101, f.x);
  float c11 = lerp1(c011, c111, f.x);
  return lerp1(lerp1(c00, c10, f.y), lerp1(c01, c11, f.y), f.z);
}
`;
// The texture unit's trilinear filter: texel centres at (i + ½)/n in normalized coordinates,
// the same convention as the exact filter; the texture is LINEAR + CLAMP_TO_EDGE.
export const HARDWARE_FILTER = /* glsl */ `
float sampleVolumeTexel(vec3 p) {
  return texture(volume, (p - u.boxMin) / (u.boxMax - u.boxMin)).r;
}
`;
/**
 * The bricked volume (bricking/): `volume` is the brick atlas, `pageTable` (3D, one RGBA float
 * per level-0 brick) says where the brick holding a point is served from — (atlas origin of
 * its slot, level) or (texel value, 0, 0, −1) for a constant brick — and `brickLevels` (3 × L)
 * holds per level (scale.xyz, brick size), (offset.xyz, 0) and (dims.xyz, brick size), the map
 * x_l = x0 · scale + offset from level-0 voxel coordinates. Virtual texturing of volumes with a
 * page table (Beyer, Hadwiger, Pfister 2015, "State-of-the-Art in GPU-Based Large-Scale
 * Volume Visualization", CGF 34(8), §5): one-voxel aprons make trilinear filtering inside a
 * slot equal the unbricked filter, so a fully resident level 0 gives the unbricked values.
 */
export const BRICK_LOOKUP = /* glsl */ `
struct VptBrick { vec3 x; ivec3 first; ivec3 shift; ivec3 dims; int size; float constant; bool isConstant; };
// x0: the point in level-0 voxel coordinates; x: in the serving level's voxel coordinates; first: that level's voxel in slot texel 0;
// shift: atlas texel = level voxel + shift.
VptBrick brickAt(vec3 p) {
  VptBrick r;
  // u.volumeDims: level 0's dims and the brick size (RenderContext sets them for a bricked volume).
  float B = float(u.volumeDims.w);
  r.size = u.volumeDims.w;
  vec3 x0 = (p - u.boxMin) / (u.boxMax - u.boxMin) * vec3(u.volumeDims.xyz);
  ivec3 b0 = clamp(ivec3(floor(x0 / B)), ivec3(0), textureSize(pageTable, 0) - 1);
  vec4 e = texelFetch(pageTable, b0, 0);
  r.isConstant = e.w < 0.0;
  r.constant = e.x;
  int level = max(int(e.w), 0);
  r.dims = u.volumeDims.xyz;
  r.first = b0 * r.size - 1;
  r.x = x0;
  if (level > 0) {
    // A coarser level serves this brick: its voxel coordinates and the brick holding b0's centre.
    vec3 s = texelFetch(brickLevels, ivec2(0, level), 0).xyz;
    vec3 o = texelFetch(brickLevels, ivec2(1, level), 0).xyz;
    r.dims = ivec3(texelFetch(brickLevels, ivec2(2, level), 0).xyz);
    ivec3 bricks = (r.dims + r.size - 1) / r.size;
    ivec3 bl = clamp(ivec3(floor(((vec3(b0) + 0.5) * B * s + o) / B)), ivec3(0), bricks - 1);
    r.first = bl * r.size - 1;
    r.x = x0 * s + o;
  }
  r.shift = ivec3(e.xyz) - r.first;
  return r;
}
`;
// The bricked filters read vec4 texels: a channel scene's drawn channels are the atlas's
// components (BRICKED_CHANNELS), a scalar volume its .x (BRICKED_SCALAR); the same loads,
// weights and arithmetic per component.
export const BRICKED_EXACT_FILTER = /* glsl */ `
vec4 brickTexels(VptBrick b, ivec3 i) {
  ivec3 c = clamp(clamp(i, ivec3(0), b.dims - 1), b.first, b.first + b.size + 1);
  return texelFetch(volume, c + b.shift, 0);
}
vec4 sampleBrickTexels(vec3 p) {
  VptBrick b = brickAt(p);
  if (b.isConstant) return vec4(b.constant);
  vec3 g = b.x - 0.5;
  vec3 g0 = floor(g);
  vec3 f = g - g0;
  ivec3 i0 = ivec3(g0);
  ivec3 i1 = ivec3(g0) + 1;
  vec4 c000 = brickTexels(b, ivec3(i0.x, i0.y, i0.z));
  vec4 c100 = brickTexels(b, ivec3(i1.x, i0.y, i0.z));
  vec4 c010 = brickTexels(b, ivec3(i0.x, i1.y, i0.z));
  vec4 c110 = brickTexels(b, ivec3(i1.x, i1.y, i0.z));
  vec4 c001 = brickTexels(b, ivec3(i0.x, i0.y, i1.z));
  vec4 c101 = brickTexels(b, ivec3(i1.x, i0.y, i1.z));
  vec4 c011 = brickTexels(b, ivec3(i0.x, i1.y, i1.z));
  vec4 c111 = brickTexels(b, ivec3(i1.x, i1.y, i1.z));
  vec4 c00 = lerp4(c000, c100, f.x);
  vec4 c10 = lerp4(c010, c110, f.x);
  vec4 c01 = lerp4(c001, c101, f.x);
  vec4 c11 = lerp4(c011, c111, f.x);
  return lerp4(lerp4(c00, c10, f.y), lerp4(c01, c11, f.y), f.z);
}
`;
// One filtered fetch inside the slot: the coordinate is kept between the slot's first and last
// texel centres, so the filter never blends a neighbouring slot.
export const BRICKED_HARDWARE_FILTER = /* glsl */ `
vec4 sampleBrickTexels(vec3 p) {
  VptBrick b = brickAt(p);
  if (b.isConstant) return vec4(b.constant);
  vec3 lo = vec3(b.first) + 0.5;
  vec3 x = clamp(b.x, lo, lo + float(b.size + 1));
  return texture(volume, (x + vec3(b.shift)) / vec3(textureSize(volume, 0)));
}
`;
export const BRICKED_SCALAR = /* glsl */ `
float sampleVolumeTexel(vec3 p) { return sampleBrickTexels(p).x; }
`;
// A constant brick holds one value in every component (the page entry has room for one).
export const BRICKED_CHANNELS = /* glsl */ `
vec4 sampleChannelTexels(vec3 p) { return sampleBrickTexels(p); }
`;
/**
 * A channel scene (scene/channels.ts; only in variants compiled with CHANNELS = the number of
 * drawn channels): the volume texture holds the drawn channels as components (unused ones
 * masked by a zero scale), `sampleChannels(p)` is each channel's value, mapped by its own
 * u.channelScale / u.channelOffset, and the TF texture holds channel k's 1D transfer function
 * in row k. `sampleVolume` / `sampleVolumeTexel` read the first drawn channel.
 */
export const CHANNEL_EXACT_FILTER = /* glsl */ `
vec4 sampleChannelTexels(vec3 p) {
  vec3 tc = (p - u.boxMin) / (u.boxMax - u.boxMin);
  ivec3 dims = u.volumeDims.xyz;
  vec3 g = tc * vec3(dims) - 0.5;
  vec3 g0 = floor(g);
  vec3 f = g - g0;
  ivec3 i0 = clamp(ivec3(g0), ivec3(0), dims - 1);
  ivec3 i1 = clamp(ivec3(g0) + 1, ivec3(0), dims - 1);
  vec4 c000 = texelFetch(volume, ivec3(i0.x, i0.y, i0.z), 0);
  vec4 c100 = texelFetch(volume, ivec3(i1.x, i0.y, i0.z), 0);
  vec4 c010 = texelFetch(volume, ivec3(i0.x, i1.y, i0.z), 0);
  vec4 c110 = texelFetch(volume, ivec3(i1.x, i1.y, i0.z), 0);
  vec4 c001 = texelFetch(volume, ivec3(i0.x, i0.y, i1.z), 0);
  vec4 c101 = texelFetch(volume, ivec3(i1.x, i0.y, i1.z), 0);
  vec4 c011 = texelFetch(volume, ivec3(i0.x, i1.y, i1.z), 0);
  vec4 c111 = texelFetch(volume, ivec3(i1.x, i1.y, i1.z), 0);
  vec4 c00 = lerp4(c000, c100, f.x);
  vec4 c10 = lerp4(c010, c110, f.x);
  vec4 c01 = lerp4(c001, c101, f.x);
  vec4 c11 = lerp4(c011, c111, f.x);
  return lerp4(lerp4(c00, c10, f.y), lerp4(c01, c11, f.y), f.z);
}
`;
export const CHANNEL_HARDWARE_FILTER = /* glsl */ `
vec4 sampleChannelTexels(vec3 p) {
  return texture(volume, (p - u.boxMin) / (u.boxMax - u.boxMin));
}
`;
export const CHANNEL_SAMPLE = /* glsl */ `
vec4 sampleChannels(vec3 p) {
  return clamp(sampleChannelTexels(p) * u.channelScale + u.channelOffset, vec4(0.0), vec4(1.0));
}
float sampleVolumeTexel(vec3 p) { return sampleChannelTexels(p).x; }
`;
/**
 * The channels as one medium: extinction is the sum of the channels' (sigma = sum of opacity_k),
 * colour / albedo each channel's colour weighted by its share opacity_k / sigma, the mixture of
 * participating media (Novák et al. 2018, "Monte Carlo Methods for Volumetric Light Transport
 * Simulation", CGF 37(2), Sec. 2: sigma_t = sum sigma_t,i, albedo = sum sigma_s,i / sigma_t).
 * Where sigma = 0 the colour is never seen; the channels' plain mean keeps it finite.
 */
export const CHANNEL_TRANSFER = /* glsl */ `
// Row 'row' of the TF texture: that drawn channel's 1D transfer function, as transferLookup.
vec4 channelLookup(float value, int row) {
  float x = clamp(value, 0.0, 1.0) * float(u.tfSize - 1);
  float x0 = floor(x);
  int i0 = int(x0);
  int i1 = min(i0 + 1, u.tfSize - 1);
  return lerp4(texelFetch(transferFunction, ivec2(i0, row), 0), texelFetch(transferFunction, ivec2(i1, row), 0), x - x0);
}
#if LABELS
vec4 imageTransferAt(vec3 p) {
#else
vec4 transferAt(vec3 p) {
#endif
  vec4 v = sampleChannels(p);
  vec4 t0 = channelLookup(v.x, 0);
  float sigma = t0.a;
#if CHANNELS >= 2
  vec4 t1 = channelLookup(v.y, 1);
  sigma += t1.a;
#endif
#if CHANNELS >= 3
  vec4 t2 = channelLookup(v.z, 2);
  sigma += t2.a;
#endif
#if CHANNELS >= 4
  vec4 t3 = channelLookup(v.w, 3);
  sigma += t3.a;
#endif
  float even = 1.0 / float(u.tfHeight);
  vec3 rgb = (sigma > 0.0 ? t0.a / sigma : even) * t0.rgb;
#if CHANNELS >= 2
  rgb += (sigma > 0.0 ? t1.a / sigma : even) * t1.rgb;
#endif
#if CHANNELS >= 3
  rgb += (sigma > 0.0 ? t2.a / sigma : even) * t2.rgb;
#endif
#if CHANNELS >= 4
  rgb += (sigma > 0.0 ? t3.a / sigma : even) * t3.rgb;
#endif
  return vec4(rgb, sigma);
}
`;

/** sampleVolume() (the filtered texel, value-mapped) and the 1D TF lookup. */
export const SAMPLE_AND_LOOKUP = /* glsl */ `
float sampleVolume(vec3 p) { return volumeValue(sampleVolumeTexel(p)); }
// 1D transfer function: texel k holds value k/(N-1); linear between texels.
vec4 transferLookup(float value) {
  float x = clamp(value, 0.0, 1.0) * float(u.tfSize - 1);
  float x0 = floor(x);
  int i0 = int(x0);
  int i1 = min(i0 + 1, u.tfSize - 1);
  return lerp4(texelFetch(transferFunction, ivec2(i0, 0), 0), texelFetch(transferFunction, ivec2(i1, 0), 0), x - x0);
}
`;

/** transferAt for a 1D transfer function. */
export const TRANSFER_1D = /* glsl */ `
// The transfer function at a world point: (linear RGB albedo/emission, opacity).
// Renderers call this, not sampleVolume + transferLookup, so a 2D (value x gradient)
// transfer function can change what it reads without touching any renderer.
#if LABELS
vec4 imageTransferAt(vec3 p) {
#else
vec4 transferAt(vec3 p) {
#endif
  return transferLookup(sampleVolume(p));
}
`;

/**
 * Gradient magnitude |grad f| (gradient/gradient-volume.ts), read from the slice atlas
 * (texture `gradientMagnitude`, tile of slice z at (z mod cols, z / cols)) with the same
 * cell-centred trilinear filter as sampleVolume, and normalized by the volume's largest
 * magnitude (1 x 1 texture `gradientMax`). Only in kernels of scenes that need it.
 */
export const GRADIENT = /* glsl */ `
float gradientTexel(ivec3 v) {
  return texelFetch(gradientMagnitude, atlasTexel(v, u.volumeDims.xyz, u.gradientAtlasColumns), 0).r;
}
float sampleGradientMagnitude(vec3 p) {
  vec3 tc = (p - u.boxMin) / (u.boxMax - u.boxMin);
  ivec3 dims = u.volumeDims.xyz;
  vec3 g = tc * vec3(dims) - 0.5;
  vec3 g0 = floor(g);
  vec3 f = g - g0;
  ivec3 i0 = clamp(ivec3(g0), ivec3(0), dims - 1);
  ivec3 i1 = clamp(ivec3(g0) + 1, ivec3(0), dims - 1);
  float c000 = gradientTexel(ivec3(i0.x, i0.y, i0.z));
  float c100 = gradientTexel(ivec3(i1.x, i0.y, i0.z));
  float c010 = gradientTexel(ivec3(i0.x, i1.y, i0.z));
  float c110 = gradientTexel(ivec3(i1.x, i1.y, i0.z));
  float c001 = gradientTexel(ivec3(i0.x, i0.y, i1.z));
  float c101 = gradientTexel(ivec3(i1.x, i0.y, i1.z));
  float c011 = gradientTexel(ivec3(i0.x, i1.y, i1.z));
  float c111 = gradientTexel(ivec3(i1.x, i1.y, i1.z));
  float c00 = lerp1(c000, c100, f.x);
  float c10 = lerp1(c010, c110, f.x);
  float c01 = lerp1(c001, c101, f.x);
  float c11 = lerp1(c011, c111, f.x);
  return lerp1(lerp1(c00, c10, f.y), lerp1(c01, c11, f.y), f.z);
}
// In [0, 1]: the magnitude divided by the 2D TF's gradientMax when set, else by the volume's
// largest (0 for a constant volume).
float normalizedGradientAt(vec3 p) {
  float gmax = u.tfGradientMax > 0.0 ? u.tfGradientMax : texelFetch(gradientMax, ivec2(0, 0), 0).r;
  return gmax > 0.0 ? min(sampleGradientMagnitude(p) / gmax, 1.0) : 0.0;
}
`;

/** transferAt for a 2D (value x normalized gradient magnitude) transfer function. */
export const TRANSFER_2D = /* glsl */ `
// 2D transfer function (Kniss et al. 2002): texel (i, j) holds value i/(W-1) and normalized
// gradient magnitude j/(H-1); bilinear between texels.
vec4 transferLookup2D(float value, float gradient) {
  float x = clamp(value, 0.0, 1.0) * float(u.tfSize - 1);
  float y = clamp(gradient, 0.0, 1.0) * float(u.tfHeight - 1);
  float x0 = floor(x);
  float y0 = floor(y);
  int i0 = int(x0);
  int i1 = min(i0 + 1, u.tfSize - 1);
  int j0 = int(y0);
  int j1 = min(j0 + 1, u.tfHeight - 1);
  vec4 a = lerp4(texelFetch(transferFunction, ivec2(i0, j0), 0), texelFetch(transferFunction, ivec2(i1, j0), 0), x - x0);
  vec4 b = lerp4(texelFetch(transferFunction, ivec2(i0, j1), 0), texelFetch(transferFunction, ivec2(i1, j1), 0), x - x0);
  return lerp4(a, b, y - y0);
}
#if LABELS
vec4 imageTransferAt(vec3 p) {
#else
vec4 transferAt(vec3 p) {
#endif
  return transferLookup2D(sampleVolume(p), normalizedGradientAt(p));
}
`;

/**
 * A scene's slice plane (scene/slice-plane.ts) as an opaque, unlit surface inside the volume:
 * planar reformatting (multiplanar reconstruction) drawn where the camera ray meets the plane,
 * t = (offset − n·o) / (n·d) (ray–plane intersection), the point inside the box and kept by the
 * clip; -1 where the ray misses it. Its colour is the slice renderer's: the voxel (NEAREST) or
 * the shared trilinear filter, the window in data units as an affine map of the normalized value,
 * then grey or the colour map's table (entries at i / (N − 1), linear between them).
 */
export const SLICE_PLANE = /* glsl */ `
float slicePlaneHit(vec3 o, vec3 d) {
  float denom = dot(d, u.slicePlaneNormal);
  float t = abs(denom) > 1e-12 ? (u.slicePlaneOffset - dot(o, u.slicePlaneNormal)) / denom : -1.0;
  vec3 p = o + d * t;
  bool hit = t > 0.0 && all(greaterThanEqual(p, u.boxMin)) && all(lessThanEqual(p, u.boxMax));
#if CLIP
  hit = hit && !isClipped(p);
#endif
  return hit ? t : -1.0;
}
float slicePlaneTexel(vec3 p) {
#if SLICE_PLANE_NEAREST
  ivec3 dims = u.volumeDims.xyz;
  vec3 tc = (p - u.boxMin) / (u.boxMax - u.boxMin);
  ivec3 i = clamp(ivec3(floor(tc * vec3(dims))), ivec3(0), dims - 1);
#if BRICKED
  // A brick atlas is read through the shared filter, at the voxel's centre.
  return sampleVolumeTexel(u.boxMin + (vec3(i) + 0.5) / vec3(dims) * (u.boxMax - u.boxMin));
#else
  return texelFetch(volume, i, 0).r;
#endif
#else
  return sampleVolumeTexel(p);
#endif
}
#if LABELS
vec3 slicePlaneImageColor(vec3 p) {
#else
vec3 slicePlaneColor(vec3 p) {
#endif
  float n = slicePlaneTexel(p) * u.valueScale + u.valueOffset;
  float w = clamp(n * u.slicePlaneWindow.x + u.slicePlaneWindow.y, 0.0, 1.0);
#if SLICE_PLANE_TABLE
  int count = textureSize(slicePlaneColormap, 0).x;
  float x = w * float(count - 1);
  float x0 = floor(x);
  int i0 = int(x0);
  int i1 = min(i0 + 1, count - 1);
  return lerp4(texelFetch(slicePlaneColormap, ivec2(i0, 0), 0), texelFetch(slicePlaneColormap, ivec2(i1, 0), 0), x - x0).rgb;
#else
  return vec3(w);
#endif
}
`;

/** Where commonChunks puts the label chunk (a line the preprocessor cuts when LABELS is off). */
export const LABELS_PLACEHOLDER = '// VPT_LABELS_CHUNK';

/**
 * The shared chunks of a generate pass, variants marked by `#if` lines that commonChunks()
 * (common.ts) resolves with the core preprocessor: the exact or hardware volume filter, the
 * gradient helpers only when the gradient textures are bound, and the transferAt() of a 1D
 * or 2D transfer function.
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
