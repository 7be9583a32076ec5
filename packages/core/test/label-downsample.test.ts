import { describe, expect, it } from 'vitest';
import { createVolume } from '../src/index.js';
import { downsampleLabels } from '../src/scene/label-downsample.js';

// Majority-vote downsampling of label volumes (scene/label-downsample.ts), on blocks whose
// vote is known by construction.
describe('downsampleLabels', () => {
  it('takes the id most voxels of each block hold, never a blend, and keeps the box', () => {
    // 4×2×2 by [2, 2, 2]: block 0 (x < 2) holds id 3 five times and 7 three times; block 1 (x ≥ 2)
    // holds 7 six times and 0 twice. A mean would give 4.5 and 5.25: ids neither block holds.
    const v = createVolume([4, 2, 2], 'uint8', new Uint8Array(16), [0.5, 1, 2]);
    const block0 = [3, 3, 3, 3, 3, 7, 7, 7];
    const block1 = [7, 7, 7, 7, 7, 7, 0, 0];
    let k = 0;
    for (let z = 0; z < 2; z++)
      for (let y = 0; y < 2; y++, k += 2) {
        v.data[0 + 4 * (y + 2 * z)] = block0[k];
        v.data[1 + 4 * (y + 2 * z)] = block0[k + 1];
        v.data[2 + 4 * (y + 2 * z)] = block1[k];
        v.data[3 + 4 * (y + 2 * z)] = block1[k + 1];
      }
    const d = downsampleLabels(v, [2, 2, 2]);
    expect(d.dims).toEqual([2, 1, 1]);
    expect(d.type).toBe('uint8');
    expect(Array.from(d.data)).toEqual([3, 7]);
    expect(d.spacing).toEqual([1, 2, 4]);
  });

  it('breaks ties toward the smaller id, and the background loses every tie', () => {
    // Blocks of 2 along x: (5, 2) → 2; (0, 9) → 9; (9, 0) → 9; (0, 0) → 0.
    const v = createVolume([8, 1, 1], 'uint16', Uint16Array.from([5, 2, 0, 9, 9, 0, 0, 0]));
    expect(Array.from(downsampleLabels(v, [2, 1, 1]).data)).toEqual([2, 9, 9, 0]);
  });

  it('lets a partial block at the far edge vote with the voxels it has', () => {
    // 5 voxels by 2: blocks (1, 1), (4, 4), (6) → the last holds only id 6.
    const v = createVolume([5, 1, 1], 'uint8', Uint8Array.from([1, 1, 4, 4, 6]));
    const d = downsampleLabels(v, [2, 1, 1]);
    expect(d.dims).toEqual([3, 1, 1]);
    expect(Array.from(d.data)).toEqual([1, 4, 6]);
  });

  it('on a random volume every output id is one its block holds, and the most frequent there', () => {
    let seed = 12345;
    const rand = () => ((seed = (seed * 1103515245 + 12345) >>> 0) >>> 16) / 65536;
    const n = [9, 7, 5] as [number, number, number];
    const v = createVolume(n, 'uint16', new Uint16Array(n[0] * n[1] * n[2]));
    for (let i = 0; i < v.data.length; i++) v.data[i] = Math.floor(rand() * 4) * 1000;
    const f = [3, 2, 2] as [number, number, number];
    const d = downsampleLabels(v, f);
    for (let oz = 0; oz < d.dims[2]; oz++)
      for (let oy = 0; oy < d.dims[1]; oy++)
        for (let ox = 0; ox < d.dims[0]; ox++) {
          const votes = new Map<number, number>();
          for (let z = oz * f[2]; z < Math.min(n[2], (oz + 1) * f[2]); z++)
            for (let y = oy * f[1]; y < Math.min(n[1], (oy + 1) * f[1]); y++)
              for (let x = ox * f[0]; x < Math.min(n[0], (ox + 1) * f[0]); x++) {
                const id = v.data[x + n[0] * (y + n[1] * z)];
                votes.set(id, (votes.get(id) ?? 0) + 1);
              }
          const got = d.data[ox + d.dims[0] * (oy + d.dims[1] * oz)];
          expect(votes.has(got)).toBe(true);
          expect(votes.get(got)).toBe(Math.max(...votes.values()));
        }
  });
});
