import { VptError } from '../errors.js';
import { FLOAT32_MAX, MAX_OPACITY, MAX_RADIANCE } from '../validation/limits.js';

/** A 1D control point: value in [0, 1] → linear RGB colour and opacity (extinction per unit density scale). */
export interface TransferPoint {
  value: number;
  color: [number, number, number];
  opacity: number;
}

/** 1D transfer function: piecewise linear over the normalized value. */
export interface TransferFunction1D {
  dimensions: '1d';
  points: TransferPoint[];
}

/**
 * A Gaussian bump over (value, normalized gradient magnitude), both in [0, 1]:
 * weight = exp(-½((v - cv)/sv)² - ½((g - cg)/sg)²).
 */
export interface GaussianWidget {
  type: 'gaussian';
  /** [value, gradient] of the peak. */
  center: [number, number];
  /** Standard deviations [along value, along gradient], both > 0. */
  width: [number, number];
  color: [number, number, number];
  opacity: number;
}

/**
 * A box over (value, normalized gradient magnitude) with optional linear ramps outside
 * it (a trapezoid per axis): weight 1 inside [min, max], falling linearly to 0 at
 * min - ramp and max + ramp; the two axes multiply. ramp [0, 0] is a hard box.
 */
export interface BoxWidget {
  type: 'box';
  min: [number, number];
  max: [number, number];
  /** Widths of the soft edges [along value, along gradient], >= 0. Default [0, 0]. */
  ramp?: [number, number];
  color: [number, number, number];
  opacity: number;
}

export type TransferWidget = GaussianWidget | BoxWidget;

/**
 * 2D transfer function over value × normalized gradient magnitude (Kniss et al. 2002,
 * "Multidimensional transfer functions for interactive volume rendering"), built from
 * widgets. Where widgets overlap, their extinctions add (a mixture of media): opacity =
 * Σ opacity_w·weight_w and colour = Σ opacity_w·weight_w·color_w / opacity.
 * The gradient axis is |∇f| (data units per spacing unit) divided by `gradientMax`, or by
 * the volume's largest gradient magnitude when `gradientMax` is left out.
 */
export interface TransferFunction2D {
  dimensions: '2d';
  widgets: TransferWidget[];
  /**
   * The gradient magnitude that maps to 1 on the gradient axis (larger ones clamp to 1), in
   * the volume's data units per spacing unit (e.g. HU/mm). Fixing it makes a TF mean the same
   * on volumes with different extreme gradients; default: the volume's largest magnitude.
   */
  gradientMax?: number;
}

/**
 * Transfer function: `'1d'` maps the normalized value, `'2d'` value × normalized gradient
 * magnitude. Both rasterize to an RGBA float texture (rgb colour, a = opacity), 256 × 1
 * or 256 × 256, which the shared `transferAt(p)` chunk reads.
 */
export type TransferFunction = TransferFunction1D | TransferFunction2D;

/** Texels of the rasterized 1D transfer function (and of each axis of a 2D one). */
export const TF_RESOLUTION = 256;
/** Texels along the gradient axis of a rasterized 2D transfer function. */
export const TF_2D_HEIGHT = 256;

export const WIDGET_TYPES = ['gaussian', 'box'] as const;

/** Size in texels [width (value axis), height (gradient axis)] of the rasterized transfer function. */
export function transferFunctionSize(tf: TransferFunction, resolution = TF_RESOLUTION): [number, number] {
  return tf.dimensions === '2d' ? [resolution, TF_2D_HEIGHT] : [resolution, 1];
}

type Bad = (m: string) => never;

/** Most control points of a 1D transfer function: rasterizing stays cheap. */
export const MAX_TF_POINTS = 4096;

/**
 * Most widgets of a 2D transfer function. Rasterizing costs texels × widgets (256 × 256 ×
 * 4,096 exponentials took over 20 s on a loaded 2-core machine, and a scene rasterizes it more
 * than once); 256 widgets keep it to about a second, far more than an editor shows.
 */
export const MAX_TF_WIDGETS = 256;

const describe = (x: unknown) => (typeof x === 'number' ? String(x) : (JSON.stringify(x) ?? String(x)));

function checkColor(c: unknown, where: string, bad: Bad): void {
  if (!Array.isArray(c) || c.length !== 3 || !c.every((x) => typeof x === 'number' && Number.isFinite(x) && x >= 0)) {
    bad(`${where}: color must be three finite non-negative numbers, got ${describe(c)}`);
  }
  // Emission (EAM) multiplies the colour like a radiance: the same float32 bound.
  if ((c as number[]).some((x) => x > MAX_RADIANCE))
    bad(
      `${where}: color ${describe(c)} exceeds the limit ${MAX_RADIANCE} (MAX_RADIANCE keeps float32 kernel arithmetic finite)`,
    );
}

function checkOpacity(o: unknown, where: string, bad: Bad): void {
  if (typeof o !== 'number' || !Number.isFinite(o))
    bad(`${where}: opacity must be a finite number, got ${describe(o)}`);
  if ((o as number) < 0) bad(`${where}: opacity must be non-negative, got ${describe(o)}`);
  if ((o as number) > MAX_OPACITY)
    bad(
      `${where}: opacity ${describe(o)} exceeds the limit ${MAX_OPACITY} (MAX_OPACITY: extinction densityScale × opacity must stay finite in float32)`,
    );
}

function checkPair(
  p: unknown,
  where: string,
  name: string,
  bad: Bad,
  rule?: (x: number) => boolean,
  ruleText?: string,
): void {
  if (
    !Array.isArray(p) ||
    p.length !== 2 ||
    !p.every((x) => typeof x === 'number' && Number.isFinite(x) && Math.abs(x) <= FLOAT32_MAX)
  ) {
    bad(`${where}: ${name} must be two finite numbers [value, gradient], got ${describe(p)}`);
  }
  if (rule && !(p as number[]).every(rule)) bad(`${where}: ${name} must be ${ruleText}, got ${describe(p)}`);
}

function validateWidget(w: TransferWidget, i: number, bad: Bad): void {
  const where = `widget ${i}`;
  if (!w || typeof w !== 'object') bad(`${where}: must be an object, got ${describe(w)}`);
  if (w.type === 'gaussian') {
    checkPair(w.center, where, 'center', bad);
    checkPair(w.width, where, 'width', bad, (x) => x > 0, 'positive (standard deviations)');
  } else if (w.type === 'box') {
    checkPair(w.min, where, 'min', bad);
    checkPair(w.max, where, 'max', bad);
    if (w.min[0] > w.max[0] || w.min[1] > w.max[1])
      bad(`${where}: min must not exceed max, got min ${describe(w.min)} max ${describe(w.max)}`);
    if (w.ramp !== undefined) checkPair(w.ramp, where, 'ramp', bad, (x) => x >= 0, 'non-negative');
  } else {
    bad(
      `${where}: unknown widget type ${describe((w as { type?: unknown }).type)} (supported: ${WIDGET_TYPES.join(', ')})`,
    );
  }
  checkColor(w.color, where, bad);
  checkOpacity(w.opacity, where, bad);
}

/** Check a transfer function against the model's rules; throws VptError('invalid-scene') naming the bad field. */
export function validateTransferFunction(tf: TransferFunction): void {
  const bad: Bad = (m: string) => {
    throw new VptError('invalid-scene', `TransferFunction: ${m}`);
  };
  if (!tf || typeof tf !== 'object') bad(`must be an object, got ${describe(tf)}`);
  if (tf.dimensions === '2d') {
    if (!Array.isArray(tf.widgets) || tf.widgets.length === 0) bad('a 2D transfer function needs at least one widget');
    if (
      tf.gradientMax !== undefined &&
      !(
        typeof tf.gradientMax === 'number' &&
        Number.isFinite(tf.gradientMax) &&
        tf.gradientMax > 0 &&
        tf.gradientMax <= FLOAT32_MAX
      )
    ) {
      bad(`gradientMax must be a positive finite number (or left out), got ${describe(tf.gradientMax)}`);
    }
    if (tf.widgets.length > MAX_TF_WIDGETS)
      throw new VptError(
        'limit-exceeded',
        `TransferFunction: ${tf.widgets.length} widgets exceed the limit of ${MAX_TF_WIDGETS} (MAX_TF_WIDGETS: rasterizing costs 65,536 texels per widget)`,
      );
    tf.widgets.forEach((w, i) => validateWidget(w, i, bad));
    return;
  }
  if (tf.dimensions !== '1d')
    bad(`unknown dimensions ${describe((tf as { dimensions?: unknown }).dimensions)} (supported: "1d", "2d")`);
  if (!Array.isArray(tf.points) || tf.points.length === 0) bad('needs at least one control point');
  let last = -Infinity;
  if (tf.points.length > MAX_TF_POINTS)
    throw new VptError(
      'limit-exceeded',
      `TransferFunction: ${tf.points.length} control points exceed the limit of ${MAX_TF_POINTS} (MAX_TF_POINTS)`,
    );
  tf.points.forEach((p, i) => {
    if (!p || typeof p !== 'object') bad(`point ${i}: must be an object, got ${describe(p)}`);
    if (typeof p.value !== 'number' || !Number.isFinite(p.value) || p.value < 0 || p.value > 1)
      bad(`point ${i}: value must be in [0, 1], got ${describe(p.value)}`);
    if (p.value < last) bad(`point ${i}: values must be sorted ascending`);
    last = p.value;
    checkColor(p.color, `point ${i}`, bad);
    checkOpacity(p.opacity, `point ${i}`, bad);
  });
}

/**
 * Rasterize to RGBA float texels (rgb colour, a = opacity), x (value) fastest.
 * 1D: piecewise linear between control points, constant beyond the ends; texel k holds
 * value k/(N-1), so the kernels' linear lookup at value v uses coordinate v·(N-1).
 * 2D: texel (i, j) holds value i/(W-1) and normalized gradient magnitude j/(H-1).
 */
export function rasterizeTransferFunction(tf: TransferFunction, resolution = TF_RESOLUTION): Float32Array {
  validateTransferFunction(tf);
  if (tf.dimensions === '2d') return rasterize2D(tf, resolution, TF_2D_HEIGHT);
  const out = new Float32Array(resolution * 4);
  const pts = tf.points;
  for (let k = 0; k < resolution; k++) {
    const v = k / (resolution - 1);
    let j = 0;
    while (j < pts.length && pts[j].value < v) j++;
    let c: number[];
    let a: number;
    if (j === 0) {
      c = pts[0].color;
      a = pts[0].opacity;
    } else if (j === pts.length) {
      const p = pts[pts.length - 1];
      c = p.color;
      a = p.opacity;
    } else {
      const p0 = pts[j - 1],
        p1 = pts[j];
      const t = p1.value > p0.value ? (v - p0.value) / (p1.value - p0.value) : 1;
      c = [0, 1, 2].map((i) => p0.color[i] + t * (p1.color[i] - p0.color[i]));
      a = p0.opacity + t * (p1.opacity - p0.opacity);
    }
    out.set([c[0], c[1], c[2], a], k * 4);
  }
  return out;
}

/** Weight of a widget at (v, g), in [0, 1]. */
export function widgetWeight(w: TransferWidget, v: number, g: number): number {
  if (w.type === 'gaussian') {
    const dv = (v - w.center[0]) / w.width[0];
    const dg = (g - w.center[1]) / w.width[1];
    return Math.exp(-0.5 * (dv * dv + dg * dg));
  }
  const ramp = w.ramp ?? [0, 0];
  return trapezoid(v, w.min[0], w.max[0], ramp[0]) * trapezoid(g, w.min[1], w.max[1], ramp[1]);
}

function trapezoid(x: number, lo: number, hi: number, ramp: number): number {
  if (x >= lo && x <= hi) return 1;
  const d = x < lo ? lo - x : x - hi;
  return ramp > 0 && d < ramp ? 1 - d / ramp : 0;
}

function rasterize2D(tf: TransferFunction2D, width: number, height: number): Float32Array {
  const out = new Float32Array(width * height * 4);
  for (let j = 0; j < height; j++) {
    const g = j / (height - 1);
    for (let i = 0; i < width; i++) {
      const v = i / (width - 1);
      let a = 0,
        r = 0,
        gr = 0,
        b = 0;
      for (const w of tf.widgets) {
        const s = w.opacity * widgetWeight(w, v, g);
        a += s;
        r += s * w.color[0];
        gr += s * w.color[1];
        b += s * w.color[2];
      }
      const k = 4 * (i + width * j);
      // Extinction-weighted mean colour; where nothing is opaque the colour is irrelevant (0).
      if (a > 0) {
        out[k] = r / a;
        out[k + 1] = gr / a;
        out[k + 2] = b / a;
      }
      out[k + 3] = a;
    }
  }
  return out;
}

/**
 * Per value texel, the largest opacity over the gradient axis: the rasterized opacity itself
 * for a 1D TF, the column maximum for a 2D one. An upper bound of the opacity at a value that
 * holds whatever the gradient is, for conservative bounds such as majorant grids.
 */
export function maxOpacityByValue(tf: TransferFunction, resolution = TF_RESOLUTION): Float32Array {
  const raster = rasterizeTransferFunction(tf, resolution);
  const [width, height] = transferFunctionSize(tf, resolution);
  const out = new Float32Array(width);
  for (let j = 0; j < height; j++) {
    for (let i = 0; i < width; i++) out[i] = Math.max(out[i], raster[4 * (i + width * j) + 3]);
  }
  return out;
}

/** A grey ramp: opacity and brightness grow with the value. */
export function rampTransferFunction(color: [number, number, number] = [1, 1, 1]): TransferFunction {
  return {
    dimensions: '1d',
    points: [
      { value: 0, color, opacity: 0 },
      { value: 1, color, opacity: 1 },
    ],
  };
}
