/**
 * A bricked volume on the GPU: the brick atlas (a 3D texture of (B+2)³ slots in the volume's
 * upload format), the page table (one RGBA float per level-0 brick) and the level table
 * (brick-cache.ts, brick-geometry.ts), filled incrementally from a MultiscaleSource.
 *
 * Every frame (`update`) the wanted bricks — the view's priority list (brick-priority.ts:
 * the coarsest level, then visible bricks level by level towards level 0, nearest first,
 * then the rest) cut where the atlas is full — are requested from the source (a bounded
 * number in flight), at most `uploadsPerFrame` arrived bricks are written to their slots
 * (evicting the least recently used bricks the view no longer wants), and the page table is
 * rewritten. `update` returns true when what the kernels read changed: the caller
 * restarts accumulation, so every image is an unbiased estimate for the data it shows.
 */
import { VptError } from '../errors.js';
import type { GpuBackend, GpuTexture } from '../gpu/backend.js';
import { BYTES_PER_TEXEL } from '../gpu/backend.js';
import { channelTextureData, volumeTextureData, type VolumeUpload } from '../gpu/volume-format.js';
import type { Volume, VoxelArray } from '../scene/volume.js';
import { MAX_ENABLED_CHANNELS } from '../scene/channels.js';
import { BrickCache } from './brick-cache.js';
import { BrickGeometry, fillSlot, type Vec3i } from './brick-geometry.js';
import { brickPriority, type BrickView } from './brick-priority.js';
import type { MultiscaleSource } from './source.js';

/** The most drawn channels a bricked volume holds: every channel a scene may draw (MAX_ENABLED_CHANNELS). */
export const MAX_BRICKED_CHANNELS = MAX_ENABLED_CHANNELS;

export interface BrickingOptions {
  /** Data voxels per brick side (a power of two; default 32). */
  brickSize: number;
  /** Bricks written to the atlas per frame at most (default 16). */
  uploadsPerFrame: number;
  /** Level of detail: load no brick finer than the view's pixels need (brick-priority.ts). */
  lod: boolean;
}

/**
 * The drawn channels of a multichannel bricked volume: the atlas is the channel texture's
 * format (rg / rgba of the source type, planChannelUpload), each slot texel holding the drawn
 * channels in order, aprons copied for every component.
 */
export interface BrickChannels {
  /** The source's components drawn, in order (2–4 of them). */
  pick: readonly number[];
  /** Per drawn channel, the data range mapped to [0, 1] (its normalization range). */
  ranges: readonly [number, number][];
}

export interface BrickingStats {
  brickSize: number;
  /** Atlas slots, and bricks of all levels together. */
  slots: number;
  bricks: number;
  /** Bricks held in slots, and constant bricks held in the page table alone. */
  resident: number;
  constant: number;
  /** Bricks requested from the source and not yet arrived or written. */
  pending: number;
  /** Bricks written to the atlas since the volume was set. */
  uploaded: number;
  /** Bricks whose read failed: not retried, served by a coarser level. */
  failed: number;
  /** Level-0 bricks served by level 0 (their own data). */
  finest: number;
  /** Nothing left to load: every wanted brick is resident, or the atlas is full of wanted bricks. */
  complete: boolean;
  /** Bytes of the atlas, page table and level table. */
  gpuBytes: number;
}

export class BrickedVolume {
  readonly geometry: BrickGeometry;
  readonly cache: BrickCache;
  readonly atlas: GpuTexture;
  readonly pageTable: GpuTexture;
  readonly levels: GpuTexture;
  /** Bumped whenever the page table changes (part of the volume binding's key). */
  generation = 0;
  private readonly slotsPerAxis: Vec3i;
  private frame = 0;
  private readonly inFlight = new Set<number>();
  private readonly arrived: { key: number; values: VoxelArray }[] = [];
  private full = false;
  private view: BrickView | null = null;
  private priority: { key: string; keys: number[] } | null = null;
  private readonly failed = new Set<number>();
  private readonly abort = new AbortController();
  private arrival: (() => void) | null = null;
  private readonly range: [number, number];

  constructor(
    private readonly backend: GpuBackend,
    readonly source: MultiscaleSource,
    private readonly upload: VolumeUpload,
    capacityBytes: number,
    private readonly opts: BrickingOptions,
    /** The data range mapped to [0, 1] (normalizationRange of the level-0 volume). */
    range: [number, number],
    /** Called once per brick whose read fails (the brick stays served by a coarser level). */
    private readonly onFailure: (message: string) => void = () => {},
    /** A multichannel volume's drawn channels (null: a scalar volume, one component). */
    private readonly channels: BrickChannels | null = null,
  ) {
    this.range = range;
    this.geometry = new BrickGeometry(source.levels, opts.brickSize);
    const g = this.geometry;
    const S = g.slotSize;
    const [bx, by, bz] = g.levels[0].bricks;
    const tableBytes = bx * by * bz * 16 + 3 * g.levels.length * 16;
    const slotBytes = S * S * S * upload.bytesPerVoxel;
    const maxSlots = Math.floor((capacityBytes - tableBytes) / slotBytes);
    const perAxis = Math.floor(backend.limits.maxTextureDimension3D / S);
    this.slotsPerAxis = atlasSlots(Math.min(maxSlots, g.brickCount), maxSlots, perAxis);
    const slots = this.slotsPerAxis[0] * this.slotsPerAxis[1] * this.slotsPerAxis[2];
    const coarsest = g.levels[g.coarsest].bricks;
    if (!(slots >= 1) || maxSlots < coarsest[0] * coarsest[1] * coarsest[2])
      throw new VptError(
        'limit-exceeded',
        `maxGpuBytes leaves ${Math.max(0, capacityBytes)} bytes for the volume: not enough for the ${coarsest.join(' x ')} bricks of its coarsest level (${slotBytes} bytes each, ${S}³ voxels with the apron)`,
      );
    this.cache = new BrickCache(g, slots, channels ? channels.pick.length : 1);
    const [sx, sy, sz] = this.slotsPerAxis;
    this.atlas = backend.createTexture({
      dimension: '3d',
      width: sx * S,
      height: sy * S,
      depth: sz * S,
      format: upload.format,
      filter: upload.filter,
      label: 'volume brick atlas',
    });
    this.pageTable = backend.createTexture({
      dimension: '3d',
      width: bx,
      height: by,
      depth: bz,
      format: 'rgba32float',
      label: 'volume page table',
    });
    const levelData = new Float32Array(4 * 3 * g.levels.length);
    g.levels.forEach((l, i) => {
      levelData.set([...l.scale, g.brickSize, ...l.offset, 0, ...l.dims, g.brickSize], 12 * i);
    });
    this.levels = backend.createTexture({
      dimension: '2d',
      width: 3,
      height: g.levels.length,
      format: 'rgba32float',
      data: levelData,
      label: 'volume brick levels',
    });
    this.writePageTable();
  }

  /**
   * One frame's residency work: request wanted bricks, write up to uploadsPerFrame arrived
   * ones, rewrite the page table. True when the page table changed (restart accumulation).
   */
  update(view: BrickView | null = this.view): boolean {
    if (view) this.view = view;
    this.frame++;
    const wanted = this.wantedKeys();
    for (const k of wanted) this.cache.touch(k, this.frame);
    let changed = false;
    for (let n = 0; n < this.opts.uploadsPerFrame && this.arrived.length; n++) {
      const { key, values } = this.arrived.shift()!;
      if (this.store(key, values)) changed = true;
    }
    if (!this.full) this.request(wanted);
    if (changed) this.writePageTable();
    return changed;
  }

  /** Resolves when a requested brick arrives (or at once when nothing is in flight). */
  nextArrival(): Promise<void> {
    if (this.inFlight.size === 0 || this.arrived.length) return Promise.resolve();
    return new Promise((resolve) => {
      this.arrival = resolve;
    });
  }

  stats(): BrickingStats {
    const { slots, constant } = this.cache.counts();
    const [bx, by, bz] = this.geometry.levels[0].bricks;
    let finest = 0;
    for (let z = 0; z < bz; z++)
      for (let y = 0; y < by; y++)
        for (let x = 0; x < bx; x++) {
          const e = this.cache.lookup([x, y, z]);
          if (e.kind !== 'none' && e.level === 0) finest++;
        }
    const wantedMissing = this.wantedKeys().some((k) => !this.cache.has(k));
    return {
      brickSize: this.geometry.brickSize,
      slots: this.cache.capacity,
      bricks: this.geometry.brickCount,
      resident: slots,
      constant,
      pending: this.inFlight.size + this.arrived.length,
      uploaded: this.cache.uploads,
      failed: this.failed.size,
      finest,
      complete: this.inFlight.size === 0 && this.arrived.length === 0 && (this.full || !wantedMissing),
      gpuBytes: this.gpuBytes(),
    };
  }

  gpuBytes(): number {
    const tex = (t: GpuTexture) => t.width * t.height * t.depth * BYTES_PER_TEXEL[t.format];
    return tex(this.atlas) + tex(this.pageTable) + tex(this.levels);
  }

  /** Per cell of a majorant grid, the normalized value range the kernels can read there (BrickCache.cellRanges). */
  cellRanges(cells: readonly [number, number, number]) {
    const [lo, hi] = this.range;
    const inv = 1 / (hi - lo);
    return this.cache.cellRanges(cells, (v) => Math.min(1, Math.max(0, (v - lo) * inv)), lo);
  }

  /** A multichannel volume's cell ranges, one per drawn channel, each normalized with that channel's range. */
  channelCellRanges(cells: readonly [number, number, number]) {
    const ranges = this.channels?.ranges ?? [this.range];
    return ranges.map(([lo, hi], k) => {
      const inv = 1 / (hi - lo);
      return this.cache.cellRanges(cells, (v) => Math.min(1, Math.max(0, (v - lo) * inv)), ranges[0][0], k);
    });
  }

  /** Free the textures and stop reading (dispose, or a new volume). */
  release(destroy = true): void {
    this.abort.abort();
    if (!destroy) return;
    this.backend.destroyTexture(this.atlas);
    this.backend.destroyTexture(this.pageTable);
    this.backend.destroyTexture(this.levels);
  }

  /**
   * The view's priority list (recomputed when the view changes) cut after as many bricks as
   * there are slots; bricks known to be constant take no slot and do not count.
   */
  private wantedKeys(): number[] {
    const v = this.view;
    const viewKey = v ? JSON.stringify([v.camera, v.width, v.height, v.lod]) : '';
    if (this.priority?.key !== viewKey) {
      this.priority = { key: viewKey, keys: brickPriority(this.geometry, this.source.levels[0], v) };
      this.full = false;
    }
    const wanted: number[] = [];
    let slots = 0;
    for (const k of this.priority.keys) {
      if (this.failed.has(k)) continue;
      if (!this.cache.isConstant(k) && ++slots > this.cache.capacity) break;
      wanted.push(k);
    }
    return wanted;
  }

  private request(wanted: number[]): void {
    const maxInFlight = 2 * this.opts.uploadsPerFrame;
    for (const key of wanted) {
      if (this.inFlight.size >= maxInFlight) break;
      if (
        this.cache.has(key) ||
        this.inFlight.has(key) ||
        this.failed.has(key) ||
        this.arrived.some((a) => a.key === key)
      )
        continue;
      const { level, brick } = this.geometry.brickOf(key);
      const { min, max } = this.geometry.readRegion(level, brick);
      this.inFlight.add(key);
      this.source.readRegion(level, min, max, this.abort.signal).then(
        (region) => {
          this.inFlight.delete(key);
          if (this.abort.signal.aborted) return;
          const pick = this.channels?.pick ?? [0];
          const values = fillSlot(
            this.geometry,
            level,
            brick,
            region,
            new (region.constructor as new (n: number) => VoxelArray)(pick.length * this.geometry.slotSize ** 3),
            this.source.channels ?? 1,
            pick,
          );
          this.arrived.push({ key, values });
          this.wake();
        },
        (e: unknown) => {
          this.inFlight.delete(key);
          if (!this.abort.signal.aborted) {
            this.failed.add(key);
            const why = e instanceof Error ? e.message : String(e);
            this.onFailure(
              `Reading brick [${brick.join(', ')}] of level ${level} failed (it stays served by a coarser level): ${why}`,
            );
          }
          this.wake();
        },
      );
    }
  }

  private wake(): void {
    const a = this.arrival;
    this.arrival = null;
    a?.();
  }

  /** Put an arrived brick into the cache (and its slot); false when nothing changed. */
  private store(key: number, values: VoxelArray): boolean {
    const ch = this.channels;
    // As the unbricked upload: a non-finite voxel reads as the value mapping to 0 (in its channel).
    const fills = ch ? ch.ranges.map((r) => r[0]) : [this.range[0]];
    if (values instanceof Float32Array)
      for (let i = 0; i < values.length; i++) if (!Number.isFinite(values[i])) values[i] = fills[i % fills.length];
    const slot = this.cache.insert(key, { values }, this.frame);
    if (slot === null) {
      this.full = true; // every slot holds a brick wanted now: finer bricks stay served by coarser ones
      return false;
    }
    if (slot >= 0) {
      const S = this.geometry.slotSize;
      const brick: Volume = {
        dims: [S, S, S],
        spacing: [1, 1, 1],
        type: this.source.type,
        data: values,
        valueRange: this.range,
        ...(ch ? { channels: ch.pick.length } : {}),
      };
      this.backend.writeTextureRegion(
        this.atlas,
        this.slotOrigin(slot),
        [S, S, S],
        ch
          ? channelTextureData(
              brick,
              this.upload,
              ch.pick.map((_, k) => k),
            )
          : volumeTextureData(brick, this.upload),
      );
    }
    return true;
  }

  private slotOrigin(slot: number): Vec3i {
    const [sx, sy] = this.slotsPerAxis;
    const S = this.geometry.slotSize;
    return [(slot % sx) * S, (Math.floor(slot / sx) % sy) * S, Math.floor(slot / (sx * sy)) * S];
  }

  private writePageTable(): void {
    const { decodeScale, decodeOffset } = this.upload;
    const toTexel = (v: number) => (v - decodeOffset) / decodeScale;
    this.backend.writeTexture(
      this.pageTable,
      this.cache.pageTable((s) => this.slotOrigin(s), toTexel, toTexel(this.range[0])),
    );
    this.generation++;
  }
}

/**
 * Slots per atlas axis for `want` slots, at most `max` in all and `perAxis` per axis: the box
 * that holds the most of the wanted slots (all of them when the budget allows), then the
 * fewest beyond them, then the most cubic (so no side nears the 3D texture limit).
 */
export function atlasSlots(want: number, max: number, perAxis: number): Vec3i {
  const n = Math.min(want, max, perAxis ** 3);
  if (n < 1) return [0, 0, 0];
  let best: Vec3i = [0, 0, 0];
  let bestScore = [-1, 0, 0];
  for (let sx = 1; sx <= Math.min(perAxis, n); sx++)
    for (let sy = 1; sy <= Math.min(perAxis, Math.ceil(n / sx)); sy++) {
      let sz = Math.min(perAxis, Math.ceil(n / (sx * sy)));
      if (sx * sy * sz > max) sz = Math.floor(max / (sx * sy));
      if (sz < 1) continue;
      const p = sx * sy * sz;
      const score = [Math.min(p, n), -p, -Math.max(sx, sy, sz)];
      if (
        score[0] > bestScore[0] ||
        (score[0] === bestScore[0] &&
          (score[1] > bestScore[1] || (score[1] === bestScore[1] && score[2] > bestScore[2])))
      ) {
        best = [sx, sy, sz];
        bestScore = score;
      }
    }
  return best;
}
