import { VptError } from '../errors.js';
import { createVolume, type Volume } from './volume.js';
import { MAX_PROCEDURAL_SIZE } from '../validation/limits.js';

export type ProceduralKind = 'sphere' | 'cube' | 'ramp' | 'blob';

/**
 * Test volumes defined in code (float32, values in [0, 1], cubic, isotropic):
 *  - sphere: 1 inside radius 0.35 of the box, 0 outside, with a one-voxel linear edge
 *  - cube:   constant 1 everywhere (a homogeneous medium filling the box)
 *  - ramp:   value = x / (N - 1), linear along x
 *  - blob:   a smooth Gaussian, exp(-r² / (2·0.18²)) in box units
 */
export function createProceduralVolume(kind: ProceduralKind, size = 32): Volume {
  if (!Number.isInteger(size) || size < 2)
    throw new VptError('invalid-scene', `Procedural volume size must be an integer >= 2, got ${size}`);
  if (size > MAX_PROCEDURAL_SIZE)
    throw new VptError(
      'limit-exceeded',
      `Procedural volume size ${size} exceeds the limit of ${MAX_PROCEDURAL_SIZE} voxels per side (MAX_PROCEDURAL_SIZE)`,
    );
  if (!['sphere', 'cube', 'ramp', 'blob'].includes(kind))
    throw new VptError('invalid-scene', `Unknown procedural volume "${kind as string}" (sphere, cube, ramp, blob)`);
  const data = new Float32Array(size * size * size);
  for (let z = 0; z < size; z++) {
    for (let y = 0; y < size; y++) {
      for (let x = 0; x < size; x++) {
        // Voxel centre in box units [-0.5, 0.5] (cell-centred, docs/design.md).
        const px = (x + 0.5) / size - 0.5,
          py = (y + 0.5) / size - 0.5,
          pz = (z + 0.5) / size - 0.5;
        const r = Math.hypot(px, py, pz);
        let v: number;
        switch (kind) {
          case 'sphere':
            v = Math.min(1, Math.max(0, (0.35 - r) * size + 0.5));
            break;
          case 'cube':
            v = 1;
            break;
          case 'ramp':
            v = x / (size - 1);
            break;
          case 'blob':
            v = Math.exp(-(r * r) / (2 * 0.18 * 0.18));
            break;
          default:
            throw new VptError(
              'invalid-scene',
              `Unknown procedural volume "${kind as string}" (sphere, cube, ramp, blob)`,
            );
        }
        data[x + size * (y + size * z)] = v;
      }
    }
  }
  const vol = createVolume([size, size, size], 'float32', data);
  vol.valueRange = [0, 1];
  vol.name = `${kind}-${size}`;
  return vol;
}
