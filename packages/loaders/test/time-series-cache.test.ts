import { describe, expect, it } from 'vitest';
import { VptError, type TimeSeriesSource, type Volume } from '@vpt/core';
import { TimeSeriesCache } from '../src/index.js';

/** A series of `steps` 4×4×4 float32 volumes whose voxels all hold the step index; counts reads. */
function series(
  steps: number,
  side = 4,
): TimeSeriesSource & { reads: number[]; inFlight: number; maxInFlight: number } {
  const s = {
    steps,
    reads: [] as number[],
    inFlight: 0,
    maxInFlight: 0,
    async loadStep(i: number): Promise<Volume> {
      s.reads.push(i);
      s.inFlight++;
      s.maxInFlight = Math.max(s.maxInFlight, s.inFlight);
      await new Promise((r) => setTimeout(r, 1));
      s.inFlight--;
      return {
        dims: [side, side, side],
        spacing: [1, 1, 1],
        type: 'float32',
        data: new Float32Array(side ** 3).fill(i),
      };
    },
  };
  return s;
}

const STEP = 4 * 4 * 4 * 4; // bytes of one step

describe('TimeSeriesCache', () => {
  it('returns each step with its own voxels', async () => {
    const cache = new TimeSeriesCache(series(5), { budgetBytes: 10 * STEP });
    for (const i of [3, 0, 4]) expect((await cache.get(i)).data[7]).toBe(i);
  });

  it('reads the next steps ahead within the budget and holds at most the budget', async () => {
    const src = series(10);
    const cache = new TimeSeriesCache(src, { budgetBytes: 3 * STEP, prefetch: 4 });
    let peak = 0;
    const probe = setInterval(() => (peak = Math.max(peak, cache.bytesHeld())), 0);
    await cache.get(2);
    await cache.whenPrefetched();
    // 3 steps fit: the one on display and the next two.
    expect(cache.residentSteps()).toEqual([2, 3, 4]);
    expect(cache.bytesHeld()).toBeLessThanOrEqual(3 * STEP);
    // Playing on: step 3 is resident (no new read for it), and the read-ahead moves to 4, 5.
    const before = src.reads.length;
    await cache.get(3);
    expect(src.reads.slice(before, before + 1)).not.toContain(3);
    await cache.whenPrefetched();
    expect(cache.residentSteps()).toEqual([3, 4, 5]);
    clearInterval(probe);
    expect(peak).toBeLessThanOrEqual(3 * STEP);
    // One read at a time in the background.
    expect(src.maxInFlight).toBe(1);
    // Every step read once so far.
    expect(new Set(src.reads).size).toBe(src.reads.length);
  });

  it('wraps around at the end (playback loops) and reads backwards when told', async () => {
    const cache = new TimeSeriesCache(series(4), { budgetBytes: 3 * STEP, prefetch: 2 });
    await cache.get(3);
    await cache.whenPrefetched();
    expect(cache.residentSteps()).toEqual([0, 1, 3]);
    cache.setDirection(-1);
    await cache.get(1);
    await cache.whenPrefetched();
    expect(cache.residentSteps()).toEqual([0, 1, 3]);
  });

  it('holds only the step asked for when the budget is smaller than one step', async () => {
    const src = series(4);
    const cache = new TimeSeriesCache(src, { budgetBytes: STEP / 2 });
    await cache.get(1);
    await cache.whenPrefetched();
    expect(cache.residentSteps()).toEqual([1]);
    await cache.get(2);
    await cache.whenPrefetched();
    expect(cache.residentSteps()).toEqual([2]);
    expect(src.reads).toEqual([1, 2]);
  });

  it('refuses a step outside the series and a step of another grid, naming them', async () => {
    const cache = new TimeSeriesCache(series(3), { budgetBytes: 10 * STEP, prefetch: 0 });
    await expect(cache.get(3)).rejects.toThrow(/time step 3 does not exist: the series has 3 steps \(0 to 2\)/);
    await expect(cache.get(-1)).rejects.toBeInstanceOf(VptError);
    const mixed: TimeSeriesSource = {
      steps: 2,
      loadStep: async (i) => ({
        dims: [4, 4, 4 + i],
        spacing: [1, 1, 1],
        type: 'uint8',
        data: new Uint8Array(16 * (4 + i)),
      }),
    };
    const c2 = new TimeSeriesCache(mixed, { budgetBytes: 1e6, prefetch: 0 });
    await c2.get(0);
    await expect(c2.get(1)).rejects.toThrow(/time step 1 is 4×4×5 uint8, unlike the series' 4×4×4 uint8/);
    expect(() => new TimeSeriesCache(mixed, { budgetBytes: NaN })).toThrow(/budgetBytes/);
  });
});
