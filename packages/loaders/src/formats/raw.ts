import { RAW_VOXEL_TYPES, checkRawHeader, parseRawSidecar, rawHeaderFromName } from '@vpt/core';
import { LoaderError, asLoaderError } from '../errors.js';
import type { LoadContext } from '../context.js';
import type { LoadedVolume, RawOptions } from '../types.js';
import { finishVolume } from '../convert/finish.js';
import { checkDims, checkFits, SOURCE_BYTES } from '../convert/size.js';
import { OUTPUT_BYTES, readSamples, toVoxelArray } from '../convert/voxels.js';
import { orientationFromAxisCodes } from './orientation.js';

/** A raw description after checking: what the bytes need to be read. */
export interface RawDescription extends Required<RawOptions> {
  /** The raw file's name (a sidecar's `file`), resolved against the sidecar. */
  file?: string;
  meta: Record<string, unknown>;
}

/** Check options.raw (or a sidecar's fields) with core's checkRawHeader; anything wrong is a 'bad-header' error naming the field. */
export function checkRawOptions(
  raw: Partial<RawOptions> | undefined,
  ctx: LoadContext,
  source = 'options.raw',
): Required<RawOptions> {
  return asLoaderError(() => checkRawHeader(raw, ctx.name, source));
}

/** Parse a JSON sidecar of the project's data folder with core's parseRawSidecar (value_range, axes… kept in meta). */
export function parseSidecar(text: string, ctx: LoadContext): RawDescription {
  const { dims, type, spacing, endianness, file, meta } = asLoaderError(() => parseRawSidecar(text, ctx.name));
  return { dims, type, spacing, endianness, file, meta };
}

/** dims and type from a name like `head_256x256x108_int16.raw` (core's rawHeaderFromName). */
export function rawFromName(name: string): RawOptions | undefined {
  return rawHeaderFromName(name);
}

/** Headerless raw voxels: the byte count must match dims × type exactly. */
export function decodeRaw(
  bytes: Uint8Array,
  raw: Required<RawOptions>,
  ctx: LoadContext,
  meta: Record<string, unknown> = {},
): LoadedVolume {
  const { dims, type } = raw;
  checkDims(dims, ctx, 'raw description');
  const count = dims[0] * dims[1] * dims[2];
  const need = count * SOURCE_BYTES[type];
  if (bytes.length < need) {
    throw new LoaderError(
      'truncated',
      `${ctx.name}: dims [${dims.join(' × ')}] of ${type} need ${need} bytes but the file has ${bytes.length}; it is cut short, or the dims/type are wrong`,
    );
  }
  if (bytes.length > need) {
    const fits = RAW_VOXEL_TYPES.filter((t) => count * SOURCE_BYTES[t] === bytes.length);
    throw new LoaderError(
      'bad-header',
      `${ctx.name}: the file has ${bytes.length} bytes but dims [${dims.join(' × ')}] of ${type} need ${need}` +
        (fits.length ? `; did you mean type ${fits.join(' or ')}?` : '; check the dims and type'),
    );
  }
  checkFits(dims, OUTPUT_BYTES[type], ctx);
  ctx.progress('convert', 0, count);
  const data = toVoxelArray(readSamples(bytes, 0, count, type, raw.endianness === 'little'), type);
  ctx.progress('convert', count, count);
  return finishVolume(
    {
      format: 'raw',
      dims: [...dims],
      spacing: [...raw.spacing],
      type,
      data,
      orientation:
        typeof meta.axisCodes === 'string' ? (orientationFromAxisCodes(meta.axisCodes) ?? undefined) : undefined,
      meta: { ...meta, endianness: raw.endianness },
    },
    ctx,
  );
}
