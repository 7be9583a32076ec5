import { describe, expect, it } from 'vitest';
import { validateGradientAtlasForDevice } from '../src/validation/device.js';
import { thrownVptError as thrown } from '../../../tests/helpers/test-scene.js';

describe("the gradient volume's slice atlas against the device's 2D limit", () => {
  // The atlas holds nz slices of nx × ny texels, so its area is at least nx·ny·nz: for 64³
  // (2^18 texels) one side is at least 512, whatever the layout.
  it('refuses an atlas that cannot fit (limit-exceeded, naming the limit)', () => {
    for (const max of [64, 511]) {
      const e = thrown(() => validateGradientAtlasForDevice([64, 64, 64], { maxTextureDimension2D: max }));
      expect(e.code).toBe('limit-exceeded');
      expect(e.message).toMatch(/\[64, 64, 64\].*maxTextureDimension2D/);
    }
  });
  it('accepts it within a large limit', () => {
    expect(() => validateGradientAtlasForDevice([64, 64, 64], { maxTextureDimension2D: 8192 })).not.toThrow();
  });
});
