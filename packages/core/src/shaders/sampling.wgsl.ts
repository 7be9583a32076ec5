/**
 * Shared WGSL sampling chunks: twins of sampling.glsl.ts, same arithmetic in the same order.
 */

/** Texture-free helpers: constants, orthonormal frames, uniform sphere, HG phase, MIS. */
export const SAMPLING = /* wgsl */ `
const VPT_PI: f32 = 3.14159265358979;
const VPT_INV_4PI: f32 = 0.0795774715459477;
// Duff et al. 2017, "Building an Orthonormal Basis, Revisited", JCGT 6(1).
fn directionAround(n: vec3f, cosTheta: f32, sinTheta: f32, phi: f32) -> vec3f {
  let s = select(-1.0, 1.0, n.z >= 0.0);
  let a = -1.0 / (s + n.z);
  let b = n.x * n.y * a;
  let t1 = vec3f(1.0 + s * n.x * n.x * a, s * b, -s * n.x);
  let t2 = vec3f(b, s + n.y * n.y * a, -n.y);
  let cp = cos(phi);
  let sp = sin(phi);
  return normalize(t1 * (sinTheta * cp) + t2 * (sinTheta * sp) + n * cosTheta);
}
fn sampleUniformSphere(xi1: f32, xi2: f32) -> vec3f {
  let z = 1.0 - 2.0 * xi1;
  let r = 2.0 * sqrt(max(xi1 * (1.0 - xi1), 0.0));
  let phi = 2.0 * VPT_PI * xi2;
  return vec3f(r * cos(phi), r * sin(phi), z);
}
// Henyey–Greenstein phase function (Henyey & Greenstein 1941, ApJ 93; PBR 4th ed. §11.3, p_HG), cancellation-free for |g| → 1 (see sampling.glsl.ts).
fn hgPhaseAB(g: f32, a: f32, b: f32) -> f32 {
  let d = select((1.0 + g) * (1.0 + g) - 2.0 * g * b, (1.0 - g) * (1.0 - g) + 2.0 * g * a, g >= 0.0);
  return (1.0 - g) * (1.0 + g) * VPT_INV_4PI / (d * sqrt(d));
}
fn hgPhase(g: f32, cosTheta: f32) -> f32 {
  return hgPhaseAB(g, 1.0 - cosTheta, 1.0 + cosTheta);
}
// HG sampling by closed-form CDF inversion (PBR 4th ed. §11.3), 1 ∓ cosθ computed directly (see sampling.glsl.ts).
fn sampleHG(w: vec3f, g: f32, xi1: f32, xi2: f32) -> vec4f {
  let den = 1.0 - g + 2.0 * g * xi1;
  let q = 2.0 / (den * den);
  let a = (1.0 - g) * (1.0 - g) * (1.0 - xi1) * (1.0 + g * xi1) * q;
  let b = (1.0 + g) * (1.0 + g) * xi1 * (1.0 - g + g * xi1) * q;
  let cosTheta = select(b - 1.0, 1.0 - a, a < 1.0);
  let sinTheta = sqrt(max(a * b, 0.0));
  let dir = directionAround(w, cosTheta, sinTheta, 2.0 * VPT_PI * xi2);
  return vec4f(dir, hgPhaseAB(g, a, b));
}
// The power (β = 2) and balance heuristics (Veach & Guibas 1995, "Optimally Combining Sampling Techniques…").
fn misPower(a: f32, b: f32) -> f32 {
  if (!(a > 0.0)) { return 0.0; }
  let r = b / a;
  return 1.0 / (1.0 + r * r);
}
fn misBalance(a: f32, b: f32) -> f32 {
  if (!(a > 0.0)) { return 0.0; }
  return 1.0 / (1.0 + b / a);
}
// Lat-long mapping of Mitsuba 3's envmap (see sampling.glsl.ts).
fn directionToLatLong(d: vec3f) -> vec2f {
  var u = select(atan2(d.x, -d.z) * (0.5 / VPT_PI), 0.0, d.x == 0.0 && d.z == 0.0);
  u = select(u, u + 1.0, u < 0.0);
  let v = acos(clamp(d.y, -1.0, 1.0)) * (1.0 / VPT_PI);
  return vec2f(u, v);
}
fn latLongToDirection(uv: vec2f) -> vec3f {
  let phi = 2.0 * VPT_PI * uv.x;
  let theta = VPT_PI * uv.y;
  let st = sin(theta);
  return vec3f(st * sin(phi), cos(theta), -st * cos(phi));
}
`;

/** Lat-long environment lookup and importance sampling (textures as in sampling.glsl.ts). */
export const ENVIRONMENT_MAP = /* wgsl */ `
struct EnvSample { direction: vec3f, pdf: f32, radiance: vec3f };
fn environmentLookup(d: vec3f) -> vec4f {
  let size = vec2i(textureDimensions(envMap));
  let uv = directionToLatLong(d);
  let i = clamp(i32(uv.x * f32(size.x)), 0, size.x - 1);
  let j = clamp(i32(uv.y * f32(size.y)), 0, size.y - 1);
  let texel = textureLoad(envMap, vec2i(i, j), 0);
  let sinTheta = sqrt(max((1.0 - d.y) * (1.0 + d.y), 0.0));
  let pdf = select(0.0, texel.a / (2.0 * VPT_PI * VPT_PI * sinTheta), sinTheta > 0.0);
  return vec4f(texel.rgb, pdf);
}
// PBR 3rd ed., §14.2 "Sampling Light Sources" (infinite area lights): marginal row, conditional column, uniform inside the texel.
fn sampleEnvironment(xi1: f32, xi2: f32) -> EnvSample {
  let size = vec2i(textureDimensions(envMap));
  var lo = 0;
  var hi = size.y - 1;
  while (lo < hi) {
    let mid = (lo + hi + 1) / 2;
    if (textureLoad(envMarginal, vec2i(mid, 0), 0).r <= xi1) { lo = mid; } else { hi = mid - 1; }
  }
  let j = lo;
  let m0 = textureLoad(envMarginal, vec2i(j, 0), 0).r;
  let m1 = textureLoad(envMarginal, vec2i(j + 1, 0), 0).r;
  let dv = clamp((xi1 - m0) / (m1 - m0), 0.0, 0.99999994);
  lo = 0;
  hi = size.x - 1;
  while (lo < hi) {
    let mid = (lo + hi + 1) / 2;
    if (textureLoad(envConditional, vec2i(mid, j), 0).r <= xi2) { lo = mid; } else { hi = mid - 1; }
  }
  let i = lo;
  let c0 = textureLoad(envConditional, vec2i(i, j), 0).r;
  let c1 = textureLoad(envConditional, vec2i(i + 1, j), 0).r;
  let du = clamp((xi2 - c0) / (c1 - c0), 0.0, 0.99999994);
  let uv = vec2f((f32(i) + du) / f32(size.x), (f32(j) + dv) / f32(size.y));
  let texel = textureLoad(envMap, vec2i(i, j), 0);
  let sinTheta = sin(VPT_PI * uv.y);
  var s: EnvSample;
  s.direction = latLongToDirection(uv);
  s.radiance = texel.rgb;
  s.pdf = select(0.0, texel.a / (2.0 * VPT_PI * VPT_PI * sinTheta), sinTheta > 0.0);
  return s;
}
`;
