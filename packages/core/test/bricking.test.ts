import { describe, expect, it } from 'vitest';
import {
  atlasSlots,
  brickPriority,
  BrickCache,
  BrickGeometry,
  createVolume,
  fillSlot,
  inMemoryMultiscaleSource,
  interleaveChannels,
  type Volume,
} from '../src/index.js';

/** A deterministic uint8 volume, exactly 0 in the corner x, y < 20. */
function testVolume(dims: [number, number, number]): Volume {
  const data = new Uint8Array(dims[0] * dims[1] * dims[2]);
  let i = 0;
  for (let z = 0; z < dims[2]; z++)
    for (let y = 0; y < dims[1]; y++)
      for (let x = 0; x < dims[0]; x++, i++) {
        if (x < 20 && y < 20) continue;
        // Increasing along every axis: a block's extremes sit at its corners, so a range that
        // misses the texels just outside a block shows at points near its faces.
        data[i] = Math.round(2 * x + y + 1.5 * z + 3 * Math.sin(x / 2));
      }
  return createVolume(dims, 'uint8', data, [1, 1, 1.5]);
}

const rng = (seed: number) => () => {
  seed = (seed * 1664525 + 1013904223) >>> 0;
  return seed / 2 ** 32;
};

/** Load bricks of a source into a cache (key order given), keeping the slot contents for the CPU sampler below. */
function load(
  geometry: BrickGeometry,
  source: ReturnType<typeof inMemoryMultiscaleSource>,
  cache: BrickCache,
  keys: number[],
  frame = 1,
) {
  const slots = new Map<number, Uint8Array>();
  for (const key of keys) {
    const { level, brick } = geometry.brickOf(key);
    const { min, max } = geometry.readRegion(level, brick);
    const values = fillSlot(
      geometry,
      level,
      brick,
      source.readRegionNow(level, min, max),
      new Uint8Array(geometry.slotSize ** 3),
    );
    const slot = cache.insert(key, { values }, frame);
    if (slot !== null && slot >= 0) slots.set(slot, values);
  }
  return slots;
}

/**
 * CPU twin of the bricked exact filter (common.glsl.ts, BRICKED_EXACT_FILTER) in data units:
 * page lookup of the level-0 brick holding x0, then trilinear in the serving level's voxels
 * with indices clamped to the level and to the slot.
 */
function sampleBricked(
  geometry: BrickGeometry,
  cache: BrickCache,
  slots: Map<number, Uint8Array>,
  x0: number[],
): number {
  const B = geometry.brickSize;
  const S = geometry.slotSize;
  const l0 = geometry.levels[0];
  const b0 = [0, 1, 2].map((a) => Math.min(l0.bricks[a] - 1, Math.max(0, Math.floor(x0[a] / B))));
  const e = cache.lookup(b0);
  if (e.kind === 'none') throw new Error('unserved brick');
  if (e.kind === 'constant') return e.value;
  const g = geometry.levels[e.level];
  const first = e.brick.map((b) => b * B - 1);
  const x = [0, 1, 2].map((a) => x0[a] * g.scale[a] + g.offset[a] - 0.5);
  const i0 = x.map(Math.floor);
  const f = x.map((v, a) => v - i0[a]);
  const values = slots.get(e.slot)!;
  const at = (i: number[]) => {
    const c = i.map((v, a) => Math.min(first[a] + B + 1, Math.max(first[a], Math.min(g.dims[a] - 1, Math.max(0, v)))));
    return values[c[0] - first[0] + S * (c[1] - first[1] + S * (c[2] - first[2]))];
  };
  return trilinear(at, i0, f);
}

/** The trilinear blend, with fractions f, of the 8 voxels `at(i0 + {0,1}³)`. */
function trilinear(at: (i: number[]) => number, i0: number[], f: number[]): number {
  const lerp = (a: number, b: number, t: number) => a + (b - a) * t;
  const c = (dx: number, dy: number, dz: number) => at([i0[0] + dx, i0[1] + dy, i0[2] + dz]);
  return lerp(
    lerp(lerp(c(0, 0, 0), c(1, 0, 0), f[0]), lerp(c(0, 1, 0), c(1, 1, 0), f[0]), f[1]),
    lerp(lerp(c(0, 0, 1), c(1, 0, 1), f[0]), lerp(c(0, 1, 1), c(1, 1, 1), f[0]), f[1]),
    f[2],
  );
}

/** Plain cell-centred clamp-to-edge trilinear of a volume at level-0 voxel coordinate x0. */
function samplePlain(v: Volume, x0: number[]): number {
  const x = x0.map((t) => t - 0.5);
  const i0 = x.map(Math.floor);
  const f = x.map((t, a) => t - i0[a]);
  const at = (i: number[]) => {
    const c = i.map((t, a) => Math.min(v.dims[a] - 1, Math.max(0, t)));
    return v.data[c[0] + v.dims[0] * (c[1] + v.dims[1] * c[2])];
  };
  return trilinear(at, i0, f);
}

const DIMS: [number, number, number] = [72, 40, 24]; // partial bricks on every axis at B = 16, whole 8-voxel cells

describe('brick geometry', () => {
  const source = inMemoryMultiscaleSource(testVolume(DIMS), { coarsestSide: 16 });
  const g = new BrickGeometry(source.levels, 16);

  it('builds 2× levels down to one brick, and numbers every brick of every level once', () => {
    expect(source.levels.map((l) => l.dims)).toEqual([
      [72, 40, 24],
      [36, 20, 12],
      [18, 10, 6],
      [9, 5, 3],
    ]);
    expect(g.levels.map((l) => l.bricks)).toEqual([
      [5, 3, 2],
      [3, 2, 1],
      [2, 1, 1],
      [1, 1, 1],
    ]);
    const seen = new Set<number>();
    g.levels.forEach((l, level) => {
      for (let z = 0; z < l.bricks[2]; z++)
        for (let y = 0; y < l.bricks[1]; y++)
          for (let x = 0; x < l.bricks[0]; x++) {
            const key = g.key(level, [x, y, z]);
            expect(g.brickOf(key)).toEqual({ level, brick: [x, y, z] });
            seen.add(key);
          }
    });
    expect(seen.size).toBe(g.brickCount);
    expect(Math.max(...seen)).toBe(g.brickCount - 1);
  });

  it('maps a level-0 brick to the level-l brick that contains it (a 2× pyramid: b0 / 2^l)', () => {
    for (let level = 1; level < g.levels.length; level++)
      for (const b0 of [
        [0, 0, 0],
        [4, 2, 1],
        [3, 1, 0],
      ])
        expect(g.coarseBrickOf(level, b0)).toEqual(
          b0.map((b, a) => Math.min(g.levels[level].bricks[a] - 1, Math.floor(b / 2 ** level))),
        );
  });

  it('fills a slot with the brick and a clamp-to-edge apron', () => {
    const v = source.volumes[0];
    const b = [4, 2, 0]; // the last brick along x and y (partial), the first along z
    const { min, max } = g.readRegion(0, b);
    const slot = fillSlot(g, 0, b, source.readRegionNow(0, min, max), new Uint8Array(18 ** 3));
    const cl = (i: number, n: number) => Math.min(n - 1, Math.max(0, i));
    for (let k = 0; k < 18; k += 1)
      for (const [j, l] of [
        [0, 0],
        [17, 17],
        [5, 9],
        [k, 17 - k],
      ]) {
        const [x, y, z] = [cl(b[0] * 16 - 1 + k, 72), cl(b[1] * 16 - 1 + j, 40), cl(b[2] * 16 - 1 + l, 24)];
        expect(slot[k + 18 * (j + 18 * l)]).toBe(v.data[x + 72 * (y + 40 * z)]);
      }
  });
});

describe('brick cache: residency, LRU eviction, page table', () => {
  const source = inMemoryMultiscaleSource(testVolume(DIMS), { coarsestSide: 16 });
  const g = new BrickGeometry(source.levels, 16);

  it('keeps a constant brick without a slot, its value in the page table', () => {
    const cache = new BrickCache(g, 4);
    load(g, source, cache, [g.key(0, [0, 0, 0])]); // x, y < 16 of this brick's slot: inside the empty corner
    expect(cache.counts()).toEqual({ slots: 0, constant: 1 });
    expect(cache.lookup([0, 0, 0])).toEqual({ kind: 'constant', level: 0, value: 0 });
    const table = cache.pageTable(
      () => [0, 0, 0],
      (v) => v / 255,
      -7,
    );
    expect(Array.from(table.subarray(0, 4))).toEqual([0, 0, 0, -1]);
    expect(Array.from(table.subarray(4, 8))).toEqual([-7, 0, 0, -1]); // brick [1, 0, 0]: nothing yet
  });

  it('serves a level-0 brick that is not resident from the finest resident coarser brick, with its slot origin and level', () => {
    const cache = new BrickCache(g, 8);
    const coarse = g.key(g.coarsest, [0, 0, 0]);
    const l1 = g.key(1, [2, 1, 0]);
    load(g, source, cache, [coarse, l1]);
    expect(cache.lookup([4, 2, 1])).toEqual({ kind: 'slot', level: 1, slot: 1, brick: [2, 1, 0] });
    expect(cache.lookup([0, 0, 0]).kind === 'slot' && cache.lookup([1, 1, 1])).toMatchObject({ level: 3, slot: 0 });
    const table = cache.pageTable(
      (s) => [s * 18, 0, 0],
      (v) => v,
      0,
    );
    const at = (b: number[]) => 4 * (b[0] + 5 * (b[1] + 3 * b[2]));
    expect(Array.from(table.subarray(at([4, 2, 1]), at([4, 2, 1]) + 4))).toEqual([18, 0, 0, 1]);
    expect(Array.from(table.subarray(at([1, 1, 1]), at([1, 1, 1]) + 4))).toEqual([0, 0, 0, 3]);
  });

  it('evicts the least recently used brick not wanted in this frame, and refuses when every slot is wanted now', () => {
    const cache = new BrickCache(g, 2);
    const [a, b, c, d] = [g.key(0, [2, 1, 0]), g.key(0, [3, 1, 0]), g.key(0, [4, 1, 0]), g.key(0, [2, 2, 0])];
    load(g, source, cache, [a], 1);
    load(g, source, cache, [b], 2);
    cache.touch(a, 3); // a wanted again: b is now the least recently used
    load(g, source, cache, [c], 4);
    expect([cache.has(a), cache.has(b), cache.has(c)]).toEqual([true, false, true]);
    cache.touch(a, 5);
    cache.touch(c, 5);
    const values = new Uint8Array(18 ** 3).map((_, i) => i % 7);
    expect(cache.insert(d, { values }, 5)).toBeNull(); // both slots hold bricks wanted in frame 5
    expect(cache.has(d)).toBe(false);
    expect(cache.insert(d, { values }, 6)).not.toBeNull(); // a later frame: the LRU one goes
    expect(cache.counts().slots).toBe(2);
    expect(cache.uploads).toBe(4);
  });
});

describe('bricked sampling (CPU twin) and majorant ranges', () => {
  const volume = testVolume(DIMS);
  const source = inMemoryMultiscaleSource(volume, { coarsestSide: 16 });
  const g = new BrickGeometry(source.levels, 16);
  const allKeys = Array.from({ length: g.brickCount }, (_, k) => g.brickCount - 1 - k); // coarsest level first

  it('a fully resident level 0 samples exactly like the unbricked volume', () => {
    const cache = new BrickCache(g, g.brickCount);
    const slots = load(g, source, cache, allKeys);
    const r = rng(7);
    for (let n = 0; n < 3000; n++) {
      const x0 = DIMS.map((d) => -1 + r() * (d + 2)); // a little outside the box too (clamp-to-edge)
      expect(sampleBricked(g, cache, slots, x0)).toBe(samplePlain(volume, x0));
    }
  }, 60_000);

  it('every cell range holds what the kernels can sample in the cell, for partial residency and unaligned cells', () => {
    // Coarse levels and the level-0 bricks of x < 48: the rest are served by level 1.
    const keys = allKeys.filter((k) => g.brickOf(k).level > 0 || g.brickOf(k).brick[0] < 3);
    const cache = new BrickCache(g, g.brickCount);
    const slots = load(g, source, cache, keys);
    const norm = (v: number) => v / 255;
    for (const cells of [
      [9, 5, 3], // 8-voxel cells, aligned with the bricks' sub-blocks
      [7, 6, 5], // unaligned
      [1, 1, 1],
    ] as [number, number, number][]) {
      const ranges = cache.cellRanges(cells, norm, 0);
      const r = rng(11);
      let coarseSamples = 0;
      // Random points, half of them within a tenth of a voxel of a cell face (where the filter reaches beyond the cell).
      for (let n = 0; n < 8000; n++) {
        const c = cells.map((k) => Math.floor(r() * k));
        const near = n % 2 === 1;
        const x0 = c.map((ci, a) => {
          const w = DIMS[a] / cells[a];
          const t = near ? (r() < 0.5 ? 0.1 * r() : w - 0.1 * r()) / w : r();
          return (ci + t) * w;
        });
        const v = norm(sampleBricked(g, cache, slots, x0));
        const i = c[0] + cells[0] * (c[1] + cells[1] * c[2]);
        expect(v).toBeGreaterThanOrEqual(ranges.vmin[i] - 1e-6);
        expect(v).toBeLessThanOrEqual(ranges.vmax[i] + 1e-6);
        const b0 = x0.map((x) => Math.min(g.levels[0].bricks[0] - 1, Math.floor(x / 16)));
        const e = cache.lookup(b0);
        if (e.kind === 'slot' && e.level > 0) coarseSamples++;
      }
      expect(coarseSamples).toBeGreaterThan(100); // the non-resident bricks were exercised
    }
  }, 60_000);

  it('a non-resident brick is bounded by its coarser level: the cell bound covers the coarse data it is served from', () => {
    const cache = new BrickCache(g, g.brickCount);
    const coarseKeys = allKeys.filter((k) => g.brickOf(k).level > 0);
    load(g, source, cache, coarseKeys); // no level-0 brick at all
    const cells: [number, number, number] = [9, 5, 3];
    const ranges = cache.cellRanges(cells, (v) => v, 0);
    // Cell (6, 2, 1) (voxels 48..56 × 16..24 × 8..16) lies in level-0 brick [3, 1, 0] → level-1
    // brick [1, 0, 0], whose slot is level-1 voxels 15..32 × −1..16 × −1..16, clamped to [36, 20, 12].
    const l1 = source.volumes[1];
    let max = -Infinity,
      min = Infinity;
    for (let z = 0; z <= 11; z++)
      for (let y = 0; y <= 16; y++)
        for (let x = 15; x <= 32; x++) {
          const v = l1.data[x + 36 * (y + 20 * z)];
          max = Math.max(max, v);
          min = Math.min(min, v);
        }
    const i = 6 + 9 * (2 + 5 * 1);
    expect(cache.lookup([3, 1, 0])).toMatchObject({ kind: 'slot', level: 1, brick: [1, 0, 0] });
    expect(ranges.vmax[i]).toBeGreaterThanOrEqual(max);
    expect(ranges.vmin[i]).toBeLessThanOrEqual(min);
  });
});

describe('atlasSlots', () => {
  it('lays out the wanted slots (or as many as a box can) within the budget and the per-axis limit', () => {
    for (const [want, max, perAxis, expected] of [
      [1, 1, 10, 1],
      [95, 100, 20, 95],
      [1000, 700, 30, 700],
      [27, 27, 3, 27],
      [64, 64, 2, 8],
      [57, 17, 60, 17], // the head's bricks under half its bytes: all 17 slots, not a 3 × 3 × 1 box
      [57, 64, 60, 57],
      [50, 10, 4, 9], // 10 slots fit no box with sides ≤ 4
    ]) {
      const [x, y, z] = atlasSlots(want, max, perAxis);
      expect(x * y * z).toBe(expected);
      expect(Math.max(x, y, z)).toBeLessThanOrEqual(perAxis);
    }
  });
});

describe('brick priority (what the view needs, in load order)', () => {
  const source = inMemoryMultiscaleSource(createVolume([64, 64, 64], 'uint8'), { coarsestSide: 16 });
  const g = new BrickGeometry(source.levels, 16); // levels 64³, 32³, 16³: 64 + 8 + 1 bricks
  const level0 = source.levels[0];
  // A narrow view along −z: at most ±0.125 wide across the box, so it sees the central 2 × 2 columns of level-0 bricks.
  const camera = {
    position: [0, 0, 2] as [number, number, number],
    target: [0, 0, 0] as [number, number, number],
    up: [0, 1, 0] as [number, number, number],
    fovy: 0.1,
  };
  const central = (k: number) =>
    g
      .brickOf(k)
      .brick.slice(0, 2)
      .every((b) => b === 1 || b === 2);

  it('without a view: every brick, coarsest level first', () => {
    const keys = brickPriority(g, level0, null);
    expect(keys).toHaveLength(g.brickCount);
    expect(new Set(keys).size).toBe(g.brickCount);
    const levels = keys.map((k) => g.brickOf(k).level);
    expect(levels).toEqual([...levels].sort((a, b) => b - a));
  });

  it('the coarsest level, then the visible bricks level by level, nearest first, then the bricks outside the frustum', () => {
    const keys = brickPriority(g, level0, { camera, width: 64, height: 64, lod: false });
    expect(keys).toHaveLength(g.brickCount);
    expect(new Set(keys).size).toBe(g.brickCount);
    expect(g.brickOf(keys[0]).level).toBe(2);
    expect(keys.slice(1, 9).map((k) => g.brickOf(k).level)).toEqual(new Array(8).fill(1)); // all of level 1 is in view
    const visible = keys.slice(9, 25);
    expect(visible.every((k) => g.brickOf(k).level === 0 && central(k))).toBe(true);
    const z = visible.map((k) => g.brickOf(k).brick[2]);
    expect(z).toEqual([...z].sort((a, b) => b - a)); // the z = 3 layer (nearest the camera) first
    expect(keys.slice(25).every((k) => !central(k))).toBe(true);
  });

  it('level of detail leaves out the bricks finer than the pixels need', () => {
    // 4 pixels high: a level-1 voxel (1/32 of the box) at distance ≥ 1.5 projects to under a pixel, a level-2 one does not.
    const lod = brickPriority(g, level0, { camera, width: 4, height: 4, lod: true });
    expect(lod.slice(0, 9).map((k) => g.brickOf(k).level)).toEqual([2, 1, 1, 1, 1, 1, 1, 1, 1]);
    expect(lod.slice(9).every((k) => !central(k))).toBe(true); // no visible level-0 brick is wanted
    expect(lod).toHaveLength(9 + 48);
  });
});

describe('multichannel bricks (BrickChannels: one component per drawn channel)', () => {
  // Channel 0: the test volume (0 in the corner x, y < 20); channel 1: another field, also 0 in that corner.
  const c0 = testVolume(DIMS);
  const d1 = new Uint8Array(c0.data.length);
  let i = 0;
  for (let z = 0; z < DIMS[2]; z++)
    for (let y = 0; y < DIMS[1]; y++)
      for (let x = 0; x < DIMS[0]; x++, i++)
        d1[i] = x < 20 && y < 20 ? 0 : Math.round(120 + 90 * Math.cos(x / 5 + y / 7 - z / 3));
  const c1 = createVolume(DIMS, 'uint8', d1, [1, 1, 1.5]);
  const both = interleaveChannels([c0, c1]);
  const multi = inMemoryMultiscaleSource(both, { coarsestSide: 16 });
  const scalar = [c0, c1].map((v) => inMemoryMultiscaleSource(v, { coarsestSide: 16 }));
  const g = new BrickGeometry(multi.levels, 16);
  const keys = Array.from({ length: g.brickCount }, (_, k) => g.brickCount - 1 - k);

  it('the source halves every channel as the scalar sources do, and a slot holds each picked channel with its apron', () => {
    expect(multi.channels).toBe(2);
    expect(multi.levels).toEqual(scalar[0].levels);
    for (const key of keys) {
      const { level, brick } = g.brickOf(key);
      const { min, max } = g.readRegion(level, brick);
      const region = multi.readRegionNow(level, min, max);
      const S3 = g.slotSize ** 3;
      const pair = fillSlot(g, level, brick, region, new Uint8Array(2 * S3), 2, [0, 1]);
      const swapped = fillSlot(g, level, brick, region, new Uint8Array(2 * S3), 2, [1, 0]);
      const one = fillSlot(g, level, brick, region, new Uint8Array(S3), 2, [1]);
      const ref = scalar.map((s) => fillSlot(g, level, brick, s.readRegionNow(level, min, max), new Uint8Array(S3)));
      for (let t = 0; t < S3; t++) {
        if (pair[2 * t] !== ref[0][t] || pair[2 * t + 1] !== ref[1][t] || swapped[2 * t] !== ref[1][t])
          throw new Error(`key ${key} texel ${t}: ${pair[2 * t]},${pair[2 * t + 1]} vs ${ref[0][t]},${ref[1][t]}`);
        if (one[t] !== ref[1][t]) throw new Error(`key ${key} texel ${t}: picked channel 1`);
      }
    }
  });

  it('per channel, the cell ranges of a 2-component cache are those of the scalar cache of that channel; a brick is constant only when every channel is one value', () => {
    const loadMulti = (cache: BrickCache, ks: number[]) => {
      for (const key of ks) {
        const { level, brick } = g.brickOf(key);
        const { min, max } = g.readRegion(level, brick);
        const values = fillSlot(
          g,
          level,
          brick,
          multi.readRegionNow(level, min, max),
          new Uint8Array(2 * g.slotSize ** 3),
          2,
          [0, 1],
        );
        cache.insert(key, { values }, 1);
      }
    };
    // Partial residency: the coarse levels and the level-0 bricks of x < 48.
    const partial = keys.filter((k) => g.brickOf(k).level > 0 || g.brickOf(k).brick[0] < 3);
    const cache = new BrickCache(g, g.brickCount, 2);
    loadMulti(cache, partial);
    const caches = scalar.map((s) => {
      const c = new BrickCache(g, g.brickCount);
      load(g, s, c, partial);
      return c;
    });
    // The corner brick [0, 0, 0] is 0 in both channels: constant in every cache.
    expect([...caches, cache].map((c) => c.lookup([0, 0, 0]).kind)).toEqual(['constant', 'constant', 'constant']);
    for (const cells of [
      [9, 5, 3],
      [7, 6, 5],
    ] as [number, number, number][])
      for (const k of [0, 1]) {
        const want = caches[k].cellRanges(cells, (v) => v / 255, 0);
        const got = cache.cellRanges(cells, (v) => v / 255, 0, k);
        expect(Array.from(got.vmin)).toEqual(Array.from(want.vmin));
        expect(Array.from(got.vmax)).toEqual(Array.from(want.vmax));
      }
    // Both channels one value: constant (no slot); channel 0 at 0 and channel 1 at 7: a slot (the page entry holds one value).
    const small = new BrickCache(g, 4, 2);
    const n = 2 * g.slotSize ** 3;
    expect(small.insert(keys[keys.length - 1], { values: new Uint8Array(n) }, 1)).toBe(-1);
    const apart = new Uint8Array(n).map((_, t) => (t % 2 ? 7 : 0));
    expect(small.insert(keys[keys.length - 2], { values: apart }, 1)).toBe(0);
    expect(small.counts()).toEqual({ slots: 1, constant: 1 });
    const r = small.cellRanges([9, 5, 3], (v) => v, 0, 1);
    expect(Math.max(...r.vmax)).toBe(7); // channel 1's range is its own
  });
});
