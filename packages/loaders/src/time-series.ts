import type { TimeSeriesSource } from '@vpt/core';
import { createContext } from './context.js';
import { baseName } from './detect.js';
import { LoaderError, toLoaderError } from './errors.js';
import { gunzip, isGzip } from './io/gzip.js';
import { bytesOf, fetchBytes, readBlob } from './io/read-bytes.js';
import { describeSource } from './load-in-thread.js';
import { hasNrrdMagic, parseNrrdHeader } from './formats/nrrd.js';
import type { LoadContext } from './context.js';
import { loadVolume } from './load-volume.js';
import { isZarrLocation } from './zarr/location.js';
import type { LoadedVolume, LoadOptions, VolumeSource } from './types.js';

/** openTimeSeries' options: a load's, and how much of a one-file series' bytes may be kept between steps. */
export interface TimeSeriesOptions extends LoadOptions {
  /**
   * Most bytes of a one-file series (a 4D NIfTI or NRRD) kept between steps so the file is
   * read once (default 1 GiB): its bytes as read, or inflated when the whole file is gzip and
   * inflates within this. A file larger than this is read again for each step.
   */
  keepBytes?: number;
}

/** Default TimeSeriesOptions.keepBytes: 1 GiB, as DEFAULT_LIMITS.maxBytes. */
export const DEFAULT_KEEP_BYTES = 1 << 30;

/** A time series of loaded volumes, with step 0 already read (its header told how many steps there are). */
export interface LoadedTimeSeries extends TimeSeriesSource<LoadedVolume> {
  /** Step 0, read to learn the series' grid and length. */
  readonly first: LoadedVolume;
}

/**
 * Open a time series: one source that holds its steps (an OME-Zarr store with a `t` axis, a
 * 4D NIfTI file: `meta.timeSteps` steps, each read with `LoadOptions.time`), or a list of
 * sources, one per step (raw + sidecar, NRRD, NIfTI… of one grid; a step of several files,
 * such as a DICOM series, is itself a File list). A one-volume source is a series of one
 * step. Steps of a list whose dims or voxel type differ from step 0's are refused
 * (`invalid-data`). A one-file series (a 4D NIfTI or NRRD by URL, File, Blob or bytes) is
 * read once: its bytes are kept (inflated once when the whole file is gzip, as a .nii.gz)
 * within `keepBytes`, and every step is decoded from them; a detached header (.nhdr,
 * .hdr/.img) or a file past `keepBytes` is read again per step.
 */
export async function openTimeSeries(
  source: VolumeSource | readonly VolumeSource[],
  options: TimeSeriesOptions = {},
): Promise<LoadedTimeSeries> {
  const list = isStepList(source) ? source : null;
  if (list && list.length === 0)
    throw new LoaderError('empty', 'A time series needs at least one step; the list is empty');
  const { keepBytes = DEFAULT_KEEP_BYTES, ...loadOptions } = options;
  options = loadOptions;
  const kept = list ? null : await keptFile(source as VolumeSource, options, keepBytes);
  const one: VolumeSource = kept ?? (source as VolumeSource);
  const first = await loadVolume(list ? list[0] : one, { ...options, time: list ? undefined : 0 });
  const steps = list ? list.length : Number((first.meta?.timeSteps as number | undefined) ?? 1);
  // A one-volume source keeps nothing; a series keeps its bytes for the other steps.
  const stepSource: VolumeSource = steps > 1 && kept ? kept : (source as VolumeSource);
  const stepSeconds = first.meta?.stepSeconds as number | undefined;
  let firstTaken = false;
  return {
    first,
    steps,
    ...(stepSeconds !== undefined ? { stepSeconds } : {}),
    async loadStep(index: number, signal?: AbortSignal): Promise<LoadedVolume> {
      if (!Number.isInteger(index) || index < 0 || index >= steps)
        throw new LoaderError(
          'bad-header',
          `time step ${index} does not exist (the series has ${steps}, 0 to ${steps - 1})`,
        );
      // Step 0 was read to open the series: handed out once, then read again like any step.
      if (index === 0 && !firstTaken) {
        firstTaken = true;
        return first;
      }
      const o = { ...options, ...(signal ? { signal } : {}) };
      const v = list ? await loadVolume(list[index], o) : await loadVolume(stepSource, { ...o, time: index });
      if (v.type !== first.type || v.dims.some((d, i) => d !== first.dims[i]))
        throw new LoaderError(
          'invalid-data',
          `time step ${index} is ${v.dims.join('×')} ${v.type}, unlike step 0's ${first.dims.join('×')} ${first.type}: the steps of a series must share one grid`,
        );
      return v;
    },
  };
}

/** A list is always one source per step here (a multi-file step is a File list inside it). */
function isStepList(s: VolumeSource | readonly VolumeSource[]): s is readonly VolumeSource[] {
  return Array.isArray(s);
}

/**
 * The bytes of a one-file source read once, as a File of its name (inflated, and its name
 * without ".gz", when the whole file is gzip and inflates within `keepBytes`), or null where
 * the source is read per step: an OME-Zarr store (read by region), a File list, a detached
 * header or sidecar (its data is another file), or a file larger than `keepBytes`.
 */
async function keptFile(source: VolumeSource, options: LoadOptions, keepBytes: number): Promise<File | null> {
  if (typeof File === 'undefined' || Array.isArray(source) || options.format === 'ome-zarr') return null;
  const name = describeSource(source);
  const isUrl = typeof source === 'string' || (typeof URL !== 'undefined' && source instanceof URL);
  const fileName = isUrl ? baseName(name) : source instanceof File ? source.name : '';
  if (isUrl && isZarrLocation(String(source))) return null;
  // Only a self-contained file: a .nhdr, .hdr or sidecar names another file that holds the data.
  if (fileName && !/\.(nii|nii\.gz|nrrd)$/i.test(fileName.replace(/[?#].*$/, ''))) return null;
  const ctx = createContext(name, options);
  try {
    let bytes: Uint8Array;
    if (isUrl) bytes = await fetchBytes(absolute(String(source)), ctx);
    else if (typeof Blob !== 'undefined' && source instanceof Blob) {
      if (source.size > keepBytes) return null;
      bytes = await readBlob(source, ctx);
    } else if (source instanceof ArrayBuffer || ArrayBuffer.isView(source)) bytes = bytesOf(source as ArrayBuffer);
    else return null;
    if (bytes.length > keepBytes) return null;
    let keptName = fileName || name;
    if (isGzip(bytes)) {
      try {
        bytes = await gunzip(bytes, ctx, { maxOutput: keepBytes });
        keptName = keptName.replace(/\.gz$/i, '');
      } catch (e) {
        // Past keepBytes inflated: keep the compressed bytes (each step inflates up to itself).
        if (!(e instanceof LoaderError && e.reason === 'limit')) throw e;
      }
    } else if (hasNrrdMagic(bytes)) bytes = (await inflatedNrrd(bytes, ctx, keepBytes)) ?? bytes;
    return new File([bytes as Uint8Array<ArrayBuffer>], keptName);
  } catch (e) {
    throw toLoaderError(e, name);
  }
}

/**
 * A gzip-encoded NRRD with attached data as the same NRRD with raw encoding: the header's
 * lines kept but "encoding" (now raw) and "line skip" (applied here, before inflating, as
 * the decoder does), the data inflated once ("byte skip" keeps its meaning: bytes of the
 * decoded data, -1 its last bytes). Null where nothing is to gain or it does not fit
 * `keepBytes` (then each step inflates up to itself, as a lone load does).
 */
async function inflatedNrrd(bytes: Uint8Array, ctx: LoadContext, keepBytes: number): Promise<Uint8Array | null> {
  const { fields, dataStart } = parseNrrdHeader(bytes, ctx);
  const encoding = (fields.encoding ?? '').toLowerCase();
  if ((encoding !== 'gzip' && encoding !== 'gz') || (fields['data file'] ?? fields.datafile) !== undefined) return null;
  const lineSkip = Number(fields['line skip'] ?? fields.lineskip ?? 0);
  if (!Number.isInteger(lineSkip) || lineSkip < 0) return null; // the decoder names the fault
  let data = bytes.subarray(dataStart);
  for (let l = 0; l < lineSkip; l++) {
    const nl = data.indexOf(0x0a);
    if (nl < 0) return null;
    data = data.subarray(nl + 1);
  }
  let inflated: Uint8Array;
  try {
    inflated = await gunzip(data, ctx, { maxOutput: keepBytes });
  } catch (e) {
    if (e instanceof LoaderError && e.reason === 'limit') return null;
    throw e;
  }
  const header = new TextDecoder('latin1')
    .decode(bytes.subarray(0, dataStart))
    .split(/\r?\n/)
    .filter((line) => !/^(line ?skip|encoding)\s*:(?!=)/i.test(line));
  while (header.length && header[header.length - 1] === '') header.pop();
  header.push('encoding: raw', '', '');
  const head = Uint8Array.from(header.join('\n'), (c) => c.charCodeAt(0) & 0xff);
  if (head.length + inflated.length > keepBytes) return null;
  const out = new Uint8Array(head.length + inflated.length);
  out.set(head);
  out.set(inflated, head.length);
  return out;
}

function absolute(url: string): string {
  try {
    return new URL(url, (globalThis as { location?: { href: string } }).location?.href).href;
  } catch {
    return url;
  }
}
