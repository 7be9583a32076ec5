import { describe, expect, it } from 'vitest';
import { AdaptiveResolution, INTERACTION_BUDGET_MS, MIN_SHRINK } from '../src/adaptive-resolution.js';
import { maxRenderPixels } from '../../core/src/context/volume-fit.js';

// Issue 28: a 3000 px element at resolution-scale 4 asked WebGPU for 12000² render targets.
function sizer(cssWidth: number, cssHeight: number, resolutionScale: number) {
  const host = { resolutionScale, addController() {}, removeController() {}, requestUpdate() {} } as never;
  const ar = new AdaptiveResolution(host, () => {});
  (ar as unknown as { cssSize: { width: number; height: number } }).cssSize = { width: cssWidth, height: cssHeight };
  return ar;
}

describe('AdaptiveResolution.renderSize and the memory budget', () => {
  it('clamps the pixel count to maxPixels, keeping the aspect', () => {
    const { width, height } = sizer(3000, 1500, 4).renderSize(8192, 4_000_000);
    expect(width * height).toBeLessThanOrEqual(4_000_000);
    expect(width * height).toBeGreaterThan(3_900_000);
    expect(width / height).toBeCloseTo(2, 2);
  });

  it('leaves a size within the budget as it is', () => {
    expect(sizer(300, 200, 1).renderSize(8192, 4_000_000)).toEqual({ width: 300, height: 200 });
  });

  it("core's maxRenderPixels keeps the render targets within half of maxGpuBytes", () => {
    const renderer = { frameFormats: ['rgba32float'], accumulationFormats: ['rgba32float'] } as never;
    const px = maxRenderPixels(1024 ** 3, renderer, 3, true);
    // 1 frame + 2 accumulations + HDR + 3 post steps + 2 guide frames + 6 guide accumulations, 16 bytes each, + the canvas.
    expect(px * (16 * 15 + 8)).toBeLessThanOrEqual(1024 ** 3 / 2);
    expect(px).toBeGreaterThan(2_000_000);
  });
});

describe('AdaptiveResolution while the camera moves', () => {
  // The side while moving after a frame of `ms` at full size (a 64² element).
  const movingSide = (ms: number) => {
    const ar = sizer(64, 64, 1);
    ar.recordIteration(ms);
    ar.interactionStarted();
    return ar.renderSize(8192).width;
  };

  it('shrinks the side by the square root of the budget over the frame cost', () => {
    expect(movingSide(4 * INTERACTION_BUDGET_MS)).toBe(32);
    expect(movingSide(INTERACTION_BUDGET_MS / (0.7 * 0.7))).toBe(Math.round(64 * 0.7));
    // Never below a quarter.
    expect(movingSide(100 * INTERACTION_BUDGET_MS)).toBe(16);
  });

  it('keeps full size where the shrink would be smaller than MIN_SHRINK (a few pixels short)', () => {
    expect(movingSide(INTERACTION_BUDGET_MS * 0.9)).toBe(64);
    // 0.89 of the side (57 of 64 px) would be asked by this cost: it stays 64.
    expect(movingSide(INTERACTION_BUDGET_MS / (0.89 * 0.89))).toBe(64);
    // Just past the threshold the shrink is made.
    const past = MIN_SHRINK - 0.02;
    expect(movingSide(INTERACTION_BUDGET_MS / (past * past))).toBe(Math.round(64 * past));
  });

  it('returns to full size once the interaction ends and settles', async () => {
    const ar = sizer(64, 64, 1);
    ar.recordIteration(4 * INTERACTION_BUDGET_MS);
    ar.interactionStarted();
    expect(ar.renderSize(8192).width).toBe(32);
    ar.interactionEnded();
    await new Promise((r) => setTimeout(r, 250));
    expect(ar.renderSize(8192).width).toBe(64);
  });
});
