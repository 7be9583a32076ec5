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
import {
  levelChunkCount,
  MAX_ZARR_CHUNKS_PER_READ,
  MAX_ZARR_READ_VOXELS,
  openOmeZarr,
  type MultiscaleLevel,
} from './multiscale-source.js';

const OUTPUT_BYTES = { uint8: 1, uint16: 2, int16: 2, float32: 4 } as const;

/** Why a whole level cannot be read within the load's limits (null: it can). */
function whyNotWhole(L: MultiscaleLevel, bytesPerVoxel: number, ctx: LoadContext): string | null {
  const voxels = L.dims[0] * L.dims[1] * L.dims[2];
  if (voxels > MAX_ZARR_READ_VOXELS) return `${voxels} voxels, more than one read holds`;
  if (voxels * bytesPerVoxel > ctx.limits.maxBytes)
    return `${voxels * bytesPerVoxel} bytes, more than the ${ctx.limits.maxBytes} allowed`;
  if (L.dims.some((n) => n > ctx.limits.maxTextureDimension3D))
    return `a side beyond the ${ctx.limits.maxTextureDimension3D}-voxel 3D texture limit`;
  const chunks = levelChunkCount(L);
  if (chunks > MAX_ZARR_CHUNKS_PER_READ) return `${chunks} chunks, more than ${MAX_ZARR_CHUNKS_PER_READ} requests`;
  return null;
}
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
  let level = wanted.level === 'coarsest' ? last : (wanted.level ?? 0);
  if (!Number.isInteger(level) || level < 0 || level > last)
    throw new LoaderError('bad-header', `${ctx.name}: level ${level} does not exist (0 to ${last})`);
  const picked = options.channels;
  if (picked !== undefined && (!Array.isArray(picked) || picked.length < 1 || picked.length > 16))
    throw new LoaderError(
      'bad-header',
      `${ctx.name}: zarr.channels must list 1 to 16 channel indices along c, got ${JSON.stringify(picked)}`,
    );
  const K = picked?.length ?? 1;
  const per = OUTPUT_BYTES[source.type] * K;
  const why = whyNotWhole(source.levels[level], per, ctx);
  if (why && wanted.level === undefined) {
    // No level asked for and the finest does not fit: the finest stored level that does.
    const fitting = source.levels.findIndex((L) => whyNotWhole(L, per, ctx) === null);
    if (fitting < 0)
      throw new LoaderError(
        'limit',
        `${ctx.name}: no level can be read whole (level 0 has ${why}; the coarsest, level ${last}, has ${whyNotWhole(source.levels[last], per, ctx)})`,
      );
    ctx.warnings.push(`level ${fitting} [${source.levels[fitting].dims.join(', ')}] is read: level 0 has ${why}`);
    level = fitting;
  } else if (why && /chunks|voxels, more than one read/.test(why)) {
    // A level asked for by name that no read can hold: refused before any request (bytes and sides downsample or fail in finishVolume).
    throw new LoaderError('limit', `${ctx.name}: level ${level} has ${why}; choose a coarser level`);
  }
  const L = source.levels[level];
  // Several channels: one read over the level's chunks, interleaved channel fastest.
  const volume = picked
    ? {
        type: source.type,
        data: await source.readChannelsRegion!(level, picked, [0, 0, 0], L.dims, ctx.signal),
      }
    : await source.readLevel(level, ctx.signal);
  ctx.warnings.push(...source.meta.warnings);
  const meta: Record<string, unknown> = {
    timeSteps: source.meta.times,
    zarr: {
      ...source.meta,
      level,
      levels: source.levels,
      bytesRead: source.bytesRead(),
    },
  };
  // As a sidecar's value_range: the viewer and the headless page apply it as the normalization range.
  if (picked) {
    // Each channel's omero window: the default ranges of a channel scene.
    (meta.zarr as Record<string, unknown>).channelsRead = [...picked];
    meta.channelRanges = picked.map((k) => source.channelWindows?.[k] ?? null);
    // Their omero labels and display colours (hex RRGGBB, sRGB): the viewer's names and default colours.
    meta.channelLabels = picked.map((k) => source.channelInfo?.[k]?.label ?? null);
    meta.channelColors = picked.map((k) => source.channelInfo?.[k]?.color ?? null);
    if (K === 1 && source.channelWindows?.[picked[0]]) meta.value_range = source.channelWindows[picked[0]];
  } else if (source.valueRange) meta.value_range = source.valueRange;
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
      ...(K > 1 ? { channels: K } : {}),
    },
    ctx,
  );
}

function definedOnly<T extends object>(o: T): Partial<T> {
  return Object.fromEntries(
    Object.entries(o).filter(([k, v]) => v !== undefined && ['level', 'channel', 'time'].includes(k)),
  ) as Partial<T>;
}
