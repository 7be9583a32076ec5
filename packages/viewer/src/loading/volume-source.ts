/**
 * Turn the element's `src` (or a dropped file) into a Volume: `procedural:<kind>?size=N`
 * in code, everything else through @vpt/loaders when it is installed, else through the
 * small sidecar loader beside this file.
 */
import {
  MAX_PROCEDURAL_SIZE,
  VptError,
  createProceduralVolume,
  type MultiscaleSource,
  type ProceduralKind,
  type RequestPolicy,
} from '@vpt/core';
import { fallbackLoadVolume } from './fallback-loader.js';
import type { LoadOptions, LoadVolumeFn, LoadedVolumeLike, VolumeSource } from './types.js';

const PROCEDURAL: readonly ProceduralKind[] = ['sphere', 'cube', 'ramp', 'blob'];

/**
 * What the loader's errors suggest for headerless raw data: an element attribute cannot
 * reach `options.raw`, so name what `src` can be (a sidecar, or dims and type in the name).
 */
export const ELEMENT_RAW_HINT =
  'point src at a JSON sidecar ({"file": "name.raw", "dims": [NX, NY, NZ], "type": "uint8"}) or put dims and type in the file name (name_128x128x84_uint8.raw)';

let loaderPromise: Promise<{ loadVolume: LoadVolumeFn; name: string }> | null = null;

/** @vpt/loaders' loadVolume when it can be imported, else the fallback (decided once per page). */
export function volumeLoader(): Promise<{ loadVolume: LoadVolumeFn; name: string }> {
  loaderPromise ??= (async () => {
    try {
      // @ts-ignore -- optional package, may be absent when this is type-checked
      const m = (await import('@vpt/loaders')) as { loadVolume?: LoadVolumeFn; __vptMissing?: string };
      if (!m.__vptMissing && typeof m.loadVolume === 'function')
        return { loadVolume: m.loadVolume, name: '@vpt/loaders' };
    } catch {
      // Not installed (or not built): the fallback handles sidecar URLs.
    }
    return { loadVolume: fallbackLoadVolume, name: 'fallback' };
  })();
  return loaderPromise;
}

/** `procedural:blob?size=64` → the volume; null for any other source. */
export function proceduralVolume(source: VolumeSource): LoadedVolumeLike | null {
  if (typeof source !== 'string' || !source.startsWith('procedural:')) return null;
  const url = new URL(source);
  const kind = url.pathname.replace(/^\/+/, '') as ProceduralKind;
  if (!PROCEDURAL.includes(kind))
    throw new VptError('load-failed', `${source}: unknown procedural volume "${kind}" (${PROCEDURAL.join(', ')})`);
  const size = url.searchParams.has('size') ? Number(url.searchParams.get('size')) : 64;
  if (!Number.isInteger(size) || size < 2 || size > MAX_PROCEDURAL_SIZE)
    throw new VptError(
      size > MAX_PROCEDURAL_SIZE ? 'limit-exceeded' : 'load-failed',
      `${source}: size must be an integer in [2, ${MAX_PROCEDURAL_SIZE}] (MAX_PROCEDURAL_SIZE)`,
    );
  return Object.assign(createProceduralVolume(kind, size), { format: 'procedural' });
}

function absolute(url: string): string {
  try {
    return new URL(url, globalThis.document?.baseURI).href;
  } catch {
    return url;
  }
}

/** Loads of one URL in flight, shared by the viewers that ask for it (see sharedLoad). */
const inFlight = new Map<string, { promise: Promise<LoadedVolumeLike>; users: number; abort: AbortController }>();

/**
 * Viewers on one page that load the same URL at the same time (compare.html's four) share
 * one load: parallel fetches of one file made Chromium report all but one as aborted
 * (net::ERR_ABORTED), and fetched it four times. The load is aborted only when every viewer
 * waiting for it has aborted; nothing is kept once it has landed.
 */
function sharedLoad(
  key: string,
  options: LoadOptions,
  start: (signal: AbortSignal) => Promise<LoadedVolumeLike>,
): Promise<LoadedVolumeLike> {
  let entry = inFlight.get(key);
  if (!entry) {
    const abort = new AbortController();
    const promise = start(abort.signal).finally(() => {
      if (inFlight.get(key)?.promise === promise) inFlight.delete(key);
    });
    entry = { promise, users: 0, abort };
    inFlight.set(key, entry);
  }
  const shared = entry;
  shared.users++;
  const signal = options.signal;
  return new Promise<LoadedVolumeLike>((resolve, reject) => {
    const onAbort = () => {
      reject(signal?.reason ?? new DOMException('Loading was aborted', 'AbortError'));
      if (--shared.users === 0) {
        if (inFlight.get(key) === shared) inFlight.delete(key);
        shared.abort.abort();
      }
    };
    if (signal?.aborted) return onAbort();
    signal?.addEventListener('abort', onAbort, { once: true });
    shared.promise.then(
      (v) => {
        signal?.removeEventListener('abort', onAbort);
        resolve(v);
      },
      (e) => {
        signal?.removeEventListener('abort', onAbort);
        reject(e);
      },
    );
  });
}

/** The channel count of the OME-Zarr stores read so far (by URL without fragment): later levels and steps read them all at once. */
const zarrChannels = new Map<string, number>();

export async function loadVolumeSource(source: VolumeSource, options: LoadOptions): Promise<LoadedVolumeLike> {
  const procedural = proceduralVolume(source);
  if (procedural) return procedural;
  const { loadVolume } = await volumeLoader();
  // An OME-Zarr store with a `c` axis whose fragment picks no channel: every channel (up to 16)
  // in one read, once a first read (or an earlier level) said how many there are.
  const store = typeof source === 'string' && !/[#&]channel=/.test(source) ? source.split('#')[0] : '';
  const all = (n: number) => ({ ...options, zarr: { channels: [...Array(Math.min(n, 16)).keys()] } });
  const known = options.zarr ? 0 : (zarrChannels.get(store) ?? 0);
  if (known > 1) return loadVolumeSource(source, all(known));
  const opts: LoadOptions = { rawHint: ELEMENT_RAW_HINT, ...options };
  // Only URLs are shared, with progress from the first viewer that asked (the others see the bar jump).
  const key =
    typeof source === 'string' || source instanceof URL
      ? JSON.stringify([absolute(String(source)), opts.limits ?? null, opts.format ?? null, opts.time ?? 0, opts.zarr])
      : null;
  const volume = key
    ? await sharedLoad(key, opts, (signal) => loadVolume(source, { ...opts, signal }))
    : await loadVolume(source, opts);
  const c = (volume.meta?.zarr as { channels?: number } | undefined)?.channels ?? 1;
  if (c > 1 && store && !opts.zarr) {
    zarrChannels.set(store, c);
    return loadVolumeSource(source, all(c));
  }
  // A file with a channel axis (an NRRD list/vector/colour axis, NIfTI dim[5] or RGB24): channel
  // 0's scalar view carrying the channels' defaults and panel (a lazy chunk: the entry bundle
  // stays within its budget).
  if ((volume.channels ?? 1) > 1) return (await import('../channels.js')).withChannels(volume);
  // A sidecar's value_range maps to [0, 1] for every voxel type, as the headless renderer
  // (vpt-render) reads scene files; @vpt/loaders keeps it in meta only. Applying it here
  // makes the element show exactly what vpt-render renders for the same scene.
  const range = volume.meta?.value_range;
  if (
    !volume.valueRange &&
    Array.isArray(range) &&
    range.length === 2 &&
    range.every(Number.isFinite) &&
    range[1] !== range[0] /* LO > HI inverts */
  ) {
    volume.valueRange = [range[0], range[1]];
  }
  return volume;
}

/**
 * An OME-Zarr `src` opened for region reads in this thread (@vpt/loaders' openOmeZarr, with
 * the channel and time of its fragment, or channel `channel`), for the brick cache (RenderContext.setVolumeSource);
 * null when @vpt/loaders is not installed (the fallback loader cannot read Zarr).
 */
export async function openMultiscaleSource(
  source: string,
  request: Partial<RequestPolicy> = {},
  channel?: number,
): Promise<MultiscaleSource | null> {
  const { name } = await volumeLoader();
  if (name !== '@vpt/loaders') return null;
  // @ts-ignore -- optional package, may be absent when this is type-checked
  const m = (await import('@vpt/loaders')) as {
    openOmeZarr: (
      location: string,
      o: { channel?: number; time?: number; request?: Partial<RequestPolicy> },
    ) => Promise<MultiscaleSource>;
    splitZarrLocation: (location: string) => { store: string; selection: { channel?: number; time?: number } };
  };
  const { store, selection: fragment } = m.splitZarrLocation(source);
  // `channel`: one channel of a store streamed with all its channels (channels.ts, StreamedChannels).
  const selection = channel !== undefined ? { ...fragment, channel } : fragment;
  // The worker resolves a relative src against the page; so does this thread.
  const location = typeof document !== 'undefined' ? new URL(store, document.baseURI).href : store;
  return m.openOmeZarr(location, {
    ...(selection.channel !== undefined ? { channel: selection.channel } : {}),
    ...(selection.time !== undefined ? { time: selection.time } : {}),
    request,
  });
}
