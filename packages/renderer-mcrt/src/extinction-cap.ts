import { volumeBox, type Scene } from '@vpt/core';

/**
 * Optical depth per voxel edge at which MCRT's extinction is capped: exp(−104) ≈ 7e-46 is
 * below the smallest float32 subnormal, so a ray that crosses one voxel edge of medium at the
 * cap already has a transmittance of exactly 0 in float32, as it has at any larger extinction.
 */
export const OPTICAL_DEPTH_PER_VOXEL_MAX = 104;

/**
 * The extinction cap σ_max (per world unit) of a scene: OPTICAL_DEPTH_PER_VOXEL_MAX over the
 * volume's shortest voxel edge in world units. The kernels use min(σ_t, σ_max) for the medium
 * and for the majorant grid's bounds (a min with a constant keeps a majorant a majorant), so
 * delta and ratio tracking take at most σ_max · length tentative collisions along any segment
 * whatever densityScale is: a denser medium is a surface at the data's resolution, and its
 * extra density cannot change what a float32 transmittance through a voxel can represent.
 */
export function extinctionCap(scene: Pick<Scene, 'volume'>): number {
  const box = volumeBox(scene.volume);
  const edge = Math.min(...[0, 1, 2].map((i) => box.size[i] / scene.volume.dims[i]));
  return Math.fround(OPTICAL_DEPTH_PER_VOXEL_MAX / edge);
}
