import { HEADERLESS_RAW_HINT } from '@vpt/core';
import { LoaderError, toLoaderError } from './errors.js';
import { createContext, type LoadContext } from './context.js';
import type { LoadedVolume, LoadOptions, VolumeSource } from './types.js';
import { baseName, formatFromBytes, formatFromName, type Format } from './detect.js';
import { bytesOf, fetchBytes, fetchText, readBlob } from './io/read-bytes.js';
import { checkRawOptions, decodeRaw, parseSidecar, rawFromName, type RawDescription } from './formats/raw.js';
import { decodeDicom, type DicomFile } from './formats/dicom.js';
import { decodeNifti, pairImageName } from './formats/nifti.js';
import { decodeNrrd } from './formats/nrrd.js';
import { isZarrLocation } from './zarr/location.js';

/** A short name for messages. */
export function describeSource(source: unknown): string {
  if (typeof source === 'string') return source;
  if (typeof URL !== 'undefined' && source instanceof URL) return source.href;
  if (Array.isArray(source)) return source.length === 1 ? fileName(source[0]) || 'the file' : `${source.length} files`;
  if (typeof Blob !== 'undefined' && source instanceof Blob) return fileName(source) || 'the blob';
  return 'the data';
}

function fileName(f: unknown): string {
  return typeof f === 'object' && f !== null && typeof (f as File).name === 'string' ? (f as File).name : '';
}

function relativePath(f: File): string {
  return (f as File & { webkitRelativePath?: string }).webkitRelativePath || f.name;
}

/** Loads a detached file named by a header: next to a URL, or among the dropped files. */
type Resolver = (name: string) => Promise<Uint8Array>;

/**
 * The whole load in the calling thread: read the bytes, find the format, decode. Every
 * failure comes out as a LoaderError.
 */
export async function loadInThread(source: VolumeSource, options: LoadOptions = {}): Promise<LoadedVolume> {
  const name = describeSource(source);
  const ctx = createContext(name, options);
  try {
    ctx.checkAborted();
    if (
      options.format !== undefined &&
      !['auto', 'raw', 'nrrd', 'nifti', 'dicom', 'ome-zarr'].includes(options.format)
    ) {
      throw new LoaderError(
        'unsupported',
        `format "${String(options.format)}" is not one of auto, raw, nrrd, nifti, dicom, ome-zarr`,
      );
    }
    const t = ctx.time;
    if (!Number.isInteger(t) || t < 0)
      throw new LoaderError('bad-header', `${name}: time step ${t} must be a whole number ≥ 0`);
    const volume = await dispatch(source, options, ctx);
    // Only a format that reads time steps sets meta.timeSteps; step 0 of any other is its one volume.
    if (t > 0 && volume.meta?.timeSteps === undefined)
      throw new LoaderError(
        'unsupported',
        `${name}: time step ${t} asked for, but this ${volume.format} source holds one volume (a time series is an OME-Zarr t axis, a 4D NIfTI file or a list of files)`,
      );
    return volume;
  } catch (e) {
    throw toLoaderError(e, name);
  }
}

async function dispatch(source: VolumeSource, options: LoadOptions, ctx: LoadContext): Promise<LoadedVolume> {
  const wanted = options.format && options.format !== 'auto' ? options.format : undefined;
  if (typeof source === 'string' || (typeof URL !== 'undefined' && source instanceof URL)) {
    const location = String(source);
    if (wanted === 'ome-zarr' || (!wanted && isZarrLocation(location))) {
      // zarrita and the codecs load only when an OME-Zarr store is asked for.
      const { loadOmeZarr } = await import('./zarr/load-ome-zarr.js');
      const zarr =
        options.zarr?.time === undefined && options.time !== undefined
          ? { ...options.zarr, time: options.time }
          : options.zarr;
      return loadOmeZarr(zarrPathOrUrl(location), zarr ?? {}, ctx);
    }
    return loadUrl(String(source), wanted, options, ctx);
  }
  if (wanted === 'ome-zarr')
    throw new LoaderError(
      'unsupported',
      'An OME-Zarr store is read from a URL (or a folder path in Node), not from bytes or files',
    );
  if (Array.isArray(source)) return loadFiles(source as readonly File[], wanted, options, ctx);
  if (typeof Blob !== 'undefined' && source instanceof Blob) {
    const name = fileName(source);
    const bytes = await readBlob(source, ctx);
    return decodeBytes(bytes, name, wanted, options, ctx, undefined);
  }
  if (source instanceof ArrayBuffer || ArrayBuffer.isView(source)) {
    const bytes = bytesOf(source as ArrayBuffer);
    ctx.borrowed = bytes.buffer;
    return decodeBytes(bytes, '', wanted, options, ctx, undefined);
  }
  throw new LoaderError(
    'unsupported',
    `Cannot load ${Object.prototype.toString.call(source)}: pass a URL, a File or Blob, an ArrayBuffer, or an array of Files`,
  );
}

/** A relative location: a page-relative URL in a browser, a path in Node (no page to be relative to). */
function zarrPathOrUrl(location: string): string {
  return (globalThis as { location?: unknown }).location ? absoluteUrl(location) : location;
}

function absoluteUrl(url: string): string {
  try {
    const base = (globalThis as { location?: { href: string } }).location?.href;
    return new URL(url, base).href;
  } catch {
    return url; // no base (Node) and relative: fetch reports it
  }
}

async function loadUrl(
  url: string,
  wanted: Format | undefined,
  options: LoadOptions,
  ctx: LoadContext,
): Promise<LoadedVolume> {
  const abs = absoluteUrl(url);
  const resolve: Resolver = (name) => fetchBytes(new URL(name, abs).href, ctx);
  const byName = formatFromName(abs);
  if (byName === 'sidecar' && (!wanted || wanted === 'raw')) {
    const sidecar = parseSidecar(await fetchText(abs, ctx), ctx);
    const rawUrl = new URL(sidecar.file ?? baseName(abs).replace(/\.json$/i, '.raw'), abs).href;
    return decodeRaw(await fetchBytes(rawUrl, ctx), sidecar, ctx, sidecar.meta);
  }
  if ((wanted ?? byName) === 'raw' && !options.raw) {
    // Headerless raw without dims: a sidecar with the same base name, else the name pattern.
    const sidecarUrl = abs.replace(/\.raw(?=([?#].*)?$)/i, '.json');
    if (sidecarUrl !== abs) {
      let text: string | undefined;
      try {
        text = await fetchText(sidecarUrl, ctx);
      } catch (e) {
        if (!(e instanceof LoaderError && e.reason === 'not-found')) throw e;
      }
      if (text !== undefined) {
        const sidecar = parseSidecar(text, { ...ctx, name: sidecarUrl });
        return decodeRaw(await fetchBytes(abs, ctx), sidecar, ctx, sidecar.meta);
      }
    }
  }
  const bytes = await fetchBytes(abs, ctx);
  return decodeBytes(bytes, baseName(abs), wanted, options, ctx, resolve);
}

async function loadFiles(
  files: readonly File[],
  wanted: Format | undefined,
  options: LoadOptions,
  ctx: LoadContext,
): Promise<LoadedVolume> {
  if (!files.length) throw new LoaderError('empty', 'No files were given');
  for (const f of files) {
    if (!(typeof Blob !== 'undefined' && f instanceof Blob))
      throw new LoaderError('unsupported', 'The file list holds something that is not a File');
  }
  const byName = (name: string) => files.find((f) => f.name === baseName(name) || relativePath(f).endsWith(name));
  const resolve: Resolver = async (name) => {
    const f = byName(name);
    if (!f)
      throw new LoaderError(
        'not-found',
        `${ctx.name}: the header names the data file "${name}", which is not among the given files; add it`,
      );
    return readBlob(f, ctx);
  };
  const kinds = files.map((f) => formatFromName(f.name));
  // A sidecar and its raw file.
  const sidecarIndex = kinds.indexOf('sidecar');
  if ((!wanted || wanted === 'raw') && sidecarIndex >= 0 && files.length > 1) {
    const sidecarFile = files[sidecarIndex];
    const sidecar = parseSidecar(new TextDecoder().decode(await readBlob(sidecarFile, ctx)), {
      ...ctx,
      name: sidecarFile.name,
    });
    const rawName = sidecar.file ?? sidecarFile.name.replace(/\.json$/i, '.raw');
    const rawFile = byName(rawName);
    if (!rawFile)
      throw new LoaderError(
        'not-found',
        `${sidecarFile.name} describes "${rawName}", which is not among the given files; add it`,
      );
    return decodeRaw(await readBlob(rawFile, ctx), sidecar, { ...ctx, name: rawFile.name }, sidecar.meta);
  }
  // A (detached) NRRD header with its data file.
  const nrrdIndex = kinds.indexOf('nrrd');
  if ((!wanted && nrrdIndex >= 0) || wanted === 'nrrd') {
    const f = files[nrrdIndex >= 0 ? nrrdIndex : 0];
    return decodeBytes(await readBlob(f, ctx), f.name, 'nrrd', options, { ...ctx, name: f.name }, resolve);
  }
  if (files.length === 1 && wanted !== 'dicom') {
    const f = files[0];
    return decodeBytes(await readBlob(f, ctx), f.name, wanted, options, { ...ctx, name: f.name }, resolve);
  }
  const niftiIndex = kinds.indexOf('nifti');
  if ((!wanted && niftiIndex >= 0) || wanted === 'nifti') {
    const f = files[niftiIndex >= 0 ? niftiIndex : 0];
    // A .hdr/.img pair is one volume in two files; anything more is said.
    const pairImage = byName(pairImageName(f.name));
    if (files.length > (pairImage ? 2 : 1)) ctx.warnings.push(`several files given; ${f.name} is loaded`);
    return decodeBytes(await readBlob(f, ctx), f.name, 'nifti', options, { ...ctx, name: f.name }, resolve);
  }
  if (wanted === 'raw') {
    const f = files[0];
    return decodeBytes(await readBlob(f, ctx), f.name, 'raw', options, { ...ctx, name: f.name }, resolve);
  }
  // Otherwise: a DICOM series (a dropped folder). Files that are clearly not DICOM are skipped.
  const total = files.reduce((n, f) => n + f.size, 0);
  const dicom: DicomFile[] = [];
  let loaded = 0,
    ignored = 0;
  ctx.progress('fetch', 0, total);
  for (const f of files) {
    ctx.checkAborted();
    const bytes = new Uint8Array(await f.arrayBuffer());
    loaded += f.size;
    ctx.progress('fetch', loaded, total);
    const kind = formatFromBytes(bytes);
    if (kind === 'dicom' || (kind === undefined && formatFromName(f.name) === 'dicom'))
      dicom.push({ name: relativePath(f), bytes });
    else ignored++;
  }
  if (!dicom.length) {
    throw new LoaderError(
      'bad-magic',
      `None of the ${files.length} files is DICOM, NIfTI, NRRD or a sidecar with its raw file`,
    );
  }
  if (ignored) ctx.warnings.push(`${ignored} file(s) that are not DICOM were skipped`);
  return decodeDicom(dicom, ctx);
}

/** Decode bytes whose format is asked for, or told by the name, or by the magic bytes. */
async function decodeBytes(
  bytes: Uint8Array,
  name: string,
  wanted: Format | undefined,
  options: LoadOptions,
  ctx: LoadContext,
  resolve: Resolver | undefined,
): Promise<LoadedVolume> {
  if (!bytes.length) throw new LoaderError('empty', `${ctx.name} is empty (0 bytes)`);
  // The extension proposes, the magic bytes decide (a .dcm that is really NIfTI loads as
  // NIfTI); headerless raw has no magic, so there the extension or options.raw decides.
  let format: Format | undefined = wanted;
  if (!format) {
    const byName = name ? formatFromName(name) : undefined;
    format = options.raw || byName === 'raw' ? 'raw' : (formatFromBytes(bytes) ?? byName);
  }
  switch (format) {
    case 'raw': {
      const raw = options.raw ? checkRawOptions(options.raw, ctx) : rawFromName(name);
      if (!raw)
        throw new LoaderError(
          'bad-header',
          `${ctx.name}: raw data has no header; ${options.rawHint ?? HEADERLESS_RAW_HINT}`,
        );
      return decodeRaw(bytes, checkRawOptions(raw, ctx), ctx);
    }
    case 'sidecar': {
      const sidecar: RawDescription = parseSidecar(new TextDecoder().decode(bytes), ctx);
      if (!resolve)
        throw new LoaderError(
          'unsupported',
          `${ctx.name} is a JSON sidecar; load it by URL, or together with its raw file`,
        );
      return decodeRaw(await resolve(sidecar.file ?? name.replace(/\.json$/i, '.raw')), sidecar, ctx, sidecar.meta);
    }
    case 'nifti': {
      return decodeNifti(bytes, ctx, resolve);
    }
    case 'nrrd': {
      return decodeNrrd(bytes, ctx, resolve);
    }
    case 'dicom': {
      return decodeDicom([{ name, bytes }], ctx);
    }
    default:
      throw new LoaderError(
        'bad-magic',
        `${ctx.name}: the format is not recognised (not NIfTI-1, NRRD, DICOM or a JSON sidecar); ` +
          `for headerless raw data, ${options.rawHint ?? HEADERLESS_RAW_HINT}; or pass options.format`,
      );
  }
}
