/**
 * The majorant grid: a coarse grid over the volume box holding, per cell, an upper bound
 * (majorant) and a lower bound (minorant, the control extinction of residual ratio
 * tracking) of the extinction σ_t(x) = densityScale · opacity(value(x)) that the kernel
 * computes anywhere inside the cell (pbrt-v4's GridMedium majorant grid; Szirmay-Kalos et
 * al. 2011, "Free path sampling in high resolution inhomogeneous participating media").
 *
 * The bound must be TRUE or delta tracking is biased, so it is built from what the kernel
 * really evaluates:
 *  - value(x) is cell-centred trilinear: a point of a cell blends the voxels whose centres
 *    lie within one voxel of the cell, so a cell's value range is [min, max] over the
 *    cell's voxels plus a one-voxel border (plus one more voxel of margin against
 *    float rounding of the kernel's positions);
 *  - opacity(v) is linear between the rasterized TF's texels, so its maximum over a value
 *    range [a, b] is the larger of its values at a and b and the texels strictly between
 *    (a range-max query, answered in O(1) from a sparse table), likewise the minimum; a 2D TF
 *    (value × gradient) is bounded over all gradient rows of those columns;
 *  - the result is padded by a relative 1e-5, far above the few float32 ulps by which
 *    the kernel's lerps can exceed their inputs.
 * The renderer builds the grid on the GPU (kernels/majorant-build.*: the same steps, the
 * value ranges exactly, the TF part in float32), the ranges once per volume and the bounds
 * on every transfer-function or density change. This CPU build is its reference in the
 * tests and gives the one global bound of `majorantGrid: false` (cached per Volume object).
 */
import { TF_RESOLUTION } from '../scene/transfer-function.js';
import { normalizedData, type Volume } from '../scene/volume.js';
import {
  enabledChannels,
  rasterizeChannelTransferFunctions,
  sceneChannelVolume,
  type ChannelSettings,
} from '../scene/channels.js';

export const MAX_GRID_CELLS_PER_AXIS = 64;
const PAD = 1e-5;

export interface CellValueRanges {
  cells: [number, number, number];
  /** Per cell, x fastest: min and max of the normalized voxel values the cell's points can blend. */
  vmin: Float32Array;
  vmax: Float32Array;
}

export interface MajorantGrid {
  cells: [number, number, number];
  /** RGBA per cell (x fastest): r = majorant, g = minorant of σ_t; b, a = 0. */
  data: Float32Array;
  /** Max / min over all cells: the bounds of the global-majorant mode. */
  globalMajorant: number;
  globalMinorant: number;
}

/** Cells per axis for a cell edge of `cellSize` voxels, between 1 and 64. */
export function gridCells(dims: readonly number[], cellSize: number): [number, number, number] {
  return dims.map((n) => Math.min(MAX_GRID_CELLS_PER_AXIS, Math.max(1, Math.ceil(n / cellSize)))) as [
    number,
    number,
    number,
  ];
}

/** Voxel index range [lo, hi] whose values can reach the points of cell c (of G) along an axis of N voxels. */
export function cellVoxelRange(c: number, G: number, N: number): [number, number] {
  // Texture coordinate [c/G, (c+1)/G] → voxel coordinate g = tc·N − 0.5; trilinear reads floor(g), floor(g)+1.
  const lo = Math.floor((c * N) / G - 0.5) - 1;
  const hi = Math.floor(((c + 1) * N) / G - 0.5) + 2;
  return [Math.max(0, lo), Math.min(N - 1, hi)];
}

/** Per-cell value ranges, by separable min/max passes along x, then y, then z. */
export function computeCellValueRanges(
  values: Float32Array,
  dims: readonly [number, number, number],
  cells: [number, number, number],
): CellValueRanges {
  const [nx, ny, nz] = dims;
  const [gx, gy, gz] = cells;
  const rx = Array.from({ length: gx }, (_, c) => cellVoxelRange(c, gx, nx));
  const ry = Array.from({ length: gy }, (_, c) => cellVoxelRange(c, gy, ny));
  const rz = Array.from({ length: gz }, (_, c) => cellVoxelRange(c, gz, nz));
  // Pass 1: along x → [gx, ny, nz]
  const ax = new Float32Array(gx * ny * nz),
    bx = new Float32Array(gx * ny * nz);
  for (let z = 0; z < nz; z++) {
    for (let y = 0; y < ny; y++) {
      const row = nx * (y + ny * z);
      for (let c = 0; c < gx; c++) {
        let lo = Infinity,
          hi = -Infinity;
        for (let x = rx[c][0]; x <= rx[c][1]; x++) {
          const v = values[row + x];
          if (v < lo) lo = v;
          if (v > hi) hi = v;
        }
        const o = c + gx * (y + ny * z);
        ax[o] = lo;
        bx[o] = hi;
      }
    }
  }
  // Pass 2: along y → [gx, gy, nz]
  const ay = new Float32Array(gx * gy * nz),
    by = new Float32Array(gx * gy * nz);
  for (let z = 0; z < nz; z++) {
    for (let cy = 0; cy < gy; cy++) {
      for (let cx = 0; cx < gx; cx++) {
        let lo = Infinity,
          hi = -Infinity;
        for (let y = ry[cy][0]; y <= ry[cy][1]; y++) {
          const o = cx + gx * (y + ny * z);
          if (ax[o] < lo) lo = ax[o];
          if (bx[o] > hi) hi = bx[o];
        }
        const o = cx + gx * (cy + gy * z);
        ay[o] = lo;
        by[o] = hi;
      }
    }
  }
  // Pass 3: along z → [gx, gy, gz]
  const vmin = new Float32Array(gx * gy * gz),
    vmax = new Float32Array(gx * gy * gz);
  for (let cz = 0; cz < gz; cz++) {
    for (let cy = 0; cy < gy; cy++) {
      for (let cx = 0; cx < gx; cx++) {
        let lo = Infinity,
          hi = -Infinity;
        for (let z = rz[cz][0]; z <= rz[cz][1]; z++) {
          const o = cx + gx * (cy + gy * z);
          if (ay[o] < lo) lo = ay[o];
          if (by[o] > hi) hi = by[o];
        }
        const o = cx + gx * (cy + gy * cz);
        vmin[o] = lo;
        vmax[o] = hi;
      }
    }
  }
  return { cells, vmin, vmax };
}

/**
 * Range-min/max queries over the opacity channel of a rasterized TF (sparse tables, O(1) per
 * query). `width` texels along the value axis; a 2D TF (value × gradient, `height` rows) is
 * first reduced to each column's max and min over all rows, so its bounds hold whatever the
 * gradient magnitude is.
 */
export class OpacityRangeTable {
  readonly size: number;
  private readonly maxT: Float64Array[] = [];
  private readonly minT: Float64Array[] = [];
  constructor(tfTexels: Float32Array, width = TF_RESOLUTION) {
    const n = width;
    const rows = Math.max(1, Math.floor(tfTexels.length / (4 * width)));
    this.size = n;
    const hi = new Float64Array(n).fill(-Infinity),
      lo = new Float64Array(n).fill(Infinity);
    for (let r = 0; r < rows; r++) {
      for (let i = 0; i < n; i++) {
        const a = tfTexels[4 * (r * n + i) + 3];
        if (a > hi[i]) hi[i] = a;
        if (a < lo[i]) lo[i] = a;
      }
    }
    this.maxT.push(hi);
    this.minT.push(lo);
    for (let k = 1; 1 << k <= n; k++) {
      const h = 1 << (k - 1);
      const pm = this.maxT[k - 1],
        pn = this.minT[k - 1];
      const m = new Float64Array(n - (1 << k) + 1),
        q = new Float64Array(n - (1 << k) + 1);
      for (let i = 0; i < m.length; i++) {
        m[i] = Math.max(pm[i], pm[i + h]);
        q[i] = Math.min(pn[i], pn[i + h]);
      }
      this.maxT.push(m);
      this.minT.push(q);
    }
  }
  /** [min, max] of the opacity texels i0..i1 (inclusive). */
  query(i0: number, i1: number): [number, number] {
    const k = 31 - Math.clz32(i1 - i0 + 1);
    const j = i1 - (1 << k) + 1;
    return [Math.min(this.minT[k][i0], this.minT[k][j]), Math.max(this.maxT[k][i0], this.maxT[k][j])];
  }
  /**
   * [min, max] opacity the kernel's linear TF lookup can return for any value in [a, b].
   * The lookup is piecewise linear in x = v·(N−1), so its extremes over an interval lie at
   * the interval's ends or at the texels strictly inside. The interval is widened by a
   * relative 1e-4, more than the float32 rounding by which the kernel's trilinear value
   * can leave [a, b] (zero when all blended voxels are equal, e.g. empty space).
   */
  valueRange(a: number, b: number): [number, number] {
    const n1 = this.size - 1;
    const clamp01 = (v: number) => Math.min(1, Math.max(0, v));
    const xa = clamp01(a) * n1 * (1 - 1e-4);
    const xb = Math.min(n1, clamp01(b) * n1 * (1 + 1e-4));
    let lo = Math.min(this.interp(this.minT[0], xa), this.interp(this.minT[0], xb));
    let hi = Math.max(this.interp(this.maxT[0], xa), this.interp(this.maxT[0], xb));
    const k0 = Math.floor(xa) + 1,
      k1 = Math.ceil(xb) - 1;
    if (k0 <= k1) {
      const [qlo, qhi] = this.query(k0, k1);
      lo = Math.min(lo, qlo);
      hi = Math.max(hi, qhi);
    }
    return [lo, hi];
  }

  private interp(t: Float64Array, x: number): number {
    const i0 = Math.min(Math.floor(x), this.size - 1),
      i1 = Math.min(i0 + 1, this.size - 1);
    return t[i0] + (t[i1] - t[i0]) * (x - i0);
  }
}

/** The majorant grid for per-cell value ranges, a rasterized TF (RGBA texels) and a density scale. */
export function buildMajorantGrid(
  ranges: CellValueRanges,
  tfTexels: Float32Array,
  densityScale: number,
  tfWidth = TF_RESOLUTION,
): MajorantGrid {
  const table = new OpacityRangeTable(tfTexels, tfWidth);
  const n = ranges.vmin.length;
  const data = new Float32Array(4 * n);
  let gMax = 0,
    gMin = Infinity;
  for (let c = 0; c < n; c++) {
    const [lo, hi] = table.valueRange(ranges.vmin[c], ranges.vmax[c]);
    const maj = Math.fround(hi * densityScale * (1 + PAD));
    const min = Math.fround(lo * densityScale * (1 - PAD));
    data[4 * c] = maj;
    data[4 * c + 1] = min;
    if (maj > gMax) gMax = maj;
    if (min < gMin) gMin = min;
  }
  return { cells: ranges.cells, data, globalMajorant: gMax, globalMinorant: Number.isFinite(gMin) ? gMin : 0 };
}

const rangeCache = new WeakMap<Volume, Map<number, CellValueRanges>>();

/** Per-cell value ranges of a volume, computed once per (Volume object, cell size). */
export function volumeCellRanges(volume: Volume, cellSize: number): CellValueRanges {
  let byCell = rangeCache.get(volume);
  if (!byCell) {
    byCell = new Map();
    rangeCache.set(volume, byCell);
  }
  let r = byCell.get(cellSize);
  if (!r) {
    r = computeCellValueRanges(normalizedData(volume), volume.dims, gridCells(volume.dims, cellSize));
    byCell.set(cellSize, r);
  }
  return r;
}

const channelRangeCache = new WeakMap<object, Map<string, CellValueRanges>>();

/**
 * The majorant grid of a channel scene (scene/channels.ts): the kernel's extinction is the sum
 * of the drawn channels' densityScale · opacity_k(value_k), so each cell's majorant is the sum
 * of the channels' majorants over their own value ranges (each padded as for one channel) and
 * its minorant the sum of their minorants. Built on the CPU (per-channel ranges cached per data
 * array, channel, range and cell size; a TF change reruns only the per-cell bounds).
 */
export function channelMajorantGrid(
  volume: Volume,
  channels: readonly ChannelSettings[],
  densityScale: number,
  cellSize: number,
): MajorantGrid {
  const drawn = enabledChannels(channels);
  const tf = rasterizeChannelTransferFunctions(channels, TF_RESOLUTION);
  let byKey = channelRangeCache.get(volume.data);
  if (!byKey) channelRangeCache.set(volume.data, (byKey = new Map()));
  let sum: Float32Array | null = null;
  let cells: [number, number, number] = [1, 1, 1];
  drawn.forEach((c, row) => {
    const one = sceneChannelVolume(volume, channels, c);
    const key = `${c}|${one.valueRange}|${cellSize}|${volume.dims}`;
    let ranges = byKey!.get(key);
    if (!ranges) {
      ranges = computeCellValueRanges(normalizedData(one), one.dims, gridCells(one.dims, cellSize));
      byKey!.set(key, ranges);
    }
    const grid = buildMajorantGrid(
      ranges,
      tf.subarray(4 * TF_RESOLUTION * row, 4 * TF_RESOLUTION * (row + 1)),
      densityScale,
    );
    cells = grid.cells;
    if (!sum) sum = grid.data;
    else for (let i = 0; i < sum.length; i++) sum[i] = Math.fround(sum[i] + grid.data[i]);
  });
  const data = sum!;
  let gMax = 0,
    gMin = Infinity;
  for (let i = 0; i < data.length; i += 4) {
    if (data[i] > gMax) gMax = data[i];
    if (data[i + 1] < gMin) gMin = data[i + 1];
  }
  return { cells, data, globalMajorant: gMax, globalMinorant: Number.isFinite(gMin) ? gMin : 0 };
}
