/**
 * A label volume downsampled for the GPU memory budget's fit (context/volume-fit.ts) by
 * majority vote: each output voxel takes the id held by most voxels of its block of
 * factor[0] × factor[1] × factor[2] input voxels (a partial block at the far edge votes with
 * what it has), never an average, so no id that the block does not hold appears (the mode
 * downsampling segmentation viewers such as Neuroglancer use). A tie goes to the smaller id,
 * except that the background (0) loses every tie, so a label as thick as half a block stays.
 * Spacing is multiplied by the factors, as downsampleVolume does for the image, so the two keep
 * one box.
 */
import { createVolume, type Volume } from './volume.js';

export function downsampleLabels(volume: Volume, factors: readonly [number, number, number]): Volume {
  const [fx, fy, fz] = factors;
  const [nx, ny, nz] = volume.dims;
  const dims: [number, number, number] = [Math.ceil(nx / fx), Math.ceil(ny / fy), Math.ceil(nz / fz)];
  const [mx, my, mz] = dims;
  const src = volume.data;
  const out = volume.type === 'uint8' ? new Uint8Array(mx * my * mz) : new Uint16Array(mx * my * mz);
  // Votes per id for one block, and the ids it touched (reset after each block).
  const votes = new Uint32Array(volume.type === 'uint8' ? 256 : 65536);
  const touched = new Uint32Array(fx * fy * fz);
  for (let oz = 0; oz < mz; oz++)
    for (let oy = 0; oy < my; oy++)
      for (let ox = 0; ox < mx; ox++) {
        let n = 0;
        for (let z = oz * fz; z < Math.min(nz, (oz + 1) * fz); z++)
          for (let y = oy * fy; y < Math.min(ny, (oy + 1) * fy); y++) {
            const row = nx * (y + ny * z);
            for (let x = ox * fx; x < Math.min(nx, (ox + 1) * fx); x++) {
              const id = src[row + x];
              if (votes[id]++ === 0) touched[n++] = id;
            }
          }
        let best = touched[0],
          most = votes[best];
        for (let k = 1; k < n; k++) {
          const id = touched[k],
            c = votes[id];
          if (c > most || (c === most && (best === 0 || (id !== 0 && id < best)))) {
            best = id;
            most = c;
          }
        }
        for (let k = 0; k < n; k++) votes[touched[k]] = 0;
        out[ox + mx * (oy + my * oz)] = best;
      }
  const spacing = volume.spacing.map((s, i) => s * factors[i]) as [number, number, number];
  const v = createVolume(dims, volume.type, out, spacing);
  if (volume.name) v.name = volume.name;
  return v;
}

/** Bytes a voxel of the label volume takes on the GPU (labels.ts labelVolumeTexture's formats). */
export function labelBytesPerVoxel(type: Volume['type'], norm16: boolean): number {
  return type === 'uint8' ? 1 : norm16 ? 2 : 4;
}
