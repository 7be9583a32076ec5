import { describe, expect, it } from 'vitest';
import { AdaptiveResolution } from '../src/adaptive-resolution.js';
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
