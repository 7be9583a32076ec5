import { describe, expect, it } from 'vitest';
import {
  DIRECT_STEP_MS,
  FIRST_IMAGE_MS,
  finestFittingLevel,
  isProgressiveSource,
  refinementPlan,
  sourceAtLevel,
  type Dims,
} from '../src/loading/multiscale.js';

const LEVELS: Dims[] = [
  [1024, 1024, 512],
  [512, 512, 256],
  [256, 256, 128],
  [128, 128, 64],
  [64, 64, 32],
];
const count = (d: Dims) => d[0] * d[1] * d[2];

describe('multiscale loading plan', () => {
  it('knows which sources it refines, and names a level in the fragment keeping channel and time', () => {
    expect(isProgressiveSource('https://x.test/a.ome.zarr')).toBe(true);
    expect(isProgressiveSource('https://x.test/a.zarr/#channel=1')).toBe(true);
    expect(isProgressiveSource('https://x.test/a.zarr#level=0')).toBe(false);
    expect(isProgressiveSource('https://x.test/a.json')).toBe(false);
    expect(sourceAtLevel('a.zarr', 2)).toBe('a.zarr#level=2');
    expect(sourceAtLevel('a.zarr#channel=1&time=3', 'coarsest')).toBe('a.zarr#channel=1&time=3&level=coarsest');
  });

  it('the target is the finest level that fits the budget and the 3D texture limit as it is', () => {
    expect(finestFittingLevel(LEVELS, 1, count(LEVELS[0]), 2048)).toBe(0);
    expect(finestFittingLevel(LEVELS, 1, count(LEVELS[0]) - 1, 2048)).toBe(1);
    expect(finestFittingLevel(LEVELS, 2, count(LEVELS[1]) * 2, 2048)).toBe(1);
    expect(finestFittingLevel(LEVELS, 1, 1e12, 1000)).toBe(1); // 1024 > maxTextureDimension3D
    expect(finestFittingLevel(LEVELS, 4, 10, 2048)).toBe(4); // nothing fits: the coarsest
  });

  it('goes straight to the target when it loads quickly, else through the finest level expected within the first-image time', () => {
    // Fast: the target (level 0) in well under DIRECT_STEP_MS.
    expect(refinementPlan(LEVELS, 0, count(LEVELS[0]) / (DIRECT_STEP_MS / 2))).toEqual([0]);
    // Slow: level 2 is the finest expected within FIRST_IMAGE_MS at this rate.
    const rate = count(LEVELS[2]) / FIRST_IMAGE_MS;
    expect(refinementPlan(LEVELS, 0, rate)).toEqual([2, 0]);
    // Already at the coarsest: nothing more to load.
    expect(refinementPlan(LEVELS, 4, rate)).toEqual([]);
    // Very slow: no level between qualifies, so the target follows the coarsest directly.
    expect(refinementPlan(LEVELS, 0, 1)).toEqual([0]);
  });
});
