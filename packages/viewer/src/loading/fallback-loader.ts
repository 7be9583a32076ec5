/**
 * The viewer's own minimal loader, used only when @vpt/loaders is not installed: a URL
 * of a JSON sidecar (data/*.json: dims, voxel_type, spacing, endianness, value_range)
 * with its .raw beside it, read by core's raw reader (scene/raw-sidecar.ts) as @vpt/loaders
 * and the headless page read it. Same interface and error shape as @vpt/loaders' loadVolume,
 * so the element does not care which one ran.
 */
import {
  RawReadError,
  VptError,
  createVolume,
  parseRawSidecar,
  rawFileBeside,
  rawVoxels,
  type Volume,
} from '@vpt/core';
import type { LoadOptions, LoadedVolumeLike, VolumeSource } from './types.js';

export type FallbackReason =
  'not-found' | 'network' | 'truncated' | 'bad-header' | 'unsupported' | 'empty' | 'overflow' | 'aborted' | 'limit';

/** A load failure with the same `reason` field as @vpt/loaders' LoaderError. */
export class ViewerLoadError extends VptError {
  readonly reason: FallbackReason;
  constructor(reason: FallbackReason, message: string, options?: { cause?: unknown }) {
    super(reason === 'limit' ? 'limit-exceeded' : 'load-failed', message, options);
    this.name = 'LoaderError';
    this.reason = reason;
  }
}

/** Fetch a URL's bytes, reporting progress as they arrive. */
async function fetchBytes(url: string, options: LoadOptions): Promise<Uint8Array> {
  let res: Response;
  try {
    res = await fetch(url, { signal: options.signal });
  } catch (e) {
    if ((e as Error).name === 'AbortError')
      throw new ViewerLoadError('aborted', `Loading ${url} was aborted`, { cause: e });
    throw new ViewerLoadError('network', `Could not fetch ${url}: ${(e as Error).message}`, { cause: e });
  }
  if (res.status === 404 || res.status === 410)
    throw new ViewerLoadError('not-found', `${url} was not found (HTTP ${res.status})`);
  if (!res.ok) throw new ViewerLoadError('network', `Could not fetch ${url}: HTTP ${res.status}`);
  const total = Number(res.headers.get('content-length')) || undefined;
  if (!res.body) return new Uint8Array(await res.arrayBuffer());
  const chunks: Uint8Array[] = [];
  let loaded = 0;
  const reader = res.body.getReader();
  for (;;) {
    const { done, value } = await reader.read();
    if (done) break;
    chunks.push(value);
    loaded += value.byteLength;
    options.onProgress?.({ stage: 'fetch', loaded, total });
  }
  const out = new Uint8Array(loaded);
  let at = 0;
  for (const c of chunks) {
    out.set(c, at);
    at += c.byteLength;
  }
  return out;
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
  const text = new TextDecoder().decode(await fetchBytes(url, { ...options, onProgress: undefined }));
  const sidecar = read(() => parseRawSidecar(text, url));
  const { dims } = sidecar;
  const max = options.limits?.maxTextureDimension3D ?? Infinity;
  if (dims.some((d) => d > max))
    throw new ViewerLoadError(
      'limit',
      `${url}: dims [${dims.join(', ')}] exceed this device's 3D texture limit of ${max} per side`,
    );
  const rawUrl = rawFileBeside(url, sidecar);
  const bytes = await fetchBytes(rawUrl, options);
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
