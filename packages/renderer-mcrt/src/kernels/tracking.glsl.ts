// Free-flight sampling and transmittance estimation against a piecewise-constant majorant:
// delta tracking (Woodcock et al. 1965), ratio tracking and residual ratio tracking (Novák,
// Selle, Jarosz 2014, "Residual Ratio Tracking for Estimating Attenuation in Participating
// Media", SIGGRAPH Asia 2014; control = per-cell minorant), over a coarse grid of per-cell extinction bounds
// walked by a 3D DDA (Amanatides & Woo 1987, "A Fast Voxel Traversal Algorithm for Ray Tracing"), as pbrt-v4's GridMedium. Exponential distances
// are drawn once and their optical depth is carried across cells (memorylessness).
// The shadow-ray estimators estimate the beam transmittance exp(-∫σt dt), PBR 4th ed. Eq. (11.5).
// Preprocessed (core's shaders/preprocess.ts) with MAJORANT_GRID, TRACKING, DEBUG_OUTPUT.

export const tracking = /* glsl */ `
// Every path gets this many tracking steps (cells + tentative collisions); a path that would
// take more is ended as absorbed: it bounds a draw's run time (no hung tab) at a negligible bias.
const int MAX_TRACKING_STEPS = 1048576;
int trackingSteps = 0;
// The sample dimension (core's SAMPLE_DIMS) of the next free flight's first distance; -1: the PCG stream.
int flightDim = -1;
int mediumLookups = 0;
int cellVisits = 0;

// (albedo in [0, 1], extinction σ_t) at a world point: σ_t = densityScale · opacity (docs/design.md),
// capped at σ_max, where one voxel's transmittance underflows float32 (extinction-cap.ts).
vec4 mediumAt(vec3 p) {
  mediumLookups++;
  vec4 tf = transferAt(p);
  return vec4(clamp(tf.rgb, 0.0, 1.0), min(u.densityScale * tf.a, u.extinctionMax));
}

#if MAJORANT_GRID
struct Dda { vec3 tNext; vec3 tDelta; ivec3 cell; ivec3 stepDir; ivec3 cells; };
Dda ddaStart(vec3 o, vec3 d, float t0) {
  Dda s;
  s.cells = u.gridCells.xyz;
  vec3 cellSize = (u.boxMax - u.boxMin) / vec3(s.cells);
  vec3 inv = safeInverse(d);
  vec3 p = (o + d * t0 - u.boxMin) / cellSize;
  s.cell = clamp(ivec3(floor(p)), ivec3(0), s.cells - 1);
  s.stepDir = ivec3(d.x < 0.0 ? -1 : 1, d.y < 0.0 ? -1 : 1, d.z < 0.0 ? -1 : 1);
  vec3 boundary = vec3(s.cell + max(s.stepDir, ivec3(0)));
  s.tNext = (u.boxMin + boundary * cellSize - o) * inv;
  s.tDelta = abs(cellSize * inv);
  return s;
}
// The current cell's (exit distance, majorant, minorant), capped as mediumAt; then step into the next cell.
vec3 ddaNext(inout Dda s) {
  cellVisits++;
  vec4 m = texelFetch(majorantGrid, atlasTexel(clamp(s.cell, ivec3(0), s.cells - 1), s.cells, u.gridCells.w), 0);
  float tExit;
  if (s.tNext.x <= s.tNext.y && s.tNext.x <= s.tNext.z) {
    tExit = s.tNext.x; s.cell.x += s.stepDir.x; s.tNext.x += s.tDelta.x;
  } else if (s.tNext.y <= s.tNext.z) {
    tExit = s.tNext.y; s.cell.y += s.stepDir.y; s.tNext.y += s.tDelta.y;
  } else {
    tExit = s.tNext.z; s.cell.z += s.stepDir.z; s.tNext.z += s.tDelta.z;
  }
  return vec3(tExit, min(m.r, u.extinctionMax), min(m.g, u.extinctionMax));
}
#endif

struct Collision { bool hit; float t; vec3 albedo; };

// Delta tracking (Woodcock et al. 1965) from t0 to t1 along o + t·d: tentative collisions at majorant rate, accepted
// with probability σ_t/majorant. No hit = the ray leaves the medium at t1.
Collision freeFlight(vec3 o, vec3 d, float t0, float t1, inout uint rng) {
  Collision c = Collision(false, t1, vec3(0.0));
  float t = t0;
  float tau = -log(1.0 - rngDim(rng, flightDim));
  flightDim = -1;
#if MAJORANT_GRID
  Dda s = ddaStart(o, d, t0);
#endif
  while (t < t1) {
    if (trackingSteps >= MAX_TRACKING_STEPS) { c.hit = true; return c; }
#if MAJORANT_GRID
    vec3 seg = ddaNext(s);
#else
    vec3 seg = vec3(t1, u.globalMajorant, u.globalMinorant);
#endif
    float tEnd = min(seg.x, t1);
    float maj = seg.y;
    for (;;) {
      trackingSteps++;
      float len = max(tEnd - t, 0.0);
      if (tau >= maj * len || trackingSteps >= MAX_TRACKING_STEPS) { tau -= maj * len; t = max(t, tEnd); break; }
      t += tau / maj;
      vec4 m = mediumAt(o + d * t);
      if (rngNext(rng) * maj < m.a) { c.hit = true; c.t = t; c.albedo = m.rgb; return c; }
      tau = -log(1.0 - rngNext(rng));
    }
  }
  return c;
}

// Transmittance from t0 to t1 along o + t·d (ratio and residual ratio tracking: Novák, Selle, Jarosz 2014). Delta tracking: 1 if the ray gets through, else 0.
// Ratio tracking: product of (1 − σ_t/majorant) over the tentative collisions. Residual ratio
// tracking: exp(−∫σ_c) in closed form times ratio tracking of the residual σ_t − σ_c with
// majorant − σ_c, σ_c the cell's minorant. Russian roulette keeps estimates below 0.1 unbiased.
float transmittance(vec3 o, vec3 d, float t0, float t1, inout uint rng) {
#if TRACKING == 0
  Collision c = freeFlight(o, d, t0, t1, rng);
  return c.hit ? 0.0 : 1.0;
#else
  float T = 1.0;
  float t = t0;
  float tau = -log(1.0 - rngNext(rng));
#if MAJORANT_GRID
  Dda s = ddaStart(o, d, t0);
#endif
  while (t < t1) {
    if (trackingSteps >= MAX_TRACKING_STEPS) return 0.0;
#if MAJORANT_GRID
    vec3 seg = ddaNext(s);
#else
    vec3 seg = vec3(t1, u.globalMajorant, u.globalMinorant);
#endif
    float tEnd = min(seg.x, t1);
#if TRACKING == 2
    float ctl = seg.z;
#else
    float ctl = 0.0;
#endif
    float res = seg.y - ctl;
    float tStart = t;
    for (;;) {
      trackingSteps++;
      float len = max(tEnd - t, 0.0);
      if (tau >= res * len || trackingSteps >= MAX_TRACKING_STEPS) { tau -= res * len; t = max(t, tEnd); break; }
      t += tau / res;
      float sigma = mediumAt(o + d * t).a;
      T *= 1.0 - (sigma - ctl) / res;
      tau = -log(1.0 - rngNext(rng));
      if (T < 0.1) {
        if (rngNext(rng) * 0.1 >= T) return 0.0;
        T = 0.1;
      }
    }
#if TRACKING == 2
    T *= exp(-ctl * (t - tStart));
    if (T < 0.1) {
      if (rngNext(rng) * 0.1 >= T) return 0.0;
      T = 0.1;
    }
#endif
  }
  return T;
#endif
}
`;
