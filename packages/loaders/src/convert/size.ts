import { MAX_RAW_VOXELS, checkRawDims } from '@vpt/core';
import { LoaderError, asLoaderError } from '../errors.js';
import type { LoadContext } from '../context.js';

/** Voxel types found in files; they are converted to core's four on load. */
export type SourceType = 'uint8' | 'int8' | 'uint16' | 'int16' | 'uint32' | 'int32' | 'float32' | 'float64';

export const SOURCE_BYTES: Record<SourceType, number> = {
  uint8: 1,
  int8: 1,
  uint16: 2,
  int16: 2,
  uint32: 4,
  int32: 4,
  float32: 4,
  float64: 8,
};

/** 2^32 voxels: past this, 32-bit sizes (GPU APIs, C readers) wrap; a header claiming it lies or is beyond reach. */
export const MAX_VOXELS = MAX_RAW_VOXELS;

/** Dims straight from a header (core's checkRawDims: positive integers, an addressable count), as a LoaderError. */
export function checkDims(
  dims: readonly number[],
  ctx: LoadContext,
  source = 'header',
): asserts dims is [number, number, number] {
  asLoaderError(() => checkRawDims(dims, ctx.name, source));
}

/**
 * Does a volume of these dims fit the limits? 'fits', or 'downsample' when it does not and
 * the caller asked for downsampling; otherwise a 'limit' error that names the limit.
 */
export function checkFits(dims: readonly number[], bytesPerVoxel: number, ctx: LoadContext): 'fits' | 'downsample' {
  const { maxTextureDimension3D: maxDim, maxBytes } = ctx.limits;
  const largest = Math.max(...dims);
  const bytes = dims[0] * dims[1] * dims[2] * bytesPerVoxel;
  if (largest <= maxDim && bytes <= maxBytes) return 'fits';
  if (ctx.downsample) return 'downsample';
  if (largest > maxDim) {
    throw new LoaderError(
      'limit',
      `${ctx.name}: dims [${dims.join(' × ')}] exceed maxTextureDimension3D = ${maxDim} (the largest 3D texture side this device allows); ` +
        'pass downsample: true to load a smaller copy',
    );
  }
  throw new LoaderError(
    'limit',
    `${ctx.name}: ${bytes} bytes of voxel data exceed maxBytes = ${maxBytes}; pass downsample: true to load a smaller copy, or raise limits.maxBytes`,
  );
}

/** The file holds fewer bytes than the header announces. */
export function checkAvailable(have: number, need: number, ctx: LoadContext, what = 'voxel data'): void {
  if (have < need) {
    throw new LoaderError(
      'truncated',
      `${ctx.name}: the ${what} needs ${need} bytes but only ${Math.max(0, have)} are there; the file is cut short, or its header gives the wrong dims or type`,
    );
  }
}

/**
 * Integer shrink factors per axis so the result fits: each axis at most the texture
 * limit, then all axes together until the bytes fit (the smallest uniform extra factor).
 */
export function downsampleFactors(
  dims: readonly number[],
  bytesPerVoxel: number,
  limits: LoadContext['limits'],
): [number, number, number] {
  const f = dims.map((d) => Math.max(1, Math.ceil(d / limits.maxTextureDimension3D))) as [number, number, number];
  const bytesFor = (g: number[]) => dims.reduce((p, d, i) => p * Math.ceil(d / g[i]), 1) * bytesPerVoxel;
  for (let k = 1; bytesFor(f) > limits.maxBytes; k++) {
    for (let i = 0; i < 3; i++) f[i] = Math.min(dims[i], Math.max(f[i], k));
    if (f.every((x, i) => x === dims[i])) break; // one voxel: cannot shrink further
  }
  return f;
}
