/**
 * The brick grid of a multiscale volume: every level is cut into bricks of B³ data voxels
 * (the last brick of an axis may be partial); a brick is stored with a one-voxel apron on
 * every side, (B+2)³ texels, the apron holding the neighbours' voxels (clamp-to-edge at the
 * volume's faces), so trilinear filtering inside a brick reads nothing outside its slot.
 *
 * Coordinates: x0 is a level-0 voxel coordinate (voxel i spans [i, i+1], texture
 * coordinate × dims); level l maps it to x_l = x0 · scale_l + offset_l (from the levels'
 * spacing and origin), and the level-l brick that serves level-0 brick b0 is the one holding
 * the centre of b0 (coarseBrickOf; the shader computes the same).
 */
import type { MultiscaleLevel } from './source.js';

export type Vec3i = [number, number, number];

export interface BrickLevelGeometry {
  dims: Vec3i;
  /** Bricks per axis, ceil(dims / B). */
  bricks: Vec3i;
  /** x_l = x0 · scale + offset (level-0 voxel coordinate → this level's). */
  scale: [number, number, number];
  offset: [number, number, number];
  /** Index of this level's first brick in the flat brick numbering of all levels. */
  firstKey: number;
}

export class BrickGeometry {
  readonly levels: BrickLevelGeometry[];
  /** Bricks of all levels together. */
  readonly brickCount: number;
  readonly slotSize: number;

  constructor(
    levels: readonly MultiscaleLevel[],
    readonly brickSize: number,
  ) {
    if (!Number.isInteger(Math.log2(brickSize)) || brickSize < 4)
      throw new RangeError(`brick size must be a power of two ≥ 4, got ${brickSize}`);
    const l0 = levels[0];
    let firstKey = 0;
    this.levels = levels.map((l) => {
      const bricks = l.dims.map((d) => Math.ceil(d / brickSize)) as Vec3i;
      const scale = [0, 1, 2].map((a) => Math.fround(l0.spacing[a] / l.spacing[a])) as Vec3i;
      const offset = [0, 1, 2].map((a) => Math.fround((l0.origin[a] - l.origin[a]) / l.spacing[a])) as Vec3i;
      const g: BrickLevelGeometry = { dims: [...l.dims] as Vec3i, bricks, scale, offset, firstKey };
      firstKey += bricks[0] * bricks[1] * bricks[2];
      return g;
    });
    this.brickCount = firstKey;
    this.slotSize = brickSize + 2;
  }

  get coarsest(): number {
    return this.levels.length - 1;
  }

  /** The flat key of brick b of a level. */
  key(level: number, b: readonly number[]): number {
    const g = this.levels[level];
    return g.firstKey + b[0] + g.bricks[0] * (b[1] + g.bricks[1] * b[2]);
  }

  /** (level, brick) of a flat key. */
  brickOf(key: number): { level: number; brick: Vec3i } {
    let level = this.levels.length - 1;
    while (this.levels[level].firstKey > key) level--;
    const g = this.levels[level];
    const i = key - g.firstKey;
    return {
      level,
      brick: [i % g.bricks[0], Math.floor(i / g.bricks[0]) % g.bricks[1], Math.floor(i / (g.bricks[0] * g.bricks[1]))],
    };
  }

  /**
   * The level-l brick serving level-0 brick b0: the one holding b0's centre, in float32 as
   * the shader computes it (bricked sampling in common.*.ts), clamped to the level's bricks.
   */
  coarseBrickOf(level: number, b0: readonly number[]): Vec3i {
    const g = this.levels[level];
    const B = this.brickSize;
    return [0, 1, 2].map((a) => {
      const f = Math.fround;
      const x = f(f(f(f(b0[a] + 0.5) * B) * g.scale[a]) + g.offset[a]);
      return Math.min(g.bricks[a] - 1, Math.max(0, Math.floor(x / B)));
    }) as Vec3i;
  }

  /** The voxel region [min, max) a brick's slot is filled from: the brick and its apron, clipped to the level. */
  readRegion(level: number, b: readonly number[]): { min: Vec3i; max: Vec3i } {
    const g = this.levels[level];
    const B = this.brickSize;
    return {
      min: [0, 1, 2].map((a) => Math.max(0, b[a] * B - 1)) as Vec3i,
      max: [0, 1, 2].map((a) => Math.min(g.dims[a], b[a] * B + B + 1)) as Vec3i,
    };
  }
}

/**
 * A brick's slot content, (B+2)³ values x fastest, from its read region: slot texel k holds
 * voxel clamp(b·B − 1 + k, 0, N − 1) on each axis (clamp-to-edge at the faces, so the
 * bricked filter equals the unbricked one there). A multichannel region (`components` values
 * per voxel, interleaved, the channel fastest) fills `pick.length` values per slot texel: the
 * region's components `pick`, in that order (the drawn channels), so every component gets
 * the same apron.
 */
export function fillSlot<T extends ArrayLike<number> & { [i: number]: number }>(
  geometry: BrickGeometry,
  level: number,
  b: readonly number[],
  region: ArrayLike<number>,
  out: T,
  components = 1,
  pick: readonly number[] = [0],
): T {
  const { min, max } = geometry.readRegion(level, b);
  const dims = geometry.levels[level].dims;
  const S = geometry.slotSize;
  const B = geometry.brickSize;
  const sx = max[0] - min[0],
    sy = max[1] - min[1];
  const src = [0, 1, 2].map((a) =>
    Int32Array.from({ length: S }, (_, k) => Math.min(dims[a] - 1, Math.max(0, b[a] * B - 1 + k)) - min[a]),
  );
  const P = pick.length;
  let o = 0;
  for (let z = 0; z < S; z++)
    for (let y = 0; y < S; y++) {
      const row = sx * (src[1][y] + sy * src[2][z]);
      for (let x = 0; x < S; x++) {
        const at = components * (row + src[0][x]);
        for (let k = 0; k < P; k++) out[o++] = region[at + pick[k]];
      }
    }
  return out;
}
