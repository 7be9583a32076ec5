/**
 * Shared GLSL ES 3.0 sampling chunks: directions, the Henyey–Greenstein phase function,
 * MIS heuristics, the lat-long environment mapping and environment importance sampling.
 * Every function has a WGSL twin in sampling.wgsl.ts with the same arithmetic in the same
 * order (bit-identical on SwiftShader). CPU twins live in scene/environment-sampling.ts
 * and reference/sampling-reference.ts.
 */

/** Texture-free helpers: constants, orthonormal frames, uniform sphere, HG phase, MIS. */
export const SAMPLING = /* glsl */ `
const float VPT_PI = 3.14159265358979;
const float VPT_INV_4PI = 0.0795774715459477;
// The unit vector at polar (cosTheta, sinTheta) and azimuth phi about the unit axis n, in the
// branchless orthonormal basis of Duff et al. 2017 ("Building an Orthonormal Basis, Revisited", JCGT 6(1)).
vec3 directionAround(vec3 n, float cosTheta, float sinTheta, float phi) {
  float s = n.z >= 0.0 ? 1.0 : -1.0;
  float a = -1.0 / (s + n.z);
  float b = n.x * n.y * a;
  vec3 t1 = vec3(1.0 + s * n.x * n.x * a, s * b, -s * n.x);
  vec3 t2 = vec3(b, s + n.y * n.y * a, -n.y);
  float cp = cos(phi);
  float sp = sin(phi);
  return normalize(t1 * (sinTheta * cp) + t2 * (sinTheta * sp) + n * cosTheta);
}
// Uniform direction on the unit sphere (pdf 1/4π); sinθ = 2·sqrt(ξ(1−ξ)) has no cancellation at the poles.
vec3 sampleUniformSphere(float xi1, float xi2) {
  float z = 1.0 - 2.0 * xi1;
  float r = 2.0 * sqrt(max(xi1 * (1.0 - xi1), 0.0));
  float phi = 2.0 * VPT_PI * xi2;
  return vec3(r * cos(phi), r * sin(phi), z);
}
// Henyey–Greenstein phase function (Henyey & Greenstein 1941, "Diffuse radiation in the Galaxy", ApJ 93; PBR 4th ed. §11.3, p_HG) from a = 1 − cosθ and b = 1 + cosθ,
// cosθ between the propagation directions before and after scattering, g > 0 forward (docs/design.md).
// 1 + g² − 2g·cosθ is written (1−g)² + 2g·a for g ≥ 0 and (1+g)² − 2g·b for g < 0: no cancellation as |g| → 1.
float hgPhaseAB(float g, float a, float b) {
  float d = g >= 0.0 ? (1.0 - g) * (1.0 - g) + 2.0 * g * a : (1.0 + g) * (1.0 + g) - 2.0 * g * b;
  return (1.0 - g) * (1.0 + g) * VPT_INV_4PI / (d * sqrt(d));
}
float hgPhase(float g, float cosTheta) {
  return hgPhaseAB(g, 1.0 - cosTheta, 1.0 + cosTheta);
}
// Sample HG about the propagation direction w by inverting its CDF in closed form (PBR 4th ed. §11.3), with
// 1 − cosθ = 2(1−g)²(1−ξ)(1+gξ)/(1−g+2gξ)² and 1 + cosθ = 2(1+g)²ξ(1−g+gξ)/(1−g+2gξ)²: the
// classic cosθ = (1 + g² − ((1−g²)/(1−g+2gξ))²)/2g rearranged so that g = 0 needs no special
// case and |g| → 1 loses no precision (no division by g, no difference of near-equal terms).
// Returns (direction, pdf in solid angle).
vec4 sampleHG(vec3 w, float g, float xi1, float xi2) {
  float den = 1.0 - g + 2.0 * g * xi1;
  float q = 2.0 / (den * den);
  float a = (1.0 - g) * (1.0 - g) * (1.0 - xi1) * (1.0 + g * xi1) * q;
  float b = (1.0 + g) * (1.0 + g) * xi1 * (1.0 - g + g * xi1) * q;
  float cosTheta = a < 1.0 ? 1.0 - a : b - 1.0;
  float sinTheta = sqrt(max(a * b, 0.0));
  vec3 dir = directionAround(w, cosTheta, sinTheta, 2.0 * VPT_PI * xi2);
  return vec4(dir, hgPhaseAB(g, a, b));
}
// MIS weights for strategy pdf a against b: the power heuristic with β = 2 and the balance heuristic (Veach & Guibas 1995, "Optimally Combining Sampling Techniques for Monte Carlo Rendering").
float misPower(float a, float b) {
  if (!(a > 0.0)) return 0.0;
  float r = b / a;
  return 1.0 / (1.0 + r * r);
}
float misBalance(float a, float b) {
  if (!(a > 0.0)) return 0.0;
  return 1.0 / (1.0 + b / a);
}
// Lat-long (equirectangular) mapping, the convention of Mitsuba 3's envmap: u = atan2(x, −z)/2π
// wrapped to [0, 1) (u = 0 looks along −z, u = 1/4 along +x), v = acos(y)/π (row 0 = +y, the top).
vec2 directionToLatLong(vec3 d) {
  float u = (d.x == 0.0 && d.z == 0.0) ? 0.0 : atan(d.x, -d.z) * (0.5 / VPT_PI);
  u = u < 0.0 ? u + 1.0 : u;
  float v = acos(clamp(d.y, -1.0, 1.0)) * (1.0 / VPT_PI);
  return vec2(u, v);
}
vec3 latLongToDirection(vec2 uv) {
  float phi = 2.0 * VPT_PI * uv.x;
  float theta = VPT_PI * uv.y;
  float st = sin(theta);
  return vec3(st * sin(phi), cos(theta), -st * cos(phi));
}
`;

/**
 * Lat-long environment lookup and importance sampling. Needs SAMPLING and three
 * textures built by `buildEnvironmentSampling` (scene/environment-sampling.ts):
 * `envMap` (W x H rgba32float: rgb radiance, a = pdf of the texel in (u, v) space),
 * `envMarginal` ((H+1) x 1, the row CDF) and `envConditional` ((W+1) x H, each row's column CDF).
 */
export const ENVIRONMENT_MAP = /* glsl */ `
struct EnvSample { vec3 direction; float pdf; vec3 radiance; };
// Radiance seen along d (nearest texel: the same piecewise-constant function the sampler draws from)
// and the solid-angle pdf of sampleEnvironment for d: p(ω) = p(u, v) / (2π² sinθ).
vec4 environmentLookup(vec3 d) {
  ivec2 size = textureSize(envMap, 0);
  vec2 uv = directionToLatLong(d);
  int i = clamp(int(uv.x * float(size.x)), 0, size.x - 1);
  int j = clamp(int(uv.y * float(size.y)), 0, size.y - 1);
  vec4 texel = texelFetch(envMap, ivec2(i, j), 0);
  float sinTheta = sqrt(max((1.0 - d.y) * (1.0 + d.y), 0.0));
  float pdf = sinTheta > 0.0 ? texel.a / (2.0 * VPT_PI * VPT_PI * sinTheta) : 0.0;
  return vec4(texel.rgb, pdf);
}
// Importance sampling by luminance × sinθ (Pharr, Jakob, Humphreys, PBR 3rd ed., §14.2 "Sampling Light Sources", infinite area lights): a row from
// the marginal CDF, a column from that row's conditional CDF (binary searches for the largest
// entry <= ξ, which skips zero-width bins), then a uniform point inside the texel.
EnvSample sampleEnvironment(float xi1, float xi2) {
  ivec2 size = textureSize(envMap, 0);
  int lo = 0;
  int hi = size.y - 1;
  while (lo < hi) {
    int mid = (lo + hi + 1) / 2;
    if (texelFetch(envMarginal, ivec2(mid, 0), 0).r <= xi1) { lo = mid; } else { hi = mid - 1; }
  }
  int j = lo;
  float m0 = texelFetch(envMarginal, ivec2(j, 0), 0).r;
  float m1 = texelFetch(envMarginal, ivec2(j + 1, 0), 0).r;
  float dv = clamp((xi1 - m0) / (m1 - m0), 0.0, 0.99999994);
  lo = 0;
  hi = size.x - 1;
  while (lo < hi) {
    int mid = (lo + hi + 1) / 2;
    if (texelFetch(envConditional, ivec2(mid, j), 0).r <= xi2) { lo = mid; } else { hi = mid - 1; }
  }
  int i = lo;
  float c0 = texelFetch(envConditional, ivec2(i, j), 0).r;
  float c1 = texelFetch(envConditional, ivec2(i + 1, j), 0).r;
  float du = clamp((xi2 - c0) / (c1 - c0), 0.0, 0.99999994);
  vec2 uv = vec2((float(i) + du) / float(size.x), (float(j) + dv) / float(size.y));
  vec4 texel = texelFetch(envMap, ivec2(i, j), 0);
  float sinTheta = sin(VPT_PI * uv.y);
  EnvSample s;
  s.direction = latLongToDirection(uv);
  s.radiance = texel.rgb;
  s.pdf = sinTheta > 0.0 ? texel.a / (2.0 * VPT_PI * VPT_PI * sinTheta) : 0.0;
  return s;
}
`;
