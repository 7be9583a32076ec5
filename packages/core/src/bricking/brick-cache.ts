/**
 * The CPU side of the brick cache: which brick lives in which atlas slot, least-recently-used
 * eviction, the page table the kernels read and the value ranges the majorant grid is built
 * from. No GPU calls here (bricked-volume.ts does the uploads), so all of it is unit-tested.
 *
 * A brick whose slot content is one value (empty space, typically) takes no slot: its page
 * entry holds the value itself.
 */
import type { BrickGeometry } from './brick-geometry.js';

/** Voxels per side of the sub-blocks whose value ranges a resident brick keeps (majorant-grid resolution). */
export const SUB_BLOCK = 8;

export interface BrickContent {
  /**
   * The slot's values, (B+2)³ data values (not texels), x fastest; for a multichannel cache
   * `components` values per texel, interleaved (the drawn channels, the channel fastest).
   */
  values: ArrayLike<number>;
}

interface Entry {
  /** Atlas slot, or −1 for a constant brick (no slot). */
  slot: number;
  /** The value of a constant brick (data units; every component holds it). */
  constant: number;
  /** Frame the brick was last wanted. */
  lastUsed: number;
  /** Per component, [min, max] over the whole slot (data units). */
  min: number[];
  max: number[];
  /** Per component, per sub-block [min, max] of what trilinear reads for points in it (level-0 bricks only), 2 per sub-block. */
  sub: Float32Array[] | null;
}

/** A page-table entry: where the kernels read level-0 brick b0 from. */
export type PageEntry =
  | { kind: 'slot'; level: number; slot: number; brick: [number, number, number] }
  | { kind: 'constant'; level: number; value: number }
  | { kind: 'none' };

export class BrickCache {
  private readonly entries = new Map<number, Entry>();
  private readonly owner: Int32Array; // slot → key, −1 free
  /** Bricks written to slots since creation (incremental uploads, for the stats). */
  uploads = 0;

  constructor(
    readonly geometry: BrickGeometry,
    readonly capacity: number,
    /** Values per slot texel (the drawn channels of a multichannel volume; 1 for a scalar one). */
    readonly components = 1,
  ) {
    this.owner = new Int32Array(capacity).fill(-1);
  }

  has(key: number): boolean {
    return this.entries.has(key);
  }

  /** The brick arrived and holds one value (it takes no slot). */
  isConstant(key: number): boolean {
    return this.entries.get(key)?.slot === -1;
  }

  /** Resident bricks with a slot, and constant ones. */
  counts(): { slots: number; constant: number } {
    let slots = 0,
      constant = 0;
    for (const e of this.entries.values()) {
      if (e.slot >= 0) slots++;
      else constant++;
    }
    return { slots, constant };
  }

  /** The brick is wanted in this frame (it will not be evicted for bricks of the same frame). */
  touch(key: number, frame: number): void {
    const e = this.entries.get(key);
    if (e) e.lastUsed = frame;
  }

  /**
   * Store a brick that arrived. A constant brick (one value in every texel and, for a
   * multichannel cache, every component) is kept without a slot. Otherwise it takes a
   * free slot or the slot of the least recently used brick not wanted in `frame`; returns the
   * slot to upload to, −1 for a constant brick, or null when every slot holds a brick wanted
   * in this frame (the brick is dropped; its region stays served by a coarser level).
   */
  insert(key: number, content: BrickContent, frame: number): number | null {
    const v = content.values;
    const C = this.components;
    const min = new Array<number>(C).fill(Infinity),
      max = new Array<number>(C).fill(-Infinity);
    for (let i = 0, k = 0; i < v.length; i++, k = k + 1 === C ? 0 : k + 1) {
      if (v[i] < min[k]) min[k] = v[i];
      if (v[i] > max[k]) max[k] = v[i];
    }
    const lo = Math.min(...min);
    if (min.every((m, k) => m === lo && max[k] === lo)) {
      this.evictKey(key);
      this.entries.set(key, { slot: -1, constant: lo, lastUsed: frame, min, max, sub: null });
      return -1;
    }
    const slot = this.entries.get(key)?.slot ?? -1;
    const target = slot >= 0 ? slot : this.freeSlot(frame);
    if (target === null) return null;
    const level = this.geometry.brickOf(key).level;
    this.owner[target] = key;
    this.entries.set(key, {
      slot: target,
      constant: 0,
      lastUsed: frame,
      min,
      max,
      sub: level === 0 ? Array.from({ length: C }, (_, k) => subBlockRanges(v, this.geometry.brickSize, C, k)) : null,
    });
    this.uploads++;
    return target;
  }

  private freeSlot(frame: number): number | null {
    let best = -1,
      bestUsed = Infinity;
    for (let s = 0; s < this.capacity; s++) {
      const k = this.owner[s];
      if (k < 0) return s;
      const used = this.entries.get(k)!.lastUsed;
      if (used < frame && used < bestUsed) {
        best = s;
        bestUsed = used;
      }
    }
    if (best < 0) return null;
    this.evictKey(this.owner[best]);
    return best;
  }

  private evictKey(key: number): void {
    const e = this.entries.get(key);
    if (!e) return;
    if (e.slot >= 0) this.owner[e.slot] = -1;
    this.entries.delete(key);
  }

  /** The finest resident level serving level-0 brick b0 (its own brick at level 0, else the coarser bricks holding its centre). */
  lookup(b0: readonly number[]): PageEntry {
    const g = this.geometry;
    for (let level = 0; level < g.levels.length; level++) {
      const brick = level === 0 ? ([b0[0], b0[1], b0[2]] as [number, number, number]) : g.coarseBrickOf(level, b0);
      const e = this.entries.get(g.key(level, brick));
      if (!e) continue;
      return e.slot >= 0
        ? { kind: 'slot', level, slot: e.slot, brick }
        : { kind: 'constant', level, value: e.constant };
    }
    return { kind: 'none' };
  }

  /**
   * The page table: one RGBA float per level-0 brick (x fastest). A brick served from a slot
   * holds (slot origin in atlas texels, level); a constant brick (texel value, 0, 0, −1); a
   * brick nothing serves yet (emptyTexel, 0, 0, −1).
   */
  pageTable(slotOrigin: (slot: number) => readonly number[], toTexel: (value: number) => number, emptyTexel: number) {
    const [bx, by, bz] = this.geometry.levels[0].bricks;
    const out = new Float32Array(4 * bx * by * bz);
    let o = 0;
    for (let z = 0; z < bz; z++)
      for (let y = 0; y < by; y++)
        for (let x = 0; x < bx; x++, o += 4) {
          const e = this.lookup([x, y, z]);
          if (e.kind === 'slot') {
            const s = slotOrigin(e.slot);
            out.set([s[0], s[1], s[2], e.level], o);
          } else out.set([e.kind === 'constant' ? toTexel(e.value) : emptyTexel, 0, 0, -1], o);
        }
    return out;
  }

  /**
   * Per cell of a grid of `cells` over the box, the [min, max] of the normalized values the
   * kernels can read at its points (majorant-grid ranges): the union over the level-0
   * sub-blocks the cell touches of what serves them: a resident level-0 brick's sub-block
   * ranges, else the whole slot of the coarser brick that serves it, or its constant.
   * `normalize` is the monotone data → [0, 1] map; `emptyValue` what an unserved brick reads;
   * `component` the channel of a multichannel cache (each drawn channel has its own ranges).
   */
  cellRanges(
    cells: readonly [number, number, number],
    normalize: (v: number) => number,
    emptyValue: number,
    component = 0,
  ): { cells: [number, number, number]; vmin: Float32Array; vmax: Float32Array } {
    const g = this.geometry;
    const dims = g.levels[0].dims;
    const B = g.brickSize;
    const sb = Math.min(SUB_BLOCK, B);
    const per = B / sb;
    const nsub = dims.map((d) => Math.ceil(d / sb));
    // Served [min, max] per level-0 sub-block (data units).
    const smin = new Float64Array(nsub[0] * nsub[1] * nsub[2]);
    const smax = new Float64Array(smin.length);
    const fine = new Uint8Array(smin.length); // served by its own level-0 brick
    const [bx, by, bz] = g.levels[0].bricks;
    for (let z = 0; z < bz; z++)
      for (let y = 0; y < by; y++)
        for (let x = 0; x < bx; x++) {
          const e = this.lookup([x, y, z]);
          const entry = e.kind === 'slot' ? this.entries.get(g.key(e.level, e.brick))! : null;
          for (let kz = 0; kz < per; kz++)
            for (let ky = 0; ky < per; ky++)
              for (let kx = 0; kx < per; kx++) {
                const sx = x * per + kx,
                  sy = y * per + ky,
                  sz = z * per + kz;
                if (sx >= nsub[0] || sy >= nsub[1] || sz >= nsub[2]) continue;
                const i = sx + nsub[0] * (sy + nsub[1] * sz);
                if (entry?.sub && e.kind === 'slot' && e.level === 0) {
                  const k = 2 * (kx + per * (ky + per * kz));
                  smin[i] = entry.sub[component][k];
                  smax[i] = entry.sub[component][k + 1];
                  fine[i] = 1;
                } else if (entry) {
                  smin[i] = entry.min[component];
                  smax[i] = entry.max[component];
                } else {
                  smin[i] = smax[i] = e.kind === 'constant' ? e.value : emptyValue;
                }
              }
        }
    const [gx, gy, gz] = cells;
    const vmin = new Float32Array(gx * gy * gz);
    const vmax = new Float32Array(gx * gy * gz);
    // At a brick face, rounding may look a point up in the brick across it. Where both bricks
    // are served by level 0 that reads the same voxels (the sub-block margin covers it); where
    // either is served otherwise, the sub-blocks on both sides take each other's range (one
    // pass per axis, so bricks across an edge or a corner are covered too).
    const step = [1, nsub[0], nsub[0] * nsub[1]];
    for (let a = 0; a < 3; a++) {
      const [min0, max0] = [smin.slice(), smax.slice()];
      for (let i = 0; i < smin.length; i++) {
        const c = Math.floor(i / step[a]) % nsub[a];
        if ((c + 1) % per !== 0 || c + 1 >= nsub[a]) continue;
        const j = i + step[a];
        if (fine[i] && fine[j]) continue;
        smin[i] = Math.min(smin[i], min0[j]);
        smax[i] = Math.max(smax[i], max0[j]);
        smin[j] = Math.min(smin[j], min0[i]);
        smax[j] = Math.max(smax[j], max0[i]);
      }
    }
    // The sub-blocks a cell touches: those overlapping its voxel interval [c·N/G, (c+1)·N/G].
    const span = (c: number, G: number, a: number): [number, number] => {
      const s0 = Math.floor((c * dims[a]) / G / sb);
      const s1 = Math.ceil(((c + 1) * dims[a]) / G / sb) - 1;
      return [Math.max(0, s0), Math.min(nsub[a] - 1, Math.max(s0, s1))];
    };
    let o = 0;
    for (let cz = 0; cz < gz; cz++) {
      const [z0, z1] = span(cz, gz, 2);
      for (let cy = 0; cy < gy; cy++) {
        const [y0, y1] = span(cy, gy, 1);
        for (let cx = 0; cx < gx; cx++, o++) {
          const [x0, x1] = span(cx, gx, 0);
          let lo = Infinity,
            hi = -Infinity;
          for (let z = z0; z <= z1; z++)
            for (let y = y0; y <= y1; y++)
              for (let x = x0; x <= x1; x++) {
                const i = x + nsub[0] * (y + nsub[1] * z);
                const a = normalize(smin[i]),
                  b = normalize(smax[i]);
                lo = Math.min(lo, a, b);
                hi = Math.max(hi, a, b);
              }
          vmin[o] = lo;
          vmax[o] = hi;
        }
      }
    }
    return { cells: [gx, gy, gz], vmin, vmax };
  }
}

/**
 * Per sub-block of a level-0 brick's slot, the [min, max] of the texels trilinear filtering
 * reads for points inside it: points of sub-block k span level-0 voxels [k·s, (k+1)·s] of the
 * brick, which read slot texels k·s … (k+1)·s + 1; one more texel each side is margin against
 * the rounding of positions. `C` values per texel, component `c` read.
 */
function subBlockRanges(v: ArrayLike<number>, B: number, C = 1, c = 0): Float32Array {
  const S = B + 2;
  const s = Math.min(SUB_BLOCK, B);
  const per = B / s;
  const out = new Float32Array(2 * per * per * per);
  const lo = (k: number) => Math.max(0, k * s - 1);
  const hi = (k: number) => Math.min(S - 1, (k + 1) * s + 2);
  for (let kz = 0; kz < per; kz++)
    for (let ky = 0; ky < per; ky++)
      for (let kx = 0; kx < per; kx++) {
        let mn = Infinity,
          mx = -Infinity;
        for (let z = lo(kz); z <= hi(kz); z++)
          for (let y = lo(ky); y <= hi(ky); y++) {
            const row = S * (y + S * z);
            for (let x = lo(kx); x <= hi(kx); x++) {
              const val = v[C * (row + x) + c];
              if (val < mn) mn = val;
              if (val > mx) mx = val;
            }
          }
        const k = 2 * (kx + per * (ky + per * kz));
        out[k] = mn;
        out[k + 1] = mx;
      }
  return out;
}
