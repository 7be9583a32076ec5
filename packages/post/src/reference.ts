/**
 * CPU references of the post steps in float64, one RGB triple at a time. They follow the
 * cited formulas directly (constants written as in the sources, e.g. 0.8 - 0.04), so tests
 * compare the f32 kernels against independent arithmetic rather than against a copy of it.
 */
import type { PostStep } from '@vpt/core';
import { EXPOSURE_OUTPUT_MAX, ExposureStep } from './exposure.js';
import { SrgbEncodeStep } from './srgb.js';
import { ToneMapStep } from './tone-mapping.js';
import { ACES_INPUT_MAX, type ToneMapOperator } from './tone-mapping-operators.js';

export type Rgb = readonly [number, number, number];
type MutableRgb = [number, number, number];

const map = (rgb: Rgb, f: (c: number) => number): MutableRgb => [f(rgb[0]), f(rgb[1]), f(rgb[2])];

/** color * 2^exposure, held within ±EXPOSURE_OUTPUT_MAX (white to every tone mapper). */
export function exposureRef(exposure: number, rgb: Rgb): MutableRgb {
  const s = 2 ** exposure;
  return map(rgb, (c) => Math.min(Math.max(c * s, -EXPOSURE_OUTPUT_MAX), EXPOSURE_OUTPUT_MAX));
}

/** Reinhard per channel, c / (1 + c) (Lesar, Bohak, Marolt 2018). */
export function reinhardRef(c: number): number {
  return c / (1 + c);
}

/** Narkowicz's ACES filmic fit (2016), saturated to [0, 1]. */
export function acesRef(c: number): number {
  const x = Math.min(c, ACES_INPUT_MAX); // output-neutral: the curve is already clamped to 1 there
  const y = (x * (2.51 * x + 0.03)) / (x * (2.43 * x + 0.59) + 0.14);
  return Math.min(Math.max(y, 0), 1);
}

/** Khronos PBR Neutral, as in its reference implementation (KhronosGroup/ToneMapping, PBR_Neutral). */
export function pbrNeutralRef(rgb: Rgb): MutableRgb {
  const startCompression = 0.8 - 0.04;
  const desaturation = 0.15;
  const x = Math.min(rgb[0], rgb[1], rgb[2]);
  const offset = x < 0.08 ? x - 6.25 * x * x : 0.04;
  const c = map(rgb, (v) => v - offset);
  const peak = Math.max(c[0], c[1], c[2]);
  if (peak < startCompression) return c;
  const d = 1 - startCompression;
  const newPeak = 1 - (d * d) / (peak + d - startCompression);
  const g = 1 - 1 / (desaturation * (peak - newPeak) + 1);
  return map(c, (v) => v * (newPeak / peak) * (1 - g) + newPeak * g);
}

/** Tone map one colour; negative input counts as 0, as in the kernel. */
export function toneMapRef(op: ToneMapOperator, rgb: Rgb): MutableRgb {
  const c = map(rgb, (v) => Math.max(v, 0));
  switch (op) {
    case 'clamp':
      return map(c, (v) => Math.min(v, 1));
    case 'reinhard':
      return map(c, reinhardRef);
    case 'aces':
      return map(c, acesRef);
    case 'pbr-neutral':
      return pbrNeutralRef(c);
  }
}

/** The sRGB OETF of IEC 61966-2-1 on one channel, clamped to [0, 1] first. */
export function srgbOetfRef(x: number): number {
  const c = Math.min(Math.max(x, 0), 1);
  return c <= 0.0031308 ? 12.92 * c : 1.055 * c ** (1 / 2.4) - 0.055;
}

export function srgbEncodeRef(rgb: Rgb): MutableRgb {
  return map(rgb, srgbOetfRef);
}

/** Apply one of this package's steps on the CPU. Throws for steps it does not know. */
export function postStepRef(step: PostStep, rgb: Rgb): MutableRgb {
  if (step instanceof ExposureStep) return exposureRef(step.exposure, rgb);
  if (step instanceof ToneMapStep) return toneMapRef(step.operator, rgb);
  if (step instanceof SrgbEncodeStep) return srgbEncodeRef(rgb);
  throw new Error(`no CPU reference for post step "${step.name}"`);
}

/** Apply a chain of steps on the CPU, in order. */
export function postChainRef(steps: readonly PostStep[], rgb: Rgb): MutableRgb {
  return steps.reduce<MutableRgb>((c, s) => postStepRef(s, c), [rgb[0], rgb[1], rgb[2]]);
}
