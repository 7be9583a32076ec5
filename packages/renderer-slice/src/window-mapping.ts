import { FLOAT32_MAX, normalizationRange, VptError, type Volume } from '@vpt/core';

/**
 * The window in data units as an affine map of the kernel's unclamped normalized value
 * n = texel · valueScale + valueOffset = (data − lo) / (hi − lo) (the volume's value range
 * [lo, hi], core's volumeValueMapping): windowed = clamp(n · windowScale + windowOffset, 0, 1)
 * = clamp((data − (center − width/2)) / width, 0, 1). Composed here in float64, so the kernel
 * adds one multiply-add to the value mapping every renderer shares, and the value range
 * (which only normalizes) leaves a window in HU unchanged. Without a window: the normalized
 * value itself (scale 1, offset 0).
 */
export function windowMapping(
  volume: Volume,
  window: readonly [number, number] | null,
): { windowScale: number; windowOffset: number } {
  if (!window) return { windowScale: 1, windowOffset: 0 };
  const [lo, hi] = rangeOf(volume);
  const [center, width] = window;
  return { windowScale: (hi - lo) / width, windowOffset: (lo - (center - width / 2)) / width };
}

/**
 * windowMapping, refused (VptError 'invalid-scene' naming SLICE.window) when a coefficient is
 * not finite in float32: a window far narrower than the value range would reach the kernel as
 * Infinity, and Infinity − Infinity is NaN. With finite, non-zero coefficients the windowed
 * value is finite or ±Infinity before the clamp, so it always lands in [0, 1].
 */
export function checkedWindowMapping(
  volume: Volume,
  window: readonly [number, number] | null,
): { windowScale: number; windowOffset: number } {
  const m = windowMapping(volume, window);
  if (!(Math.abs(m.windowScale) <= FLOAT32_MAX && Math.abs(m.windowOffset) <= FLOAT32_MAX)) {
    const [lo, hi] = rangeOf(volume);
    throw new VptError(
      'invalid-scene',
      `SLICE.window: [${window}] against the volume's value range [${lo}, ${hi}] needs a scale of ${m.windowScale} and an offset of ${m.windowOffset}, beyond the float32 range (±${FLOAT32_MAX}) the GPU computes in; widen the window`,
    );
  }
  return m;
}

// normalizationRange scans an int16/float32 volume without a valueRange; paramValues runs every iteration.
const ranges = new WeakMap<Volume, { valueRange: Volume['valueRange']; range: [number, number] }>();
function rangeOf(volume: Volume): [number, number] {
  const memo = ranges.get(volume);
  if (memo && memo.valueRange === volume.valueRange) return memo.range;
  const range = normalizationRange(volume);
  ranges.set(volume, { valueRange: volume.valueRange, range });
  return range;
}
