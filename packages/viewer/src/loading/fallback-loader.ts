/**
 * The viewer's own minimal loader, used only when @vpt/loaders is not installed: a URL
 * of a JSON sidecar (data/*.json: dims, voxel_type, spacing, endianness, value_range)
 * with its .raw beside it. Same interface and error shape as @vpt/loaders' loadVolume,
 * so the element does not care which one ran.
 */
import { VptError, createVolume, type Volume, type VoxelType } from '@vpt/core';
import type { LoadOptions, LoadedVolumeLike, VolumeSource } from './types.js';

export type FallbackReason = 'not-found' | 'network' | 'truncated' | 'bad-header' | 'unsupported' | 'aborted' | 'limit';

/** A load failure with the same `reason` field as @vpt/loaders' LoaderError. */
export class ViewerLoadError extends VptError {
  readonly reason: FallbackReason;
  constructor(reason: FallbackReason, message: string, options?: { cause?: unknown }) {
    super(reason === 'limit' ? 'limit-exceeded' : 'load-failed', message, options);
    this.name = 'LoaderError';
    this.reason = reason;
  }
}

const ARRAYS = { uint8: Uint8Array, uint16: Uint16Array, int16: Int16Array, float32: Float32Array } as const;

/** Fetch a URL's bytes, reporting progress as they arrive. */
async function fetchBytes(url: string, options: LoadOptions): Promise<Uint8Array> {
  let res: Response;
  try {
    res = await fetch(url, { signal: options.signal });
  } catch (e) {
    if ((e as Error).name === 'AbortError') throw new ViewerLoadError('aborted', `Loading ${url} was aborted`, { cause: e });
    throw new ViewerLoadError('network', `Could not fetch ${url}: ${(e as Error).message}`, { cause: e });
  }
  if (res.status === 404 || res.status === 410) throw new ViewerLoadError('not-found', `${url} was not found (HTTP ${res.status})`);
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
  for (const c of chunks) { out.set(c, at); at += c.byteLength; }
  return out;
}

function sidecarField<T>(meta: Record<string, unknown>, key: string, ok: (v: unknown) => boolean, url: string): T {
  const v = meta[key];
  if (!ok(v)) throw new ViewerLoadError('bad-header', `${url}: the sidecar's "${key}" is missing or malformed (got ${JSON.stringify(v)})`);
  return v as T;
}

const isVec3 = (v: unknown) => Array.isArray(v) && v.length === 3 && v.every((x) => typeof x === 'number' && Number.isFinite(x) && x > 0);

async function loadSidecar(url: string, options: LoadOptions): Promise<LoadedVolumeLike> {
  const text = new TextDecoder().decode(await fetchBytes(url, { ...options, onProgress: undefined }));
  let meta: Record<string, unknown>;
  try {
    meta = JSON.parse(text);
  } catch (e) {
    throw new ViewerLoadError('bad-header', `${url}: the sidecar is not valid JSON (${(e as Error).message})`, { cause: e });
  }
  const dims = sidecarField<[number, number, number]>(meta, 'dims', (v) => isVec3(v) && (v as number[]).every(Number.isInteger), url);
  const type = sidecarField<VoxelType>(meta, 'voxel_type', (v) => typeof v === 'string' && v in ARRAYS, url);
  const spacing = meta.spacing === undefined ? [1, 1, 1] as [number, number, number] : sidecarField<[number, number, number]>(meta, 'spacing', isVec3, url);
  const max = options.limits?.maxTextureDimension3D ?? Infinity;
  if (dims.some((d) => d > max)) throw new ViewerLoadError('limit', `${url}: dims [${dims.join(', ')}] exceed this device's 3D texture limit of ${max} per side`);
  const file = typeof meta.file === 'string' && !meta.file.includes('/') ? meta.file : url.split(/[?#]/)[0].split('/').pop()!.replace(/\.json$/i, '') + '.raw';
  const rawUrl = new URL(file, url).href;
  const bytes = await fetchBytes(rawUrl, options);
  const Ctor = ARRAYS[type as keyof typeof ARRAYS];
  const expected = dims[0] * dims[1] * dims[2] * Ctor.BYTES_PER_ELEMENT;
  if (bytes.byteLength < expected) throw new ViewerLoadError('truncated', `${rawUrl}: dims [${dims.join(', ')}] of ${type} need ${expected} bytes, the file has ${bytes.byteLength}`);
  if (bytes.byteLength > expected) throw new ViewerLoadError('bad-header', `${rawUrl}: dims [${dims.join(', ')}] of ${type} need ${expected} bytes, the file has ${bytes.byteLength} (wrong dims or type in the sidecar?)`);
  if (meta.endianness === 'big' && Ctor.BYTES_PER_ELEMENT > 1) {
    for (let i = 0; i < bytes.length; i += Ctor.BYTES_PER_ELEMENT) bytes.subarray(i, i + Ctor.BYTES_PER_ELEMENT).reverse();
  }
  const volume: Volume = createVolume(dims, type, new Ctor(bytes.buffer as ArrayBuffer, 0, expected / Ctor.BYTES_PER_ELEMENT), spacing);
  const range = meta.value_range;
  if (Array.isArray(range) && range.length === 2 && range.every(Number.isFinite) && range[1] !== range[0] /* LO > HI inverts */) {
    // As the headless page does: the sidecar's range maps to [0, 1] for every voxel type.
    volume.valueRange = range as [number, number];
  }
  volume.name = file;
  // A sidecar's "axes" ('PIR'…): the anatomical direction of each index axis, for the default camera.
  const axisCodes = typeof meta.axes === 'string' ? meta.axes.toUpperCase() : undefined;
  return Object.assign(volume, { format: 'raw', meta: axisCodes ? { axisCodes, space: 'RAS' } : {} });
}

export async function fallbackLoadVolume(source: VolumeSource, options: LoadOptions = {}): Promise<LoadedVolumeLike> {
  if (typeof source !== 'string' && !(source instanceof URL)) {
    throw new ViewerLoadError('unsupported', 'Loading files or bytes needs @vpt/loaders, which is not installed; only URLs of a JSON sidecar (with its .raw beside it) load without it');
  }
  const url = new URL(String(source), globalThis.document?.baseURI ?? undefined).href;
  if (/\.json([?#]|$)/i.test(url)) return loadSidecar(url, options);
  throw new ViewerLoadError('unsupported', `${url}: this format needs @vpt/loaders, which is not installed (without it only a JSON sidecar URL loads, with its .raw beside it)`);
}
