import { VptError } from '../errors.js';
import { FLOAT32_MAX } from '../validation/limits.js';
import { normalizationRange, type Volume } from './volume.js';

export interface WindowCoefficients {
  windowScale: number;
  windowOffset: number;
}

/** The smallest positive normal float32 (2⁻¹²⁶): a scale below it would reach the kernel as 0 (or a denormal). */
const FLOAT32_MIN_NORMAL = 2 ** -126;

/**
 * The window in data units as an affine map of the kernel's unclamped normalized value
 * n = texel · valueScale + valueOffset = (data − lo) / (hi − lo) (the volume's value range
 * [lo, hi], core's volumeValueMapping): windowed = clamp(n · windowScale + windowOffset, 0, 1)
 * = clamp((data − (center − width/2)) / width, 0, 1). Composed here in float64, so the kernel
 * adds one multiply-add to the value mapping every renderer shares, and the value range
 * (which only normalizes) leaves a window in HU unchanged. Without a window: the normalized
 * value itself (scale 1, offset 0).
 */
export function windowCoefficients(
  range: readonly [number, number],
  window: readonly [number, number] | null,
): WindowCoefficients {
  if (!window) return { windowScale: 1, windowOffset: 0 };
  const [lo, hi] = range;
  const [center, width] = window;
  return { windowScale: (hi - lo) / width, windowOffset: (lo - (center - width / 2)) / width };
}

/**
 * windowCoefficients, refused (VptError 'invalid-scene' naming the field) unless the scale
 * is a normal float32 and the offset finite in float32: a window far narrower than the value
 * range would reach the kernel as Infinity (and Infinity − Infinity is NaN), a far wider one as a
 * scale of 0 (and 0 · Infinity is NaN). With a normal scale and a finite offset the windowed value
 * is finite or ±Infinity before the clamp, so it always lands in [0, 1].
 */
export function checkedWindowCoefficients(
  range: readonly [number, number],
  window: readonly [number, number] | null,
  field = 'SLICE.window',
): WindowCoefficients {
  const m = windowCoefficients(range, window);
  const scale = Math.abs(m.windowScale);
  if (!(scale >= FLOAT32_MIN_NORMAL && scale <= FLOAT32_MAX && Math.abs(m.windowOffset) <= FLOAT32_MAX)) {
    throw new VptError(
      'invalid-scene',
      `${field}: [${window}] against the volume's value range [${range[0]}, ${range[1]}] needs a scale of ${m.windowScale} and an offset of ${m.windowOffset}, outside the float32 range (±${FLOAT32_MIN_NORMAL} to ±${FLOAT32_MAX}) the GPU computes in`,
    );
  }
  return m;
}

/** windowCoefficients for a volume's value range (core's normalizationRange). */
export function windowMapping(volume: Volume, window: readonly [number, number] | null): WindowCoefficients {
  return windowCoefficients(volumeRange(volume), window);
}

// normalizationRange scans an int16/float32 volume without a valueRange; paramValues runs every iteration.
const ranges = new WeakMap<Volume, { valueRange: Volume['valueRange']; range: [number, number] }>();

/** The volume's value range [lo, hi] (normalizationRange), memoized per volume object and valueRange. */
export function volumeRange(volume: Volume): [number, number] {
  const memo = ranges.get(volume);
  if (memo && memo.valueRange === volume.valueRange) return memo.range;
  const range = normalizationRange(volume);
  ranges.set(volume, { valueRange: volume.valueRange, range });
  return range;
}
