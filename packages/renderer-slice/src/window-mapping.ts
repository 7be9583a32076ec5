import { normalizationRange, type Volume } from '@vpt/core';

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

// normalizationRange scans an int16/float32 volume without a valueRange; paramValues runs every iteration.
const ranges = new WeakMap<Volume, { valueRange: Volume['valueRange']; range: [number, number] }>();
function rangeOf(volume: Volume): [number, number] {
  const memo = ranges.get(volume);
  if (memo && memo.valueRange === volume.valueRange) return memo.range;
  const range = normalizationRange(volume);
  ranges.set(volume, { valueRange: volume.valueRange, range });
  return range;
}
