/**
 * Volumes for the clipping tests (tests/clip.test.ts), built the same way in the page and in
 * Node: `bandedVolume` zeroes every voxel whose centre lies within `band` of a cut surface (a
 * clip plane, or a face plane of the crop box), on both sides; `zeroedVolume` then zeroes the
 * voxels the clip removes. Trilinear interpolation reads voxels within one voxel of a point, so
 * with a band of more than one voxel the two volumes hold the same medium in the kept region and
 * the zeroed one is exactly 0 in the removed region: rendering the banded volume clipped and the
 * zeroed one unclipped must give the same image in expectation (MCRT) or up to the march's
 * discretisation (EAM, MIP). Node side: the tests send the voxels to the page.
 */
import type { Clip, Volume } from '@vpt/core';

/** A copy of a float32 N³ cube volume (box [-0.5, 0.5]³, cell-centred voxels) with the voxels for which `drop(centre)` holds set to 0. */
export function maskVolume(v: Volume, drop: (p: [number, number, number]) => boolean): Volume {
  const n = v.dims[0];
  const src = v.data as Float32Array;
  const data = new Float32Array(src.length);
  for (let z = 0; z < n; z++)
    for (let y = 0; y < n; y++)
      for (let x = 0; x < n; x++) {
        const i = x + n * (y + n * z);
        const c = [(x + 0.5) / n - 0.5, (y + 0.5) / n - 0.5, (z + 0.5) / n - 0.5] as [number, number, number];
        data[i] = drop(c) ? 0 : src[i];
      }
  return { ...v, data, name: `${v.name ?? 'volume'}-masked` };
}

/** Whether p lies within `band` of a cut surface of the clip. */
export function nearCut(clip: Clip, p: [number, number, number], band: number): boolean {
  for (const pl of clip.planes ?? []) {
    const len = Math.hypot(...pl.normal);
    const s = (pl.normal[0] * p[0] + pl.normal[1] * p[1] + pl.normal[2] * p[2] - pl.offset) / len;
    if (Math.abs(s) < band) return true;
  }
  const b = clip.box;
  if (b)
    for (let i = 0; i < 3; i++) if (Math.abs(p[i] - b.min[i]) < band || Math.abs(p[i] - b.max[i]) < band) return true;
  return false;
}

/** The CPU's judgement of a point (twin of the kernels' isClipped). */
export function clippedAt(clip: Clip, p: [number, number, number]): boolean {
  for (const pl of clip.planes ?? [])
    if (pl.normal[0] * p[0] + pl.normal[1] * p[1] + pl.normal[2] * p[2] > pl.offset) return true;
  const b = clip.box;
  return !!b && [0, 1, 2].some((i) => p[i] < b.min[i] || p[i] > b.max[i]);
}
