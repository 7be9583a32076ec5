/**
 * Where a bricked volume's voxels come from: a multiresolution source (level 0 finest),
 * read region by region. `@vpt/loaders` implements it for OME-Zarr (structurally: no import
 * of core needed there); `inMemoryMultiscaleSource` builds one from a core `Volume`, with
 * coarser levels made by 2× box averages (scene/downsample.ts).
 */
import { downsampleChannels, downsampleVolume } from '../scene/downsample.js';
import { channelCount, type Volume, type VoxelArray, type VoxelType } from '../scene/volume.js';

export interface MultiscaleLevel {
  /** Voxels per axis, x fastest. */
  dims: [number, number, number];
  /** Physical voxel size (same units at every level). */
  spacing: [number, number, number];
  /** Physical position of the corner of voxel 0 (the box corner), same units as spacing. */
  origin: [number, number, number];
  /** The source's natural read size (a Zarr chunk); a hint only. */
  chunk: [number, number, number];
}

export interface MultiscaleSource {
  type: VoxelType;
  /** Level 0 is the finest; each later level is coarser and covers the same box. */
  levels: MultiscaleLevel[];
  /** The data range mapped to [0, 1] (Volume.valueRange); without it the type's convention. */
  valueRange?: [number, number];
  /**
   * Channels per voxel (Volume.channels; default 1): a multichannel source's regions hold
   * this many values per voxel, interleaved, the channel fastest (the bricks keep the drawn ones).
   */
  channels?: number;
  /** The voxels of [min, max) (max exclusive) of a level, x fastest (channel fastest within a voxel). */
  readRegion(
    level: number,
    min: [number, number, number],
    max: [number, number, number],
    signal?: AbortSignal,
  ): Promise<VoxelArray>;
  /** A whole level as a Volume. */
  readLevel(level: number, signal?: AbortSignal): Promise<Volume>;
}

/**
 * A source over a volume in memory: level 0 is the volume itself, each next level halves
 * every side longer than one voxel, down to the first level whose longest side is at most
 * `coarsestSide` (default 32: one brick of the default size).
 */
export function inMemoryMultiscaleSource(
  volume: Volume,
  opts: { coarsestSide?: number } = {},
): InMemoryMultiscaleSource {
  return new InMemoryMultiscaleSource(volume, opts.coarsestSide ?? 32);
}

export class InMemoryMultiscaleSource implements MultiscaleSource {
  readonly type: VoxelType;
  readonly levels: MultiscaleLevel[];
  readonly valueRange?: [number, number];
  readonly channels: number;
  /** The level volumes, level 0 = the given volume. */
  readonly volumes: Volume[];

  constructor(volume: Volume, coarsestSide: number) {
    this.type = volume.type;
    this.channels = channelCount(volume);
    if (volume.valueRange) this.valueRange = [volume.valueRange[0], volume.valueRange[1]];
    this.volumes = [volume];
    let v = volume;
    while (Math.max(...v.dims) > Math.max(1, coarsestSide)) {
      const f = v.dims.map((d) => (d > 1 ? 2 : 1)) as [number, number, number];
      // A multichannel volume: every channel by the same box averages (scene/downsample.ts).
      v = this.channels > 1 ? downsampleChannels(v, f) : downsampleVolume(v, f);
      this.volumes.push(v);
    }
    this.levels = this.volumes.map((l) => ({
      dims: [...l.dims] as [number, number, number],
      spacing: [...l.spacing] as [number, number, number],
      origin: [0, 0, 0],
      chunk: [...l.dims] as [number, number, number],
    }));
  }

  readRegionNow(level: number, min: readonly number[], max: readonly number[]): VoxelArray {
    const v = this.volumes[level];
    const [nx, ny] = v.dims;
    const C = this.channels;
    const sx = max[0] - min[0],
      sy = max[1] - min[1],
      sz = max[2] - min[2];
    const out = new (v.data.constructor as new (n: number) => VoxelArray)(sx * sy * sz * C);
    for (let z = 0; z < sz; z++)
      for (let y = 0; y < sy; y++) {
        const from = C * (min[0] + nx * (min[1] + y + ny * (min[2] + z)));
        out.set(v.data.subarray(from, from + C * sx), C * sx * (y + sy * z));
      }
    return out;
  }

  readRegion(level: number, min: [number, number, number], max: [number, number, number]): Promise<VoxelArray> {
    return Promise.resolve(this.readRegionNow(level, min, max));
  }

  readLevel(level: number): Promise<Volume> {
    return Promise.resolve(this.volumes[level]);
  }
}
