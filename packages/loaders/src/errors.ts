import { RawReadError, VptError } from '@vpt/core';

/** Why a load failed; one value per thing a person can do something about. */
export type LoaderErrorReason =
  | 'not-found' // the URL answered 404/410, or a file named by a header is missing
  | 'network' // the request failed (offline, CORS, a 5xx answer)
  | 'truncated' // the file ends before the data its header announces
  | 'bad-header' // the header is malformed, incomplete or contradicts itself or the file size
  | 'bad-magic' // the bytes are not the format they were said or guessed to be
  | 'unsupported' // a valid file using a feature vpt does not read (compression, type, 4D…)
  | 'overflow' // dims whose voxel count cannot be addressed (≥ 2^32 voxels)
  | 'empty' // a dimension is 0: nothing to render
  | 'limit' // larger than the device/memory limit (code 'limit-exceeded')
  | 'aborted' // the caller's AbortSignal fired
  | 'invalid-data'; // the data itself is unusable (inconsistent DICOM slices, a crash while parsing)

export const LOADER_ERROR_REASONS: readonly LoaderErrorReason[] = [
  'not-found',
  'network',
  'truncated',
  'bad-header',
  'bad-magic',
  'unsupported',
  'overflow',
  'empty',
  'limit',
  'aborted',
  'invalid-data',
];

/**
 * Every load failure. `code` is core's 'load-failed', except `reason: 'limit'`, which uses
 * 'limit-exceeded' so an application handles "too big for this device" in one place,
 * whether the loader or the render context noticed it.
 */
export class LoaderError extends VptError {
  readonly reason: LoaderErrorReason;
  constructor(reason: LoaderErrorReason, message: string, options?: { cause?: unknown }) {
    super(reason === 'limit' ? 'limit-exceeded' : 'load-failed', message, options);
    this.name = 'LoaderError';
    this.reason = reason;
  }
}

/** Run core's raw reader, turning its RawReadError into a LoaderError with the same reason and message. */
export function asLoaderError<T>(read: () => T): T {
  try {
    return read();
  } catch (e) {
    if (e instanceof RawReadError) throw new LoaderError(e.reason, e.message, { cause: e });
    throw e;
  }
}

export function isLoaderError(e: unknown, reason?: LoaderErrorReason): e is LoaderError {
  return e instanceof LoaderError && (reason === undefined || e.reason === reason);
}

/** Prefix used for errors that escaped every specific check (a bug; the fuzz tests look for it). */
export const UNEXPECTED_PREFIX = 'Unexpected error while loading';

/**
 * Turn anything thrown into a LoaderError. An allocation failure is reported as a memory
 * limit; anything else that is not already a LoaderError is a bug, reported as such.
 */
export function toLoaderError(e: unknown, what: string): LoaderError {
  if (e instanceof LoaderError) return e;
  if (isAbort(e)) return new LoaderError('aborted', `Loading ${what} was aborted`, { cause: e });
  if (e instanceof RangeError && /allocat|Invalid typed array length|Array buffer/i.test(e.message)) {
    return new LoaderError(
      'limit',
      `${what}: out of memory (${e.message}); pass limits.maxBytes and downsample: true to load a smaller copy`,
      { cause: e },
    );
  }
  const msg = e instanceof Error ? e.message : String(e);
  return new LoaderError('invalid-data', `${UNEXPECTED_PREFIX} ${what}: ${msg}`, { cause: e });
}

export function isAbort(e: unknown): boolean {
  return typeof e === 'object' && e !== null && (e as { name?: string }).name === 'AbortError';
}

export function throwIfAborted(signal: AbortSignal | undefined, what: string): void {
  if (signal?.aborted) throw new LoaderError('aborted', `Loading ${what} was aborted`, { cause: signal.reason });
}
