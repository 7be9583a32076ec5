/**
 * Integer box-average downsampling of a volume, for volumes that exceed the GPU memory
 * budget or the device's 3D texture size (RenderContext). Each output voxel averages the
 * block of factor[0] × factor[1] × factor[2] input voxels it covers (a partial block at the
 * far edge averages what it has); spacing is multiplied by the factors, so the box keeps
 * its shape. Integer types round to the nearest integer; non-finite float voxels are left
 * out of their block's mean.
 */
import {
  channelCount,
  channelVolume,
  createVolume,
  interleaveChannels,
  type Volume,
  type VoxelArray,
} from './volume.js';

export function downsampleVolume(volume: Volume, factors: readonly [number, number, number]): Volume {
  const [fx, fy, fz] = factors;
  const [nx, ny, nz] = volume.dims;
  const dims: [number, number, number] = [Math.ceil(nx / fx), Math.ceil(ny / fy), Math.ceil(nz / fz)];
  const [mx, my, mz] = dims;
  const src = volume.data;
  const sum = new Float64Array(mx * my);
  const count = new Float64Array(mx * my);
  const out = volume.type === 'float32' ? new Float32Array(mx * my * mz) : null;
  const result: VoxelArray = out ?? new (src.constructor as new (n: number) => VoxelArray)(mx * my * mz);
  for (let oz = 0; oz < mz; oz++) {
    sum.fill(0);
    count.fill(0);
    for (let z = oz * fz; z < Math.min(nz, (oz + 1) * fz); z++) {
      for (let y = 0; y < ny; y++) {
        const rowOut = mx * Math.floor(y / fy);
        const rowIn = nx * (y + ny * z);
        for (let x = 0; x < nx; x++) {
          const v = src[rowIn + x];
          if (!Number.isFinite(v)) continue;
          const k = rowOut + Math.floor(x / fx);
          sum[k] += v;
          count[k]++;
        }
      }
    }
    const base = mx * my * oz;
    for (let k = 0; k < mx * my; k++) {
      const mean = count[k] > 0 ? sum[k] / count[k] : 0;
      result[base + k] = out ? mean : Math.round(mean);
    }
  }
  const spacing = volume.spacing.map((s, i) => s * factors[i]) as [number, number, number];
  const v = createVolume(dims, volume.type, result, spacing);
  if (volume.valueRange) v.valueRange = [volume.valueRange[0], volume.valueRange[1]];
  if (volume.name) v.name = volume.name;
  return v;
}

/**
 * Per-axis integer factors giving the largest volume that fits: every side ≤ max3D and
 * voxels × bytesPerVoxel ≤ budgetBytes. Grows the factor of the axis with the most output
 * voxels first, so the result stays as close to isotropic as the input allows. [1, 1, 1]
 * when the volume fits as it is; null when not even one voxel fits.
 */
export function fitFactors(
  dims: readonly [number, number, number],
  bytesPerVoxel: number,
  budgetBytes: number,
  max3D: number,
): [number, number, number] | null {
  if (!(budgetBytes >= bytesPerVoxel)) return null;
  const f: [number, number, number] = [0, 1, 2].map((i) => Math.max(1, Math.ceil(dims[i] / max3D))) as [
    number,
    number,
    number,
  ];
  const out = (i: number) => Math.ceil(dims[i] / f[i]);
  while (out(0) * out(1) * out(2) * bytesPerVoxel > budgetBytes) {
    let axis = 0;
    for (let i = 1; i < 3; i++) if (out(i) > out(axis)) axis = i;
    // Skip factors that leave the side unchanged (ceil plateaus), so every step shrinks the volume.
    const side = out(axis);
    while (out(axis) === side) f[axis]++;
  }
  return f;
}

/** A multichannel volume downsampled channel by channel (the same box averages), interleaved again. */
export function downsampleChannels(v: Volume, factors: readonly [number, number, number]): Volume {
  const parts = Array.from({ length: channelCount(v) }, (_, c) => downsampleVolume(channelVolume(v, c), factors));
  const out = interleaveChannels(parts);
  return { ...out, ...(v.valueRange ? { valueRange: v.valueRange } : {}), ...(v.name ? { name: v.name } : {}) };
}
