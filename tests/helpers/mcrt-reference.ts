/**
 * CPU expectations for the MCRT tests, derived from docs/design.md's conventions (camera, box,
 * σ_t = densityScale · opacity, HG with cosθ between propagation directions) in float64:
 * box-filtered pixel footprints by a stratified sub-pixel grid, analytic or quadrature
 * optical depths, and the single-scattering integral under a directional light.
 */
import {
  rasterizeTransferFunction,
  reference,
  TF_RESOLUTION,
  volumeBox,
  type Scene,
  type TransferFunction,
  type Vec3,
} from '../../packages/core/src/index.js';

export const hg = (g: number, cos: number) => (1 - g * g) / (4 * Math.PI * Math.pow(1 + g * g - 2 * g * cos, 1.5));
const norm = (v: Vec3): Vec3 => {
  const l = Math.hypot(...v);
  return [v[0] / l, v[1] / l, v[2] / l];
};
const dot = (a: Vec3, b: Vec3) => a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
const at = (o: Vec3, d: Vec3, t: number): Vec3 => [o[0] + d[0] * t, o[1] + d[1] * t, o[2] + d[2] * t];

/** The TF's opacity as the kernel looks it up (linear between rasterized texels). */
export function opacityLookup(tf: TransferFunction): (v: number) => number {
  const tex = rasterizeTransferFunction(tf, TF_RESOLUTION);
  return (v) => {
    const x = Math.min(1, Math.max(0, v)) * (TF_RESOLUTION - 1);
    const i0 = Math.floor(x),
      i1 = Math.min(i0 + 1, TF_RESOLUTION - 1);
    return tex[4 * i0 + 3] + (tex[4 * i1 + 3] - tex[4 * i0 + 3]) * (x - i0);
  };
}

export interface PixelExpectation {
  value: Vec3;
  /** Every corner and the centre of the pixel's footprint hit the box (a smooth integrand). */
  interior: boolean;
  /** No part of the footprint hits the box. */
  miss: boolean;
}

/**
 * Per-pixel expectation of `radiance(origin, dir, tNear, tFar)` (tNear ≥ tFar when the ray
 * misses the box) averaged over the pixel footprint with sub × sub stratified rays.
 */
export function pixelExpectations(
  scene: Scene,
  W: number,
  H: number,
  radiance: (o: Vec3, d: Vec3, t0: number, t1: number) => Vec3,
  sub = 8,
): PixelExpectation[] {
  const box = volumeBox(scene.volume);
  const out: PixelExpectation[] = [];
  const hits = (fx: number, fy: number) => {
    const { origin, dir } = reference.cameraRay(scene, W, H, fx, fy);
    const [t0, t1] = reference.intersectBox(origin, dir, box.min, box.max);
    return t1 > t0;
  };
  for (let y = 0; y < H; y++)
    for (let x = 0; x < W; x++) {
      const acc: Vec3 = [0, 0, 0];
      let nHit = 0;
      for (let j = 0; j < sub; j++)
        for (let i = 0; i < sub; i++) {
          const { origin, dir } = reference.cameraRay(
            scene,
            W,
            H,
            (x + (i + 0.5) / sub) / W,
            (y + (j + 0.5) / sub) / H,
          );
          const [t0, t1] = reference.intersectBox(origin, dir, box.min, box.max);
          if (t1 > t0) nHit++;
          const L = radiance(origin, dir, t0, t1);
          for (let c = 0; c < 3; c++) acc[c] += L[c] / (sub * sub);
        }
      const corners = [
        [0, 0],
        [1, 0],
        [0, 1],
        [1, 1],
        [0.5, 0.5],
      ].every(([cx, cy]) => hits((x + cx) / W, (y + cy) / H));
      out.push({ value: acc, interior: corners && nHit === sub * sub, miss: nHit === 0 });
    }
  return out;
}

/** Optical depth ∫σ_t along o + t·d over [t0, t1] by the midpoint rule on the kernel's trilinear + TF lookup. */
export function opticalDepth(scene: Scene, steps = 1000): (o: Vec3, d: Vec3, t0: number, t1: number) => number {
  const sampler = new reference.CpuVolumeSampler(scene);
  const opacity = opacityLookup(scene.transferFunction);
  return (o, d, t0, t1) => {
    if (!(t1 > t0)) return 0;
    const h = (t1 - t0) / steps;
    let s = 0;
    for (let k = 0; k < steps; k++) s += opacity(sampler.sample(at(o, d, t0 + (k + 0.5) * h)));
    return scene.densityScale * s * h;
  };
}

/**
 * Single scattering in a homogeneous box (σ_t, albedo a, HG g) lit by one directional light
 * (direction toward the light l, irradiance E), black environment:
 * L = ∫ e^{−σ(t−t0)} σ a p(l·d) E e^{−σ·d_l(x(t))} dt, d_l = distance from x to the box along l.
 * (Light propagates along −l and leaves toward the camera along −d: cosθ = (−l)·(−d) = l·d.)
 */
export function singleScatteringRadiance(
  scene: Scene,
  sigma: number,
  albedo: Vec3,
  g: number,
  light: { direction: Vec3; irradiance: Vec3 },
  steps = 400,
) {
  const box = volumeBox(scene.volume);
  const l = norm(light.direction);
  return (o: Vec3, d: Vec3, t0: number, t1: number): Vec3 => {
    if (!(t1 > t0)) return [0, 0, 0];
    const ph = hg(g, dot(l, d));
    const h = (t1 - t0) / steps;
    let s = 0;
    for (let k = 0; k < steps; k++) {
      const t = t0 + (k + 0.5) * h;
      const x = at(o, d, t);
      const [, exit] = reference.intersectBox(x, l, box.min, box.max);
      s += Math.exp(-sigma * (t - t0)) * Math.exp(-sigma * Math.max(0, exit));
    }
    return [0, 1, 2].map((c) => sigma * albedo[c] * ph * light.irradiance[c] * s * h) as Vec3;
  };
}
