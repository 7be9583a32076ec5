/**
 * An OME-Zarr image opened for reading: its levels (finest first) with dims, spacing,
 * origin and chunk shape along x, y, z, and reads of a box or a whole level as one of
 * core's voxel types. zarrita does the Zarr part (v2 and v3 metadata, chunk keys, codecs
 * Blosc / zstd / gzip / zlib / lz4, sharding); this module picks the channel and time
 * point, orders the result x fastest and converts the data type.
 */
import * as zarr from 'zarrita';
import { createVolume, type Volume, type VoxelArray, type VoxelType } from '@vpt/core';
import { LoaderError, isAbort } from '../errors.js';
import { parseOmeMultiscales, type ImageLabelEntry, type OmeMultiscale, type Vec3 } from './ome-metadata.js';
import { openZarrStore, type CountingStore, type ZarrStoreOptions } from './store.js';

export interface MultiscaleLevel {
  dims: Vec3;
  spacing: Vec3;
  origin: Vec3;
  chunk: Vec3;
}

/** One image of an OME-Zarr store, at one channel and time point, at every level. */
export interface MultiscaleSource {
  type: VoxelType;
  /** Level 0 is the finest. */
  levels: MultiscaleLevel[];
  /** The channel's omero display window [start, end], when the metadata gives one. */
  valueRange?: [number, number];
  /** Voxels of the box [min, max) (x fastest) at a level, as `type`. */
  readRegion(level: number, min: Vec3, max: Vec3, signal?: AbortSignal): Promise<VoxelArray>;
  /** A whole level as a core Volume (spacing from the metadata; valueRange when known). */
  readLevel(level: number, signal?: AbortSignal): Promise<Volume>;
  /**
   * Several channels along `c` of the box [min, max) at a level in one read (one pass over
   * the chunks, each fetched once), interleaved channel fastest in the order given:
   * value(k, x, y, z) = data[k + K·(x + NX·(y + NY·z))], K = channels.length.
   */
  readChannelsRegion?(
    level: number,
    channels: readonly number[],
    min: Vec3,
    max: Vec3,
    signal?: AbortSignal,
  ): Promise<VoxelArray>;
  /** Every channel's omero display window (by channel index), where the metadata gives one. */
  channelWindows?: readonly ([number, number] | undefined)[];
  /** Every channel's omero label and display colour (`RRGGBB`), where the metadata gives them. */
  channelInfo?: readonly { label?: string; color?: string }[];
  /** Where the store is, the NGFF version, axes, unit, channel and time chosen, warnings. */
  readonly meta: OmeZarrMeta;
  /** Bytes read from the store so far (metadata and chunks, as stored: compressed). */
  bytesRead(): number;
}

export interface OmeZarrMeta {
  location: string;
  ngffVersion: string;
  zarrFormat: 2 | 3;
  axes: { name: string; type?: string; unit?: string }[];
  unit?: string;
  sourceDtype: string;
  channel: number;
  channels: number;
  time: number;
  times: number;
  /** A label image's `image-label` colours and names (ome-metadata.ts), when present. */
  imageLabel?: ImageLabelEntry[];
  warnings: string[];
}

export interface OmeZarrOptions extends ZarrStoreOptions {
  /** Channel index along the `c` axis (default 0). */
  channel?: number;
  /** Time index along the `t` axis (default 0). */
  time?: number;
  /** Most chunk requests in flight at once (default 8). */
  concurrency?: number;
  /** Chunks read so far of the region being read, and how many it spans (progress; for the latest read when reads overlap). */
  onChunks?: (done: number, total: number) => void;
}

/**
 * Zarr data types → core's voxel types. int8 widens to int16; int32, uint32 and float64
 * become float32 (exact to 2^24; meta.warnings says so); 64-bit integers, booleans and
 * others are refused.
 */
const TYPE_MAP: Record<string, { type: VoxelType; lossy: boolean }> = {
  uint8: { type: 'uint8', lossy: false },
  int8: { type: 'int16', lossy: false },
  uint16: { type: 'uint16', lossy: false },
  int16: { type: 'int16', lossy: false },
  float32: { type: 'float32', lossy: false },
  int32: { type: 'float32', lossy: true },
  uint32: { type: 'float32', lossy: true },
  float64: { type: 'float32', lossy: true },
};

const OUTPUT_ARRAY: Record<VoxelType, new (n: number) => VoxelArray> = {
  uint8: Uint8Array,
  uint16: Uint16Array,
  int16: Int16Array,
  float32: Float32Array,
};

type ZArray = zarr.Array<zarr.DataType, CountingStore>;

/**
 * Most chunks one read may span (a whole level or a brick's box). 1³ chunks on a 64³ shape
 * are 262,144 requests, which took minutes; a reasonable store reads a level in a few thousand.
 */
export const MAX_ZARR_CHUNKS_PER_READ = 32_768;
/** Most voxels one read may return: past this no typed array can hold them (2^31 − 1 elements). */
export const MAX_ZARR_READ_VOXELS = 2 ** 31 - 1;
/** Slack past a chunk's decoded size that an inflating codec may produce before it is refused (headers, padding). */
const INFLATE_SLACK_BYTES = 1 << 16;

const DTYPE_BYTES: Record<string, number> = {
  int8: 1,
  uint8: 1,
  bool: 1,
  int16: 2,
  uint16: 2,
  float16: 2,
  int32: 4,
  uint32: 4,
  float32: 4,
};

/**
 * gzip and zlib as zarrita decodes them, but with the inflated size bounded by the chunk's
 * own decoded size: a gzip bomb in a chunk (a few KiB inflating to gigabytes) is refused as
 * soon as it passes that size, instead of after the whole stream was inflated.
 */
function boundedInflateCodec(format: 'gzip' | 'deflate') {
  return class BoundedInflateCodec {
    readonly kind = 'bytes_to_bytes';
    constructor(private readonly maxBytes: number) {}
    static fromConfig(_config: unknown, meta?: { shape?: number[]; data_type?: string }) {
      const n = (meta?.shape ?? []).reduce((a, b) => a * b, 1);
      const per = DTYPE_BYTES[String(meta?.data_type)] ?? 8;
      return new BoundedInflateCodec(meta?.shape ? n * per + INFLATE_SLACK_BYTES : Infinity);
    }
    encode(): never {
      throw new Error(`${format} encoding is not supported`);
    }
    async decode(bytes: Uint8Array): Promise<Uint8Array> {
      const input = new Uint8Array(bytes.byteLength);
      input.set(bytes);
      const stream = new Blob([input]).stream().pipeThrough(new DecompressionStream(format));
      const reader = stream.getReader();
      const parts: Uint8Array[] = [];
      let total = 0;
      for (;;) {
        let step: ReadableStreamReadResult<Uint8Array>;
        try {
          step = await reader.read();
        } catch (e) {
          throw new Error(`Failed to decode ${format}: ${(e as Error).message}`);
        }
        if (step.done) break;
        total += step.value.length;
        if (total > this.maxBytes) {
          await reader.cancel().catch(() => {});
          throw new LoaderError(
            'limit',
            `a ${format} chunk inflates past ${this.maxBytes} bytes, more than its shape holds (a compression bomb?)`,
          );
        }
        parts.push(step.value);
      }
      const out = new Uint8Array(total);
      let at = 0;
      for (const p of parts) {
        out.set(p, at);
        at += p.length;
      }
      return out;
    }
  };
}
const BoundedGzip = boundedInflateCodec('gzip');
const BoundedZlib = boundedInflateCodec('deflate');
for (const name of ['gzip', 'numcodecs.gzip']) zarr.registry.set(name, () => BoundedGzip as never);
for (const name of ['zlib', 'numcodecs.zlib']) zarr.registry.set(name, () => BoundedZlib as never);

/** How many chunks a whole level spans. */
export function levelChunkCount(level: MultiscaleLevel): number {
  return [0, 1, 2].reduce((n, i) => n * Math.ceil(level.dims[i] / level.chunk[i]), 1);
}

/** Turn what zarrita throws into a LoaderError (LoaderErrors from the store pass through). */
export function zarrError(e: unknown, where: string): LoaderError {
  if (e instanceof LoaderError) return e;
  const cause = (e as { cause?: unknown })?.cause;
  if (cause instanceof LoaderError) return cause;
  if (isAbort(e)) return new LoaderError('aborted', `Loading ${where} was aborted`, { cause: e });
  const tag = (e as { _tag?: string })?._tag;
  const msg = (e as Error)?.message ?? String(e);
  switch (tag) {
    case 'NotFoundError':
      return new LoaderError('not-found', `${where}: ${msg}`, { cause: e });
    case 'InvalidMetadataError':
      return new LoaderError('bad-header', `${where}: ${msg}`, { cause: e });
    case 'UnknownCodecError':
    case 'UnsupportedError':
      return new LoaderError('unsupported', `${where}: ${msg}`, { cause: e });
    case 'CodecPipelineError':
      return new LoaderError(
        'invalid-data',
        `${where}: a chunk does not decode (${msg}${cause ? `: ${(cause as Error).message ?? cause}` : ''})`,
        {
          cause: e,
        },
      );
  }
  if (e instanceof SyntaxError)
    return new LoaderError('bad-header', `${where}: metadata is not valid JSON (${msg})`, { cause: e });
  return new LoaderError('invalid-data', `${where}: ${msg}`, { cause: e });
}

/**
 * zarrita copies a decoded chunk without checking its length, so an uncompressed chunk cut
 * short would read as wrong voxels: this extension refuses it, and tells `onChunk` of
 * every chunk read (progress).
 */
function checkedChunks(onChunk: () => void) {
  return zarr.defineArrayExtension((array) => ({
    async getChunk(coords: number[], options?: zarr.GetOptions, opts?: { useSharedArrayBuffer?: boolean }) {
      const chunk = await array.getChunk(coords, options, opts);
      const want = chunk.shape.reduce((a, b) => a * b, 1);
      if ((chunk.data as ArrayLike<unknown>).length !== want)
        throw new LoaderError(
          'truncated',
          `${array.path}: chunk ${coords.join('/')} holds ${(chunk.data as ArrayLike<unknown>).length} of its ${want} values`,
        );
      onChunk();
      return chunk;
    },
  }));
}

/** Open the OME-Zarr image at `location` (an http(s) URL, or a folder path / file: URL in Node). */
export async function openOmeZarr(location: string, options: OmeZarrOptions = {}): Promise<MultiscaleSource> {
  const store = await openZarrStore(location, options);
  let chunkListener: (() => void) | null = null;
  const where = location;
  // Zarr v3 keeps a group's attributes in zarr.json, v2 in .zattrs (.zgroup marks the
  // group). They are read here, once (zarrita would fetch them again and would report bad
  // JSON as "not found"); the levels' array metadata is then fetched in parallel.
  const v3 = await store.get('/zarr.json');
  const v2 = v3 ? undefined : ((await store.get('/.zattrs')) ?? (await store.get('/.zgroup')));
  if (!v3 && !v2)
    throw new LoaderError('not-found', `${where}: no Zarr group here (neither zarr.json nor .zgroup/.zattrs)`);
  let json: { node_type?: unknown; attributes?: unknown } & Record<string, unknown>;
  try {
    json = JSON.parse(new TextDecoder().decode(v3 ?? v2));
  } catch (e) {
    throw new LoaderError(
      'bad-header',
      `${where}: ${v3 ? 'zarr.json' : '.zattrs'} is not valid JSON (${(e as Error).message})`,
    );
  }
  if (v3 && json?.node_type !== 'group')
    throw new LoaderError('bad-header', `${where}: zarr.json describes a ${String(json?.node_type)}, not a group`);
  const zarrFormat = v3 ? 3 : 2;
  const ms: OmeMultiscale = parseOmeMultiscales(v3 ? json.attributes : json, where);
  const rootLocation = zarr.root(store);
  const arrays: ZArray[] = await Promise.all(
    ms.datasets.map(async (d) => {
      try {
        const location = rootLocation.resolve(d.path);
        const array =
          zarrFormat === 3
            ? await zarr.open.v3(location, { kind: 'array' })
            : await zarr.open.v2(location, { kind: 'array', attrs: false });
        return checkedChunks(() => chunkListener?.())(array as ZArray) as ZArray;
      } catch (e) {
        throw zarrError(e, `${where}/${d.path}`);
      }
    }),
  );
  const first = arrays[0];
  const ndim = ms.axes.length;
  const dtype = String(first.dtype);
  const mapped = TYPE_MAP[dtype];
  if (!mapped)
    throw new LoaderError(
      'unsupported',
      `${where}: data type ${dtype} is not read (uint8, int8, uint16, int16, float32; int32, uint32, float64 as float32)`,
    );
  const warnings = [...ms.warnings];
  if (mapped.lossy) warnings.push(`${dtype} data is read as float32 (integers beyond ±2^24 round)`);
  arrays.forEach((a, k) => {
    if (a.shape.length !== ndim)
      throw new LoaderError(
        'bad-header',
        `${where}/${ms.datasets[k].path}: ${a.shape.length} dimensions, but the multiscale names ${ndim} axes`,
      );
    if (String(a.dtype) !== dtype)
      throw new LoaderError('bad-header', `${where}: level ${k} is ${a.dtype}, level 0 is ${dtype}`);
  });
  const { x, y, z, c, t } = ms.axisIndex;
  const channels = c === undefined ? 1 : first.shape[c];
  const times = t === undefined ? 1 : first.shape[t];
  const channel = options.channel ?? 0;
  const time = options.time ?? 0;
  if (!Number.isInteger(channel) || channel < 0 || channel >= channels)
    throw new LoaderError('bad-header', `${where}: channel ${channel} does not exist (the image has ${channels})`);
  if (!Number.isInteger(time) || time < 0 || time >= times)
    throw new LoaderError('bad-header', `${where}: time point ${time} does not exist (the image has ${times})`);
  const levels: MultiscaleLevel[] = arrays.map((a, k) => {
    const dims = [a.shape[x], a.shape[y], a.shape[z]] as Vec3;
    if (!dims.every((n) => Number.isInteger(n) && n >= 1))
      throw new LoaderError('empty', `${where}/${ms.datasets[k].path}: dims [${dims.join(', ')}] hold no voxels`);
    // A chunk side of 0 (or a fraction) would divide the shape into no chunks, or infinitely many.
    if (a.chunks.length !== a.shape.length || !a.chunks.every((n) => Number.isInteger(n) && n >= 1))
      throw new LoaderError(
        'bad-header',
        `${where}/${ms.datasets[k].path}: chunk shape [${a.chunks.join(', ')}] must be ${a.shape.length} positive integers`,
      );
    return {
      dims,
      spacing: ms.datasets[k].spacing,
      origin: ms.datasets[k].origin,
      chunk: [a.chunks[x], a.chunks[y], a.chunks[z]] as Vec3,
    };
  });
  const meta: OmeZarrMeta = {
    location,
    ngffVersion: ms.version,
    zarrFormat,
    axes: ms.axes,
    ...(ms.unit ? { unit: ms.unit } : {}),
    sourceDtype: dtype,
    channel,
    channels,
    time,
    times,
    ...(ms.imageLabel ? { imageLabel: ms.imageLabel } : {}),
    warnings,
  };
  const valueRange = ms.windows[channel];
  const concurrency = Math.max(1, options.concurrency ?? 8);

  async function readRegion(level: number, min: Vec3, max: Vec3, signal?: AbortSignal): Promise<VoxelArray> {
    return read(level, min, max, null, signal);
  }

  /** The box at a level: at `channel` (picked: null), or along c over `picked` (interleaved in that order). */
  async function read(
    level: number,
    min: Vec3,
    max: Vec3,
    picked: readonly number[] | null,
    signal?: AbortSignal,
  ): Promise<VoxelArray> {
    const a = arrays[level];
    if (!a) throw new LoaderError('bad-header', `${where}: level ${level} does not exist (0 to ${arrays.length - 1})`);
    const dims = levels[level].dims;
    for (let i = 0; i < 3; i++) {
      if (!(
        Number.isInteger(min[i]) &&
        Number.isInteger(max[i]) &&
        0 <= min[i] &&
        min[i] < max[i] &&
        max[i] <= dims[i]
      ))
        throw new LoaderError(
          'bad-header',
          `${where}: region [${min.join(', ')}]–[${max.join(', ')}] is not a non-empty box inside level ${level}'s dims [${dims.join(', ')}]`,
        );
    }
    const selection: (number | zarr.Slice)[] = new Array(ndim).fill(0);
    [x, y, z].forEach((axis, i) => (selection[axis] = zarr.slice(min[i], max[i])));
    // Several channels: the run of c from the lowest to the highest asked for, in one zarr.get.
    const lo = picked ? Math.min(...picked) : 0;
    const hi = picked ? Math.max(...picked) + 1 : 1;
    if (picked) {
      if (!picked.length || picked.some((k) => !Number.isInteger(k) || k < 0 || k >= channels))
        throw new LoaderError(
          'bad-header',
          `${where}: channels [${picked.join(', ')}] must be channel indices 0 to ${channels - 1} (the image has ${channels})`,
        );
      if (c !== undefined) selection[c] = zarr.slice(lo, hi);
    } else if (c !== undefined) selection[c] = channel;
    if (t !== undefined) selection[t] = time;
    let got: zarr.Chunk<zarr.DataType>;
    const chunk = levels[level].chunk;
    const cChunk = c !== undefined && picked ? a.chunks[c] : 1;
    const cChunks = picked && c !== undefined ? Math.ceil(hi / cChunk) - Math.floor(lo / cChunk) : 1;
    const total =
      cChunks * [0, 1, 2].reduce((n, i) => n * (Math.ceil(max[i] / chunk[i]) - Math.floor(min[i] / chunk[i])), 1);
    const voxels = (max[0] - min[0]) * (max[1] - min[1]) * (max[2] - min[2]) * (picked ? hi - lo : 1);
    if (voxels > MAX_ZARR_READ_VOXELS)
      throw new LoaderError(
        'limit',
        `${where}: level ${level}'s region of [${max.map((m, i) => m - min[i]).join(', ')}] voxels is more than one read can hold (${MAX_ZARR_READ_VOXELS}); choose a coarser level`,
      );
    if (total > MAX_ZARR_CHUNKS_PER_READ)
      throw new LoaderError(
        'limit',
        `${where}: reading level ${level}'s region would take ${total} chunk requests of [${chunk.join(', ')}] voxels, more than ${MAX_ZARR_CHUNKS_PER_READ}; choose a coarser level or rechunk the store`,
      );
    let done = 0;
    chunkListener = () => options.onChunks?.(++done, total);
    try {
      got = await zarr.get(a, selection, { createQueue: () => limitedQueue(concurrency), opts: { signal } });
    } catch (e) {
      throw zarrError(e, `${where}/${ms.datasets[level].path}`);
    } finally {
      chunkListener = null;
    }
    if (signal?.aborted) throw new LoaderError('aborted', `Loading ${where} was aborted`);
    const size = max.map((m, i) => m - min[i]) as Vec3;
    if (!picked) return toVoxels(got, [x, y, z], mapped.type, size);
    return toChannelVoxels(
      got,
      [x, y, z],
      c,
      picked.map((k) => k - lo),
      mapped.type,
      size,
    );
  }

  return {
    type: mapped.type,
    levels,
    ...(valueRange ? { valueRange } : {}),
    meta,
    readRegion,
    readChannelsRegion: (level, picked, min, max, signal) => read(level, min, max, picked, signal),
    channelWindows: Array.from({ length: channels }, (_, k) => ms.windows[k]),
    channelInfo: Array.from({ length: channels }, (_, k) => ms.channelInfo[k] ?? {}),
    bytesRead: () => store.bytesRead,
    async readLevel(level, signal) {
      const L = levels[level];
      if (!L)
        throw new LoaderError('bad-header', `${where}: level ${level} does not exist (0 to ${levels.length - 1})`);
      const data = await readRegion(level, [0, 0, 0], L.dims, signal);
      const volume = createVolume([...L.dims], mapped.type, data, [...L.spacing]);
      if (valueRange) volume.valueRange = [valueRange[0], valueRange[1]];
      volume.name = `${location
        .replace(/[?#].*$/, '')
        .replace(/\/+$/, '')
        .split('/')
        .pop()} level ${level}`;
      return volume;
    },
  };
}

/**
 * zarrita's result (C order over the kept axes, which are the space axes in file order)
 * → a fresh array of `type`, x fastest. `xyz` are the array dimensions of x, y, z.
 */
function toVoxels(got: zarr.Chunk<zarr.DataType>, xyz: readonly number[], type: VoxelType, size: Vec3): VoxelArray {
  const src = got.data as ArrayLike<number>;
  // The kept dimensions are the space axes in array order; find each one's stride.
  const kept = [...xyz].sort((p, q) => p - q);
  const stride = xyz.map((axis) => got.stride[kept.indexOf(axis)]);
  const [nx, ny, nz] = size;
  const out = new OUTPUT_ARRAY[type](nx * ny * nz);
  if (stride[0] === 1 && stride[1] === nx && stride[2] === nx * ny && src.length === out.length) {
    // z, y, x order (NGFF's usual): a straight copy with conversion.
    for (let i = 0; i < out.length; i++) out[i] = src[i];
    return out;
  }
  let i = 0;
  for (let k = 0; k < nz; k++)
    for (let j = 0; j < ny; j++) {
      const row = j * stride[1] + k * stride[2];
      for (let q = 0; q < nx; q++) out[i++] = src[row + q * stride[0]];
    }
  return out;
}

/**
 * zarrita's result over space axes and a run of c (C order over the kept axes, in array
 * order) → a fresh array of `type`, channel fastest in the order of `picked` (offsets into the
 * run), then x, y, z. Without a c axis the one channel is offset 0.
 */
function toChannelVoxels(
  got: zarr.Chunk<zarr.DataType>,
  xyz: readonly number[],
  c: number | undefined,
  picked: readonly number[],
  type: VoxelType,
  size: Vec3,
): VoxelArray {
  const src = got.data as ArrayLike<number>;
  const axes = c === undefined ? [...xyz] : [...xyz, c];
  const kept = [...axes].sort((p, q) => p - q);
  const stride = axes.map((axis) => got.stride[kept.indexOf(axis)]);
  const sc = c === undefined ? 0 : stride[3];
  const K = picked.length;
  const [nx, ny, nz] = size;
  const out = new OUTPUT_ARRAY[type](K * nx * ny * nz);
  let i = 0;
  for (let k = 0; k < nz; k++)
    for (let j = 0; j < ny; j++) {
      const row = j * stride[1] + k * stride[2];
      for (let q = 0; q < nx; q++) {
        const at = row + q * stride[0];
        for (let p = 0; p < K; p++) out[i++] = src[at + picked[p] * sc];
      }
    }
  return out;
}

/** A chunk queue running at most `n` requests at once (zarrita's default starts them all). */
interface ChunkQueue {
  add(fn: () => Promise<void>): void;
  onIdle(): Promise<void[]>;
}

function limitedQueue(n: number): ChunkQueue {
  const waiting: (() => Promise<void>)[] = [];
  const all: Promise<void>[] = [];
  let running = 0;
  const next = () => {
    while (running < n && waiting.length) {
      const fn = waiting.shift()!;
      running++;
      const p = fn().then(
        () => {
          running--;
          next();
        },
        (e) => {
          // One failed chunk fails the read: start nothing more.
          running--;
          waiting.length = 0;
          throw e;
        },
      );
      p.catch(() => {}); // the failure is reported once, by onIdle
      all.push(p);
    }
  };
  return {
    add(fn) {
      waiting.push(fn);
      next();
    },
    async onIdle() {
      const results: void[] = [];
      // New work starts only as earlier work settles, so loop until nothing is left.
      while (waiting.length || all.length) {
        const batch = all.splice(0);
        results.push(...(await Promise.all(batch)));
        if (!batch.length) await Promise.resolve();
      }
      return results;
    },
  };
}
