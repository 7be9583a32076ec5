import { describe, expect, it } from 'vitest';
import { createProceduralVolume, createVolume, gradientMagnitudes, volumeBox } from '@vpt/core';
import { fitCamera } from '../src/camera-fit.js';
import { hexToLinear, linearToHex, linearToSrgb, srgbToLinear } from '../src/color.js';
import { encodePfm } from '../src/export.js';
import { gradientSamples, valueGradientHistogram, valueHistogram } from '../src/histogram.js';

describe('colour conversions', () => {
  it('sRGB encode/decode are inverse, and a colour above 1 keeps its hue and intensity', () => {
    for (const x of [0, 0.001, 0.2, 0.5, 1]) expect(srgbToLinear(linearToSrgb(x))).toBeCloseTo(x, 6);
    expect(linearToHex([1, 0.5, 0])).toBe('#ffbc00');
    const c = hexToLinear(linearToHex([3, 1.5, 0]), 3);
    expect(c[0]).toBeCloseTo(3, 3);
    expect(Math.abs(c[1] - 1.5)).toBeLessThan(3 * 0.004); // 8-bit hex: one step is ~0.4 % of the intensity
    expect(c[2]).toBe(0);
  });
});

describe('PFM export', () => {
  it('writes the header and RGB floats bottom row first', () => {
    const rgba = new Float32Array([1, 2, 3, 9, 4, 5, 6, 9, 7, 8, 9, 9, 10, 11, 12, 9]); // 2 x 2, top row first
    const pfm = encodePfm(rgba, 2, 2);
    const header = 'PF\n2 2\n-1.0\n';
    expect(new TextDecoder().decode(pfm.slice(0, header.length))).toBe(header);
    const floats = new Float32Array(pfm.slice(header.length).buffer);
    expect(Array.from(floats)).toEqual([7, 8, 9, 10, 11, 12, 1, 2, 3, 4, 5, 6]);
  });
});

describe('histograms', () => {
  it('counts normalized values per bin', () => {
    const v = createVolume([4, 1, 1], 'uint8', Uint8Array.from([0, 255, 255, 128]));
    const h = valueHistogram(v, 4);
    expect(Array.from(h.bins)).toEqual([1, 0, 1, 2]);
    expect(h.max).toBe(1); // the largest bin set aside
  });

  it("gradient samples equal core's gradient magnitudes, and the 2D histogram bins them on [0, gradientMax]", () => {
    const v = createProceduralVolume('blob', 12);
    const s = gradientSamples(v);
    const g = gradientMagnitudes(v);
    expect(Array.from(s.gradients)).toEqual(Array.from(g));
    expect(s.maxGradient).toBe(Math.max(...g));
    const h = valueGradientHistogram(s, s.maxGradient, 8, 4);
    expect(h.bins.reduce((a, b) => a + b, 0)).toBe(12 ** 3);
    // With half the range, everything above it lands in the top row.
    const half = valueGradientHistogram(s, s.maxGradient / 2, 8, 4);
    let above = 0;
    for (const x of g) if (x >= s.maxGradient / 2) above++;
    let top = 0;
    for (let i = 0; i < 8; i++) top += half.bins[i + 8 * 3];
    expect(top).toBeGreaterThanOrEqual(above);
  });
});

describe('automatic camera', () => {
  it('frames the whole box: every corner projects inside the vertical and horizontal field of view', () => {
    const v = { dims: [128, 64, 32] as [number, number, number], spacing: [1, 1, 2] as [number, number, number] };
    const c = fitCamera(v, 0.7);
    const { min, max } = volumeBox(v);
    const f = c.position.map((p) => -p);
    const fl = Math.hypot(...f);
    const fwd = f.map((x) => x / fl);
    for (const x of [min[0], max[0]])
      for (const y of [min[1], max[1]])
        for (const z of [min[2], max[2]]) {
          const d = [x - c.position[0], y - c.position[1], z - c.position[2]];
          const along = d[0] * fwd[0] + d[1] * fwd[1] + d[2] * fwd[2];
          const off = Math.sqrt(Math.max(0, d[0] ** 2 + d[1] ** 2 + d[2] ** 2 - along ** 2));
          expect(Math.atan2(off, along)).toBeLessThan(0.35); // half of fovy, in any direction (square view)
        }
  });
});
