/**
 * The viewer's own minimal loader, used only when @vpt/loaders is not installed: a URL
 * of a JSON sidecar (data/*.json: dims, voxel_type, spacing, endianness, value_range)
 * with its .raw beside it, read by core's raw reader (scene/raw-sidecar.ts) as @vpt/loaders
 * and the headless page read it. Same interface and error shape as @vpt/loaders' loadVolume,
 * so the element does not care which one ran.
 */
import {
  RawReadError,
  RequestError,
  VptError,
  fetchWithPolicy,
  createVolume,
  parseRawSidecar,
  rawFileBeside,
  rawVoxels,
  type Volume,
} from '@vpt/core';
import type { LoadOptions, LoadedVolumeLike, VolumeSource } from './types.js';

export type FallbackReason =
  'not-found' | 'network' | 'truncated' | 'bad-header' | 'unsupported' | 'empty' | 'overflow' | 'aborted' | 'limit';

/** Largest sidecar fetched (as @vpt/loaders bounds its text files). */
const MAX_SIDECAR_BYTES = 16 * 1024 * 1024;
const BYTES_PER_VOXEL = { uint8: 1, uint16: 2, int16: 2, float32: 4 } as const;

/** A load failure with the same `reason` field as @vpt/loaders' LoaderError. */
export class ViewerLoadError extends VptError {
  readonly reason: FallbackReason;
  constructor(reason: FallbackReason, message: string, options?: { cause?: unknown }) {
    super(reason === 'limit' ? 'limit-exceeded' : 'load-failed', message, options);
    this.name = 'LoaderError';
    this.reason = reason;
  }
}

/** A URL's bytes under core's request policy, reporting progress as they arrive. */
async function fetchBytes(url: string, options: LoadOptions, maxBytes: number): Promise<Uint8Array> {
  try {
    const { bytes } = await fetchWithPolicy(url, {
      signal: options.signal,
      policy: options.request,
      maxBytes,
      onProgress: (loaded, total) => options.onProgress?.({ stage: 'fetch', loaded, total }),
    });
    return bytes;
  } catch (e) {
    if (e instanceof RequestError) throw new ViewerLoadError(e.reason, e.message, { cause: e });
    throw e;
  }
}

/** Core's raw reader, its RawReadError as a ViewerLoadError with the same reason and message. */
function read<T>(fn: () => T): T {
  try {
    return fn();
  } catch (e) {
    if (e instanceof RawReadError) throw new ViewerLoadError(e.reason, e.message, { cause: e });
    throw e;
  }
}

async function loadSidecar(url: string, options: LoadOptions): Promise<LoadedVolumeLike> {
  const text = new TextDecoder().decode(
    await fetchBytes(url, { ...options, onProgress: undefined }, MAX_SIDECAR_BYTES),
  );
  const sidecar = read(() => parseRawSidecar(text, url));
  const { dims } = sidecar;
  const max = options.limits?.maxTextureDimension3D ?? Infinity;
  if (dims.some((d) => d > max))
    throw new ViewerLoadError(
      'limit',
      `${url}: dims [${dims.join(', ')}] exceed this device's 3D texture limit of ${max} per side`,
    );
  const rawUrl = rawFileBeside(url, sidecar);
  // A raw file holds exactly dims × type bytes (rawVoxels checks it): nothing longer is read.
  const bytes = await fetchBytes(rawUrl, options, dims[0] * dims[1] * dims[2] * BYTES_PER_VOXEL[sidecar.type]);
  const volume: Volume = createVolume(
    dims,
    sidecar.type,
    read(() => rawVoxels(bytes, sidecar, rawUrl)),
    sidecar.spacing,
  );
  // As the headless page does: the sidecar's range maps to [0, 1] for every voxel type (min > max inverts).
  if (sidecar.valueRange) volume.valueRange = sidecar.valueRange;
  volume.name = rawUrl.split('/').pop();
  // A sidecar's "axes" ('PIR'…): the anatomical direction of each index axis, for the default camera.
  return Object.assign(volume, {
    format: 'raw',
    meta: sidecar.axisCodes ? { axisCodes: sidecar.axisCodes, space: 'RAS' } : {},
  });
}

export async function fallbackLoadVolume(source: VolumeSource, options: LoadOptions = {}): Promise<LoadedVolumeLike> {
  if (typeof source !== 'string' && !(source instanceof URL)) {
    throw new ViewerLoadError(
      'unsupported',
      'Loading files or bytes needs @vpt/loaders, which is not installed; only URLs of a JSON sidecar (with its .raw beside it) load without it',
    );
  }
  const url = new URL(String(source), globalThis.document?.baseURI ?? undefined).href;
  if (/\.json([?#]|$)/i.test(url)) return loadSidecar(url, options);
  throw new ViewerLoadError(
    'unsupported',
    `${url}: this format needs @vpt/loaders, which is not installed (without it only a JSON sidecar URL loads, with its .raw beside it)`,
  );
}
