import type { RequestPolicy, Volume } from '@vpt/core';

/**
 * What loadVolume accepts: a URL (string or URL; a sidecar .json URL works too), a Blob or
 * File, the bytes themselves, or a set of files (a DICOM series, a dropped folder, a
 * sidecar with its raw file, a detached NRRD header with its data file).
 */
export type VolumeSource = string | URL | Blob | File | ArrayBuffer | ArrayBufferView | readonly File[];

export interface LoadProgress {
  /** fetch: bytes read; parse: compressed bytes inflated or DICOM files parsed; convert: voxels decoded. */
  stage: 'fetch' | 'parse' | 'convert';
  loaded: number;
  total?: number;
}

export type LoaderFormat = 'auto' | 'raw' | 'nrrd' | 'nifti' | 'dicom' | 'ome-zarr';

/**
 * What to read from an OME-Zarr store (a URL or, in Node, a folder path ending in .zarr;
 * the URL's fragment `#level=2&channel=1&time=0` does the same, these fields win).
 */
export interface ZarrLoadOptions {
  /** Level index, 0 = finest (default), or 'coarsest'. */
  level?: number | 'coarsest';
  /** Index along the `c` axis (default 0). */
  channel?: number;
  /**
   * Several indices along `c`, read in one pass over the chunks into one multichannel volume
   * (interleaved, channel fastest, in this order; `meta.channelRanges` holds their omero
   * windows). Replaces `channel`.
   */
  channels?: number[];
  /** Index along the `t` axis (default 0). */
  time?: number;
  /** A chunk the store lacks: 'fill' (default: the array's fill value, as the Zarr spec says) or 'error' (strict, reason 'not-found'). */
  missingChunks?: 'error' | 'fill';
  /** Shorthand for `request.stallTimeoutMs` (LoadOptions.request): the longest wait for an answer or for progress, in ms. */
  requestTimeoutMs?: number;
  /** Shorthand for `request.retries`: further attempts of a request that failed for a transient reason. */
  retries?: number;
}

export interface RawOptions {
  dims: [number, number, number];
  type: 'uint8' | 'uint16' | 'int16' | 'float32';
  spacing?: [number, number, number];
  endianness?: 'little' | 'big';
}

export interface LoadLimits {
  /** Largest allowed size of any axis (the device's 3D texture size). Default 2048. */
  maxTextureDimension3D?: number;
  /** Largest allowed size in bytes of the loaded voxel data (dims × bytes per voxel of the result type). Default 1 GiB. */
  maxBytes?: number;
}

export interface LoadOptions {
  /** auto: by file extension, then by magic bytes. */
  format?: LoaderFormat;
  /** Dims and type of headerless raw data (a sidecar .json next to it, or as the source, does the same). */
  raw?: RawOptions;
  signal?: AbortSignal;
  onProgress?: (p: LoadProgress) => void;
  limits?: LoadLimits;
  /** Shrink by integer factors (box average) to fit the limits instead of failing. */
  downsample?: boolean;
  /** OME-Zarr: level, channel, time and how to treat missing chunks. */
  zarr?: ZarrLoadOptions;
  /**
   * The time step to read of a time series held in one source (default 0): a 4D NIfTI
   * file's volume along dim[4], an OME-Zarr store's `t` index (where `zarr.time` is unset).
   * A source that holds one volume refuses a step above 0. `meta.timeSteps` says how many
   * there are (NIfTI, OME-Zarr).
   */
  time?: number;
  /**
   * Bounds on every HTTP request of this load (core's RequestPolicy: stall timeout on
   * headers and body, total bound, retries); unset fields keep DEFAULT_REQUEST_POLICY.
   */
  request?: Partial<RequestPolicy>;
  /** Parse in a Web Worker. Default true where Worker exists (browsers); Node parses in-thread. */
  worker?: boolean;
  /**
   * How the caller can give headerless raw data its dims and type, as the errors for such
   * data say it (default: "pass options.raw = { dims: [NX, NY, NZ], type }"). A caller
   * that cannot reach `raw` (an element attribute) names what it can: a sidecar, a file name.
   */
  rawHint?: string;
  /**
   * The source is a label volume (a segmentation: integer ids, 0 = background; core's
   * scene/labels.ts): its ids are kept, never averaged or normalized. uint8 and uint16 stay as
   * they are; any other type converts to the narrowest of the two when every value is an integer
   * in [0, 65535] (else LoaderError 'invalid-data'); OME-Zarr's `image-label` colours and names
   * come in `meta.zarr.imageLabel`; a downsample takes each
   * block's first voxel instead of the block's mean.
   */
  labels?: boolean;
}

/** The errors' advice for headerless raw data without dims (LoadOptions.rawHint). */
export const DEFAULT_RAW_HINT = 'pass options.raw = { dims: [NX, NY, NZ], type }';

/**
 * A Volume plus where it sits in the world. `orientation` is the 3×3 matrix of direction
 * cosines, row-major, whose columns are the world directions of the i, j, k index axes;
 * world = orientation · (index ∘ spacing) + origin, in the space named by `meta.space`
 * ('RAS' for NIfTI, 'LPS' for DICOM, NRRD's own `space`).
 */
export interface LoadedVolume extends Volume {
  format: string;
  orientation?: number[];
  origin?: [number, number, number];
  meta?: Record<string, unknown>;
}

export const DEFAULT_LIMITS: Required<LoadLimits> = {
  maxTextureDimension3D: 2048,
  maxBytes: 1024 * 1024 * 1024,
};
