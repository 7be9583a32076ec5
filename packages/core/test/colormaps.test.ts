import { describe, expect, it } from 'vitest';
import { colormapTable } from '../src/scene/colormaps.js';

describe('colour map tables', () => {
  it("viridis is matplotlib's 256-entry table (spot entries of _cm_listed.py) within 1e-5", () => {
    const t = colormapTable('viridis');
    expect(t.length).toBe(256 * 4);
    // Entries 0, 128 and 255 of matplotlib's _viridis_data.
    const spots: [number, number[]][] = [
      [0, [0.267004, 0.004874, 0.329415]],
      [128, [0.127568, 0.566949, 0.550556]],
      [255, [0.993248, 0.906157, 0.143936]],
    ];
    for (const [i, rgb] of spots) {
      for (let c = 0; c < 3; c++) expect(Math.abs(t[4 * i + c]! - rgb[c]!)).toBeLessThan(1e-5);
      expect(t[4 * i + 3]).toBe(1);
    }
    // Smooth and monotone in lightness proxy (green rises over the whole map).
    for (let i = 1; i < 256; i++) expect(t[4 * i + 1]!).toBeGreaterThan(t[4 * (i - 1) + 1]!);
  });
});
