/**
 * loadVolume's OME-Zarr path: open the store, pick a level (default 0, the finest), read
 * it whole, and finish it like every other format (limits, data range, validation).
 * The levels, the chosen channel and time and the bytes read are in `meta.zarr`, so a
 * caller that loaded the coarsest level knows which finer ones there are.
 */
import type { LoadContext } from '../context.js';
import { LoaderError } from '../errors.js';
import { finishVolume } from '../convert/finish.js';
import type { LoadedVolume, ZarrLoadOptions } from '../types.js';
import { openOmeZarr } from './multiscale-source.js';
import { splitZarrLocation } from './location.js';

export async function loadOmeZarr(location: string, options: ZarrLoadOptions, ctx: LoadContext): Promise<LoadedVolume> {
  const { store, selection } = splitZarrLocation(location);
  const wanted = { ...selection, ...definedOnly(options) };
  const source = await openOmeZarr(store, {
    ...options,
    ...(wanted.channel !== undefined ? { channel: wanted.channel } : {}),
    ...(wanted.time !== undefined ? { time: wanted.time } : {}),
    signal: ctx.signal,
    request: ctx.request,
    // Progress in chunks: their compressed sizes are unknown until they arrive.
    onChunks: (done, total) => ctx.progress('fetch', done, total),
  });
  const last = source.levels.length - 1;
  const level = wanted.level === 'coarsest' ? last : (wanted.level ?? 0);
  if (!Number.isInteger(level) || level < 0 || level > last)
    throw new LoaderError('bad-header', `${ctx.name}: level ${level} does not exist (0 to ${last})`);
  const L = source.levels[level];
  const volume = await source.readLevel(level, ctx.signal);
  ctx.warnings.push(...source.meta.warnings);
  const meta: Record<string, unknown> = {
    zarr: {
      ...source.meta,
      level,
      levels: source.levels,
      bytesRead: source.bytesRead(),
    },
  };
  // As a sidecar's value_range: the viewer and the headless page apply it as the normalization range.
  if (source.valueRange) meta.value_range = source.valueRange;
  return finishVolume(
    {
      format: 'ome-zarr',
      dims: [...L.dims],
      spacing: [...L.spacing],
      type: volume.type,
      data: volume.data,
      // No orientation: NGFF's space axes carry no anatomical direction.
      origin: [...L.origin],
      meta,
    },
    ctx,
  );
}

function definedOnly<T extends object>(o: T): Partial<T> {
  return Object.fromEntries(
    Object.entries(o).filter(([k, v]) => v !== undefined && ['level', 'channel', 'time'].includes(k)),
  ) as Partial<T>;
}
