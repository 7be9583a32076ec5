// Free-flight sampling and transmittance estimation (delta tracking, Woodcock et al. 1965; ratio and residual ratio tracking,
// Novák, Selle, Jarosz 2014) over a majorant grid walked by a 3D DDA (Amanatides & Woo 1987).
// The shadow-ray estimators estimate the beam transmittance exp(-∫σt dt), PBR 4th ed. Eq. (11.5).
// Twin of tracking.glsl.ts: same arithmetic in the same order.

export const tracking = /* wgsl */ `
const MAX_TRACKING_STEPS: i32 = 1048576;
var<private> trackingSteps: i32 = 0;
// The sample dimension (core's SAMPLE_DIMS) of the next free flight's first distance; -1: the PCG stream.
var<private> flightDim: i32 = -1;
var<private> mediumLookups: i32 = 0;
var<private> cellVisits: i32 = 0;

fn mediumAt(p: vec3f) -> vec4f {
  mediumLookups++;
  let tf = transferAt(p);
  return vec4f(clamp(tf.rgb, vec3f(0.0), vec3f(1.0)), min(u.densityScale * tf.a, u.extinctionMax));
}

#if MAJORANT_GRID
struct Dda { tNext: vec3f, tDelta: vec3f, cell: vec3i, stepDir: vec3i, cells: vec3i };
fn ddaStart(o: vec3f, d: vec3f, t0: f32) -> Dda {
  var s: Dda;
  s.cells = u.gridCells.xyz;
  let cellSize = (u.boxMax - u.boxMin) / vec3f(s.cells);
  let inv = safeInverse(d);
  let p = (o + d * t0 - u.boxMin) / cellSize;
  s.cell = clamp(vec3i(floor(p)), vec3i(0), s.cells - 1);
  s.stepDir = vec3i(select(1, -1, d.x < 0.0), select(1, -1, d.y < 0.0), select(1, -1, d.z < 0.0));
  let boundary = vec3f(s.cell + max(s.stepDir, vec3i(0)));
  s.tNext = (u.boxMin + boundary * cellSize - o) * inv;
  s.tDelta = abs(cellSize * inv);
  return s;
}
fn ddaNext(s: ptr<function, Dda>) -> vec3f {
  cellVisits++;
  let m = textureLoad(majorantGrid, atlasTexel(clamp((*s).cell, vec3i(0), (*s).cells - 1), (*s).cells, u.gridCells.w), 0);
  var tExit: f32;
  if ((*s).tNext.x <= (*s).tNext.y && (*s).tNext.x <= (*s).tNext.z) {
    tExit = (*s).tNext.x; (*s).cell.x += (*s).stepDir.x; (*s).tNext.x += (*s).tDelta.x;
  } else if ((*s).tNext.y <= (*s).tNext.z) {
    tExit = (*s).tNext.y; (*s).cell.y += (*s).stepDir.y; (*s).tNext.y += (*s).tDelta.y;
  } else {
    tExit = (*s).tNext.z; (*s).cell.z += (*s).stepDir.z; (*s).tNext.z += (*s).tDelta.z;
  }
  return vec3f(tExit, min(m.r, u.extinctionMax), min(m.g, u.extinctionMax));
}
#endif

struct Collision { hit: bool, t: f32, albedo: vec3f };

fn freeFlight(o: vec3f, d: vec3f, t0: f32, t1: f32, rng: ptr<function, u32>) -> Collision {
  var c = Collision(false, t1, vec3f(0.0));
  var t = t0;
  var tau = -log(1.0 - rngDim(rng, flightDim));
  flightDim = -1;
#if MAJORANT_GRID
  var s = ddaStart(o, d, t0);
#endif
  while (t < t1) {
    if (trackingSteps >= MAX_TRACKING_STEPS) { c.hit = true; return c; }
#if MAJORANT_GRID
    let seg = ddaNext(&s);
#else
    let seg = vec3f(t1, u.globalMajorant, u.globalMinorant);
#endif
    let tEnd = min(seg.x, t1);
    let maj = seg.y;
    loop {
      trackingSteps++;
      let len = max(tEnd - t, 0.0);
      if (tau >= maj * len || trackingSteps >= MAX_TRACKING_STEPS) { tau -= maj * len; t = max(t, tEnd); break; }
      t += tau / maj;
      let m = mediumAt(o + d * t);
      if (rngNext(rng) * maj < m.a) { c.hit = true; c.t = t; c.albedo = m.rgb; return c; }
      tau = -log(1.0 - rngNext(rng));
    }
  }
  return c;
}

fn transmittance(o: vec3f, d: vec3f, t0: f32, t1: f32, rng: ptr<function, u32>) -> f32 {
#if TRACKING == 0
  let c = freeFlight(o, d, t0, t1, rng);
  return select(1.0, 0.0, c.hit);
#else
  var T = 1.0;
  var t = t0;
  var tau = -log(1.0 - rngNext(rng));
#if MAJORANT_GRID
  var s = ddaStart(o, d, t0);
#endif
  while (t < t1) {
    if (trackingSteps >= MAX_TRACKING_STEPS) { return 0.0; }
#if MAJORANT_GRID
    let seg = ddaNext(&s);
#else
    let seg = vec3f(t1, u.globalMajorant, u.globalMinorant);
#endif
    let tEnd = min(seg.x, t1);
#if TRACKING == 2
    let ctl = seg.z;
#else
    let ctl = 0.0;
#endif
    let res = seg.y - ctl;
    let tStart = t;
    loop {
      trackingSteps++;
      let len = max(tEnd - t, 0.0);
      if (tau >= res * len || trackingSteps >= MAX_TRACKING_STEPS) { tau -= res * len; t = max(t, tEnd); break; }
      t += tau / res;
      let sigma = mediumAt(o + d * t).a;
      T *= 1.0 - (sigma - ctl) / res;
      tau = -log(1.0 - rngNext(rng));
      if (T < 0.1) {
        if (rngNext(rng) * 0.1 >= T) { return 0.0; }
        T = 0.1;
      }
    }
#if TRACKING == 2
    T *= exp(-ctl * (t - tStart));
    if (T < 0.1) {
      if (rngNext(rng) * 0.1 >= T) { return 0.0; }
      T = 0.1;
    }
#endif
  }
  return T;
#endif
}
`;
