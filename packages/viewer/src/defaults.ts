/**
 * What <vpt-viewer> shows when only `src` is set: a transfer function fitted to the data's
 * histogram, and per renderer a density, an environment and lights that contrast with it
 * (a warm, emissive or lit volume against a dark background). Each applies only while
 * its attribute is unset; environment and lights are one choice (either set: neither default).
 */
import type { Camera, Environment, Light, TransferFunction, Volume } from '@vpt/core';
import { valueHistogram } from './histogram.js';

type Rgb = [number, number, number];

const PALETTES: Record<'warm' | 'hot' | 'cool', [Rgb, Rgb, Rgb]> = {
  warm: [
    [0.8, 0.45, 0.3],
    [1.0, 0.8, 0.65],
    [2.2, 2.1, 1.9],
  ],
  hot: [
    [1.2, 0.15, 0.02],
    [2.4, 1.1, 0.1],
    [4, 3.4, 2.4],
  ],
  cool: [
    [0.1, 0.3, 1.0],
    [0.4, 1.2, 1.6],
    [2.5, 2.6, 2.8],
  ],
};
export type Palette = keyof typeof PALETTES;

/**
 * A transfer function from the histogram: clear below the median of the non-background
 * voxels (bin 0 left out), rising to opaque at the 99.5th percentile, in a palette's
 * colours (linear RGB; the brightest above 1, emissive). Good enough to see any volume.
 */
export function autoTransferFunction(volume: Volume, palette: Palette = 'warm'): TransferFunction {
  const h = valueHistogram(volume, 256);
  let total = 0;
  for (let i = 1; i < h.bins.length; i++) total += h.bins[i];
  const quantile = (q: number) => {
    let acc = 0;
    for (let i = 1; i < h.bins.length; i++) {
      acc += h.bins[i];
      if (acc >= q * total) return (i + 0.5) / h.bins.length;
    }
    return 1;
  };
  const [c0, c1, c2] = PALETTES[palette];
  const lo = quantile(0.5),
    mid = Math.max(quantile(0.9), lo + 0.01),
    hi = Math.max(quantile(0.995), mid + 0.02);
  const r = (x: number) => Math.round(Math.min(1, x) * 1e4) / 1e4;
  return {
    dimensions: '1d',
    points: [
      { value: r(lo), color: [...c0], opacity: 0 },
      { value: r(mid), color: [...c1], opacity: 0.15 },
      { value: r(hi), color: [...c2], opacity: 1 },
    ],
  };
}

/** A 1D transfer function's colours as albedos in [0, 1] for the path tracer (emissive colours above 1 are not albedos). */
export function asAlbedo(tf: TransferFunction): TransferFunction {
  if (tf.dimensions !== '1d') return tf;
  return {
    ...tf,
    points: tf.points.map((p) => ({
      ...p,
      color: p.color.map((c) => Math.min(0.98, c / Math.max(1, ...p.color))) as Rgb,
    })),
  };
}

/** A 1D transfer function with every colour multiplied by k. */
export function scaleColors(tf: TransferFunction, k: number): TransferFunction {
  if (tf.dimensions !== '1d') return tf;
  return {
    ...tf,
    points: tf.points.map((p) => ({ ...p, color: p.color.map((c) => Math.round(c * k * 1e4) / 1e4) as Rgb })),
  };
}

/** The value where a 1D transfer function first reaches a third of its largest opacity: a sensible isovalue. */
export function isoValueOf(tf: TransferFunction): number {
  if (tf.dimensions !== '1d') return 0.5;
  const max = Math.max(...tf.points.map((p) => p.opacity));
  return tf.points.find((p) => p.opacity >= max / 3)?.value ?? 0.5;
}

/** A directional light from above the camera's left shoulder, in the camera's "up". */
export function keyLight(camera: Camera, irradiance: Rgb): Light[] {
  const [px, py, pz] = camera.position;
  const [tx, ty, tz] = camera.target;
  const [ux, uy, uz] = camera.up;
  const d: Rgb = [px - tx, py - ty, pz - tz];
  const len = Math.hypot(...d) || 1;
  const dir: Rgb = [d[0] / len + 1.2 * ux, d[1] / len + 1.2 * uy, d[2] / len + 1.2 * uz];
  const l = Math.hypot(...dir) || 1;
  return [{ type: 'directional', direction: dir.map((x) => Math.round((x / l) * 1e4) / 1e4) as Rgb, irradiance }];
}

export interface RendererLook {
  /** Extinction per world unit at opacity 1 that suits the automatic transfer function. */
  densityScale: number;
  environment: Environment;
  /** Lights for a camera (the framing camera when the volume loaded). */
  lights(camera: Camera): Light[];
  /** The automatic transfer function as this renderer wants it. */
  transferFunction(tf: TransferFunction): TransferFunction;
}

const dark = (r: number, g: number, b: number): Environment => ({ type: 'constant', radiance: [r, g, b] });

/** The default look of each built-in renderer (others get the emission–absorption one). */
export function rendererLook(renderer: string): RendererLook {
  switch (renderer) {
    case 'mip':
      return { densityScale: 20, environment: dark(0, 0, 0), lights: () => [], transferFunction: (tf) => tf };
    case 'iso':
      return {
        densityScale: 20,
        environment: dark(0.1, 0.11, 0.14),
        lights: (c) => keyLight(c, [2.6, 2.5, 2.3]),
        transferFunction: (tf) => tf,
      };
    case 'mcrt':
      return {
        densityScale: 150,
        environment: dark(0.08, 0.09, 0.12),
        lights: (c) => keyLight(c, [4, 3.7, 3.2]),
        transferFunction: asAlbedo,
      };
    default:
      // Emission–absorption: the palette's emissive top (2.2) saturates a dense volume; 0.55× keeps its structure.
      return {
        densityScale: 60,
        environment: dark(0.03, 0.035, 0.05),
        lights: () => [],
        transferFunction: (tf) => scaleColors(tf, 0.55),
      };
  }
}

/** Renderer parameters that depend on the data, used while `renderer-params` is unset (iso: one surface at the automatic function's isovalue). */
export function defaultRendererParams(renderer: string, tf: TransferFunction | null): Record<string, unknown> {
  if (renderer === 'iso' && tf?.dimensions === '1d' && tf.points.length >= 2) {
    // Halfway between where the automatic function starts (the median of the foreground)
    // and its 90th percentile: the outer surface of the object rather than its densest core.
    const value = (tf.points[0].value + tf.points[1].value) / 2;
    return {
      surfaces: [{ value: Math.round(value * 1000) / 1000, color: [0.92, 0.88, 0.8], opacity: 1 }],
      specular: 0.15,
      shininess: 30,
    };
  }
  return {};
}
