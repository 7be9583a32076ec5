import { describe, expect, it } from 'vitest';
import { tf1d } from '../../../tests/helpers/test-scene.js';
import {
  createVolume,
  rasterizeTransferFunction,
  reference,
  TF_RESOLUTION,
  type TransferFunction,
  type Vec3,
  type Volume,
} from '@vpt/core';
import { seededRandom as rng } from '../../../tests/helpers/seeded-random.js';
import {
  buildMajorantGrid,
  cellVoxelRange,
  computeCellValueRanges,
  gridCells,
  volumeCellRanges,
} from '../src/index.js';

/** The kernel's opacity lookup (linear between texels at coordinate v·(N−1)), in float64. */
function opacityAt(tf: Float32Array, v: number, width = TF_RESOLUTION, row = 0): number {
  const x = Math.min(1, Math.max(0, v)) * (width - 1);
  const i0 = Math.floor(x),
    i1 = Math.min(i0 + 1, width - 1);
  const a = tf[4 * (row * width + i0) + 3],
    b = tf[4 * (row * width + i1) + 3];
  return a + (b - a) * (x - i0);
}

/**
 * For random points of every cell (uniform inside, plus points on the cell's faces), σ_t as
 * the kernel computes it (cell-centred trilinear value → linear TF lookup → × densityScale)
 * must lie within the cell's [minorant, majorant]. Also returns how often σ exceeds a naive
 * bound taken from the cell's own voxels only, to show the test can catch that mistake.
 */
function checkBounds(
  volume: Volume,
  tf: TransferFunction,
  densityScale: number,
  cellSize: number,
  pointsPerCell: number,
  seed: number,
) {
  const tfTexels = rasterizeTransferFunction(tf, TF_RESOLUTION);
  const ranges = volumeCellRanges(volume, cellSize);
  const grid = buildMajorantGrid(ranges, tfTexels, densityScale);
  const sampler = new reference.CpuVolumeSampler({ volume });
  const [gx, gy, gz] = grid.cells;
  const { min: bmin, size } = sampler.box;
  const rand = rng(seed);
  let violations = 0,
    naiveViolations = 0,
    checked = 0;
  const rows = tfTexels.length / (4 * TF_RESOLUTION);
  for (let cz = 0; cz < gz; cz++)
    for (let cy = 0; cy < gy; cy++)
      for (let cx = 0; cx < gx; cx++) {
        const c = cx + gx * (cy + gy * cz);
        const maj = grid.data[4 * c],
          min = grid.data[4 * c + 1];
        // Naive: voxels whose centres lie inside the cell, no border.
        let naive = 0;
        const vr = [cx, cy, cz].map((k, a) => [
          Math.ceil((k * volume.dims[a]) / [gx, gy, gz][a] - 0.5),
          Math.floor(((k + 1) * volume.dims[a]) / [gx, gy, gz][a] - 0.5),
        ]);
        const norm = sampler.data;
        for (let z = Math.max(0, vr[2][0]); z <= Math.min(volume.dims[2] - 1, vr[2][1]); z++)
          for (let y = Math.max(0, vr[1][0]); y <= Math.min(volume.dims[1] - 1, vr[1][1]); y++)
            for (let x = Math.max(0, vr[0][0]); x <= Math.min(volume.dims[0] - 1, vr[0][1]); x++) {
              const v = norm[x + volume.dims[0] * (y + volume.dims[1] * z)];
              for (let r = 0; r < rows; r++)
                naive = Math.max(naive, densityScale * opacityAt(tfTexels, v, TF_RESOLUTION, r));
            }
        for (let k = 0; k < pointsPerCell; k++) {
          const f = [rand(), rand(), rand()];
          if (k % 4 === 0) f[k % 3] = k % 8 === 0 ? 0 : 1; // on a face
          const p = [0, 1, 2].map((a) => bmin[a] + (size[a] * ([cx, cy, cz][a] + f[a])) / [gx, gy, gz][a]) as Vec3;
          const v = sampler.sample(p);
          for (let r = 0; r < rows; r++) {
            const sigma = densityScale * opacityAt(tfTexels, v, TF_RESOLUTION, r);
            checked++;
            if (sigma > maj || sigma < min) violations++;
            if (sigma > naive * (1 + 1e-5)) naiveViolations++;
          }
        }
      }
  return { violations, naiveViolations, checked, grid };
}

/** TF whose opacity has a narrow peak at 0.5 and is ~0 at both ends: range max must find the peak. */
const PEAK_TF = tf1d(
  [0, [1, 1, 1], 0.02],
  [0.48, [1, 1, 1], 0.02],
  [0.5, [1, 0.5, 0.2], 1],
  [0.52, [1, 1, 1], 0.02],
  [1, [1, 1, 1], 0.05],
);

describe('majorant grid', () => {
  it('cell voxel ranges cover the trilinear footprint with a one-voxel border', () => {
    // 16 voxels, 4 cells: cell 1 covers voxel coordinates 4..8, so points blend voxels 3..8; plus margin 2..9.
    expect(cellVoxelRange(1, 4, 16)).toEqual([2, 9]);
    expect(cellVoxelRange(0, 4, 16)).toEqual([0, 5]);
    expect(cellVoxelRange(3, 4, 16)).toEqual([10, 15]);
    expect(gridCells([128, 128, 84], 8)).toEqual([16, 16, 11]);
    expect(gridCells([2000, 3, 8], 8)).toEqual([64, 1, 1]);
  });

  it('is a true upper and lower bound of σ_t on random spiky volumes with a peaked TF', () => {
    const rand = rng(3);
    const dims: [number, number, number] = [23, 17, 29];
    const data = new Float32Array(dims[0] * dims[1] * dims[2]);
    // Mostly 0 or 1 (so a cell's endpoints miss the TF peak at 0.5), with isolated spikes.
    for (let i = 0; i < data.length; i++) data[i] = rand() < 0.9 ? (rand() < 0.5 ? 0 : 1) : rand();
    const volume = createVolume(dims, 'float32', data, [1, 1.3, 0.8]);
    volume.valueRange = [0, 1];
    for (const cellSize of [3, 8]) {
      const r = checkBounds(volume, PEAK_TF, 37, cellSize, 400, 11 + cellSize);
      expect(r.checked).toBeGreaterThan(10000);
      expect(r.violations).toBe(0);
    }
  });

  it('is a true bound on smooth data whose cells have narrow value ranges (rising and falling ramps, both borders matter)', () => {
    // On a smooth field a cell's own voxels span a narrow range, so points near either face,
    // which blend in the neighbour cell's voxels, exceed it: a dropped upper or lower border
    // shows at once. Ramps rising and falling along each axis, plus a gentle wave.
    const dims: [number, number, number] = [19, 14, 17];
    const tf = tf1d([0, [1, 1, 1], 0], [1, [1, 1, 1], 1]);
    for (const sign of [1, -1]) {
      const data = new Float32Array(dims[0] * dims[1] * dims[2]);
      for (let z = 0; z < dims[2]; z++)
        for (let y = 0; y < dims[1]; y++)
          for (let x = 0; x < dims[0]; x++) {
            const ramp = (x / dims[0] + y / dims[1] + z / dims[2]) / 3;
            data[x + dims[0] * (y + dims[1] * z)] =
              0.5 + sign * (ramp - 0.5) * 0.9 + 0.04 * Math.sin(0.7 * x + 0.3 * y);
          }
      const volume = createVolume(dims, 'float32', data);
      volume.valueRange = [0, 1];
      for (const cellSize of [2, 3, 5]) {
        const r = checkBounds(volume, tf, 20, cellSize, 150, 31 + cellSize);
        expect(r.checked).toBeGreaterThan(5000);
        expect(r.violations, `sign ${sign}, cell size ${cellSize}`).toBe(0);
        // The naive bound fails here, so this data does exercise the borders.
        expect(r.naiveViolations, `sign ${sign}, cell size ${cellSize}`).toBeGreaterThan(0);
      }
    }
  });

  // A single bright voxel next to empty cells: points of the neighbour cell blend it in.
  // Voxel 7 sits at the top of cell 0 (voxels 0..7), so cell 1 needs it through its lower
  // border; voxel 8 sits at the bottom of cell 1, so cell 0 needs it through its upper border.
  it.each([
    ['low side of the cell boundary (cell 1 needs its lower border)', 7],
    ['high side of the cell boundary (cell 0 needs its upper border)', 8],
  ])(
    'needs the one-voxel border: bright voxel on the %s; a naive bound from the cell’s own voxels is violated',
    (_side, at) => {
      const dims: [number, number, number] = [16, 16, 16];
      const data = new Float32Array(16 ** 3);
      data[at + 16 * (at + 16 * at)] = 1;
      const volume = createVolume(dims, 'float32', data);
      volume.valueRange = [0, 1];
      const tf = tf1d([0, [1, 1, 1], 0], [1, [1, 1, 1], 1]);
      const r = checkBounds(volume, tf, 10, 8, 2000, 5);
      expect(r.violations).toBe(0);
      expect(r.naiveViolations).toBeGreaterThan(0);
      // Every one of the 8 cells touches the bright voxel's trilinear footprint, so none may be empty.
      for (let c = 0; c < 8; c++) expect(r.grid.data[4 * c], `cell ${c}`).toBeGreaterThan(0);
    },
  );

  it('bounds a 2D (value × gradient) transfer function over every gradient row', () => {
    const rand = rng(9);
    const dims: [number, number, number] = [12, 12, 12];
    const data = new Float32Array(12 ** 3).map(() => rand());
    const volume = createVolume(dims, 'float32', data);
    volume.valueRange = [0, 1];
    const tf = {
      dimensions: '2d',
      widgets: [{ type: 'gaussian', center: [0.5, 0.8], width: [0.05, 0.05], color: [1, 1, 1], opacity: 2 }],
    } as unknown as TransferFunction;
    const texels = rasterizeTransferFunction(tf, TF_RESOLUTION);
    const rows = texels.length / (4 * TF_RESOLUTION);
    expect(rows).toBeGreaterThan(1); // really a 2D table: every row must be bounded
    const r = checkBounds(volume, tf, 5, 4, 100, 2);
    expect(r.checked).toBe(27 * 100 * rows);
    expect(r.violations).toBe(0);
  });

  it('is zero in empty space (so empty cells cost one DDA step) and scales with the density', () => {
    const dims: [number, number, number] = [32, 32, 32];
    const data = new Float32Array(32 ** 3);
    for (let z = 12; z < 20; z++)
      for (let y = 12; y < 20; y++) for (let x = 12; x < 20; x++) data[x + 32 * (y + 32 * z)] = 1;
    const volume = createVolume(dims, 'float32', data);
    volume.valueRange = [0, 1];
    const tf = rasterizeTransferFunction({
      dimensions: '1d',
      points: [
        { value: 0, color: [1, 1, 1], opacity: 0 },
        { value: 1, color: [1, 1, 1], opacity: 1 },
      ],
    });
    const ranges = computeCellValueRanges(data, dims, gridCells(dims, 8));
    const g1 = buildMajorantGrid(ranges, tf, 1);
    const g50 = buildMajorantGrid(ranges, tf, 50);
    let empty = 0;
    for (let c = 0; c < 64; c++) {
      if (g1.data[4 * c] === 0) empty++;
      expect(g50.data[4 * c]).toBeCloseTo(50 * g1.data[4 * c], 3);
    }
    // The 8³ block sits in the 8 centre cells (voxels 12..19 touch cells 1 and 2 per axis).
    expect(empty).toBe(64 - 8);
    expect(g50.globalMajorant).toBeGreaterThanOrEqual(50);
    expect(g50.globalMinorant).toBe(0);
  });

  it('caches the volume-dependent ranges per volume object', () => {
    const volume = createVolume([8, 8, 8], 'float32', new Float32Array(512).fill(0.5));
    expect(volumeCellRanges(volume, 4)).toBe(volumeCellRanges(volume, 4));
    expect(volumeCellRanges(volume, 2)).not.toBe(volumeCellRanges(volume, 4));
  });
});
