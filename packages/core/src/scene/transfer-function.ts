import { VptError } from '../errors.js';

/** A 1D control point: value in [0, 1] → linear RGB colour and opacity (extinction per unit density scale). */
export interface TransferPoint {
  value: number;
  color: [number, number, number];
  opacity: number;
}

/**
 * Transfer function. `'1d'` maps the normalized value; the `dimensions` tag leaves room
 * for `'2d'` (value × gradient magnitude, rasterized from widgets) without changing
 * the renderers' contract: both rasterize to an RGBA float texture (width × height).
 */
export type TransferFunction = { dimensions: '1d'; points: TransferPoint[] };

/** Texels of the rasterized 1D transfer function. */
export const TF_RESOLUTION = 256;

export function validateTransferFunction(tf: TransferFunction): void {
  const bad = (m: string) => { throw new VptError('invalid-scene', `TransferFunction: ${m}`); };
  if (!tf || tf.dimensions !== '1d') bad(`unknown dimensions "${(tf as { dimensions?: string })?.dimensions}" (supported: "1d")`);
  if (!Array.isArray(tf.points) || tf.points.length === 0) bad('needs at least one control point');
  let last = -Infinity;
  tf.points.forEach((p, i) => {
    if (!Number.isFinite(p.value) || p.value < 0 || p.value > 1) bad(`point ${i}: value must be in [0, 1], got ${p.value}`);
    if (p.value < last) bad(`point ${i}: values must be sorted ascending`);
    last = p.value;
    if (!Array.isArray(p.color) || p.color.length !== 3 || !p.color.every((c) => Number.isFinite(c) && c >= 0)) bad(`point ${i}: color must be three finite non-negative numbers`);
    if (!Number.isFinite(p.opacity) || p.opacity < 0) bad(`point ${i}: opacity must be finite and non-negative, got ${p.opacity}`);
  });
}

/**
 * Rasterize to RGBA float texels (rgb colour, a = opacity), piecewise linear between
 * control points and constant beyond the ends. Texel k holds the value k/(N-1), so the
 * kernels' linear lookup at value v uses coordinate v*(N-1).
 */
export function rasterizeTransferFunction(tf: TransferFunction, resolution = TF_RESOLUTION): Float32Array {
  validateTransferFunction(tf);
  const out = new Float32Array(resolution * 4);
  const pts = tf.points;
  for (let k = 0; k < resolution; k++) {
    const v = k / (resolution - 1);
    let j = 0;
    while (j < pts.length && pts[j].value < v) j++;
    let c: number[];
    let a: number;
    if (j === 0) { c = pts[0].color; a = pts[0].opacity; }
    else if (j === pts.length) { const p = pts[pts.length - 1]; c = p.color; a = p.opacity; }
    else {
      const p0 = pts[j - 1], p1 = pts[j];
      const t = p1.value > p0.value ? (v - p0.value) / (p1.value - p0.value) : 1;
      c = [0, 1, 2].map((i) => p0.color[i] + t * (p1.color[i] - p0.color[i]));
      a = p0.opacity + t * (p1.opacity - p0.opacity);
    }
    out.set([c[0], c[1], c[2], a], k * 4);
  }
  return out;
}

/** A grey ramp: opacity and brightness grow with the value. */
export function rampTransferFunction(color: [number, number, number] = [1, 1, 1]): TransferFunction {
  return { dimensions: '1d', points: [{ value: 0, color, opacity: 0 }, { value: 1, color, opacity: 1 }] };
}
