/**
 * What <vpt-viewer> shows when only `src` is set: a transfer function fitted to the data's
 * histogram, and per renderer a density, an environment and lights that contrast with it
 * (a warm, emissive or lit volume against a dark background). Each applies only while
 * its attribute is unset; environment and lights are one choice (either set: neither default).
 */
import {
  DEFAULT_RENDERER_NAME,
  type Camera,
  type ChannelSettings,
  type Environment,
  type Light,
  type RendererLookDefaults,
  type TransferFunction,
  type Volume,
} from '@vpt/core';
import { rendererEntry } from './renderer-registry.js';
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

/**
 * The default look of a renderer: its descriptor's (core's RendererLookDefaults), else the
 * default renderer's (emission–absorption), else an unlit black sky.
 */
export function rendererLook(renderer: string): RendererLook {
  const look =
    rendererEntry(renderer)?.descriptor?.look ?? rendererEntry(DEFAULT_RENDERER_NAME)?.descriptor?.look ?? BLACK_LOOK;
  const [r, g, b] = look.environment;
  const key = look.keyLight;
  const adapt = look.transferFunction ?? 'as-is';
  return {
    densityScale: look.densityScale,
    environment: dark(r, g, b),
    lights: key ? (c) => keyLight(c, [key[0], key[1], key[2]]) : () => [],
    transferFunction:
      adapt === 'albedo' ? asAlbedo : adapt === 'as-is' ? (tf) => tf : (tf) => scaleColors(tf, adapt.scaleColors),
  };
}

const BLACK_LOOK: RendererLookDefaults = { densityScale: 20, environment: [0, 0, 0] };

/**
 * Renderer parameters that depend on the data, used while `renderer-params` is unset (the
 * descriptor's look.params; iso: one surface at the automatic function's isovalue, or with
 * `channels`, the drawn channels of a multichannel volume, one surface per channel).
 */
export function defaultRendererParams(
  renderer: string,
  tf: TransferFunction | null,
  channels?: readonly ChannelSettings[],
): Record<string, unknown> {
  return rendererEntry(renderer)?.descriptor?.look?.params?.(tf, channels) ?? {};
}
