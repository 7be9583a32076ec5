/**
 * The read-only key → bytes store zarrita reads an OME-Zarr through: HTTP(S) with range
 * requests, or a folder on disk in Node. It exists (rather than zarrita's FetchStore) so
 * every failure is a LoaderError with a reason, every request runs under core's request
 * policy (a stall times out instead of hanging, a transient failure is retried, all of it
 * inside a total bound), and the bytes fetched are counted.
 */
import { fetchWithPolicy, RequestError, type FetchedBytes, type RequestPolicy } from '@vpt/core';
import { LoaderError } from '../errors.js';

/** Largest object (metadata file or chunk, as stored) fetched from a store. */
const MAX_OBJECT_BYTES = 1024 * 1024 * 1024;

/** The zarrita store contract (`AsyncReadable` of @zarrita/storage), restated so this module needs no import. */
export interface ZarrReadStore {
  get(key: `/${string}`, opts?: { signal?: AbortSignal }): Promise<Uint8Array | undefined>;
  getRange?(
    key: `/${string}`,
    range: { offset: number; length: number } | { suffixLength: number },
    opts?: { signal?: AbortSignal },
  ): Promise<Uint8Array | undefined>;
}

export interface ZarrStoreOptions {
  signal?: AbortSignal;
  /** Bounds on every request (core's RequestPolicy; unset fields keep DEFAULT_REQUEST_POLICY). */
  request?: Partial<RequestPolicy>;
  /** Shorthand for `request.stallTimeoutMs`: the longest wait for an answer or for progress, in ms. */
  requestTimeoutMs?: number;
  /** Shorthand for `request.retries`: further attempts after a transient failure (network error, 5xx, stall). */
  retries?: number;
  /**
   * A chunk the store does not have: 'fill' (default) reads it as the array's fill value, as
   * the Zarr spec says (zarr-python does not write chunks that hold only the fill value);
   * 'error' fails with reason 'not-found' (strict: for stores known to be complete).
   */
  missingChunks?: 'error' | 'fill';
  /** Called with the byte count of every answer (for progress and benchmarks). */
  onBytes?: (bytes: number) => void;
  /**
   * Bytes of chunks (as stored, compressed) kept for reads that overlap: a brick is read
   * with a one-voxel apron, so each chunk serves up to 27 bricks' reads. Least recently
   * used out; requests for a chunk already on its way share it. Default 32 MiB; 0: none.
   */
  chunkCacheBytes?: number;
}

export interface CountingStore extends ZarrReadStore {
  /** Where the store reads from, for messages. */
  readonly location: string;
  /** Bytes received so far. */
  bytesRead: number;
}

const METADATA_KEY = /(^|\/)(zarr\.json|\.zarray|\.zattrs|\.zgroup|\.zmetadata)$/;

/** A URL with a scheme other than file: goes over fetch; anything else is a path (Node). */
export function isHttpLocation(location: string): boolean {
  return /^[a-z][a-z0-9+.-]*:/i.test(location) && !/^file:/i.test(location);
}

/** Promises of chunk bytes by key, least recently used dropped past `limit` bytes; a failed read is forgotten. */
function chunkCache(limit: number) {
  if (!(limit > 0)) return null;
  const entries = new Map<string, { promise: Promise<Uint8Array | undefined>; bytes: number }>();
  let total = 0;
  return {
    get(key: string, read: () => Promise<Uint8Array | undefined>): Promise<Uint8Array | undefined> {
      const hit = entries.get(key);
      if (hit) {
        entries.delete(key);
        entries.set(key, hit);
        return hit.promise;
      }
      const entry = { promise: read(), bytes: 0 };
      entries.set(key, entry);
      entry.promise.then(
        (b) => {
          if (entries.get(key) !== entry) return;
          entry.bytes = b?.length ?? 0;
          total += entry.bytes;
          for (const [k, e] of entries) {
            if (total <= limit) break;
            if (e.bytes === 0) continue; // still on its way
            entries.delete(k);
            total -= e.bytes;
          }
        },
        () => {
          if (entries.get(key) === entry) entries.delete(key);
        },
      );
      return entry.promise;
    },
  };
}

/** `promise`, or an abort error as soon as `signal` aborts. */
function abortable<T>(promise: Promise<T>, signal: AbortSignal | undefined): Promise<T> {
  if (!signal) return promise;
  if (signal.aborted) return Promise.reject(signal.reason);
  return new Promise<T>((resolve, reject) => {
    const onAbort = () => reject(signal.reason);
    signal.addEventListener('abort', onAbort, { once: true });
    promise.then(
      (v) => {
        signal.removeEventListener('abort', onAbort);
        resolve(v);
      },
      (e) => {
        signal.removeEventListener('abort', onAbort);
        reject(e);
      },
    );
  });
}

export async function openZarrStore(location: string, options: ZarrStoreOptions = {}): Promise<CountingStore> {
  const base = isHttpLocation(location) ? httpReader(location, options) : await fileReader(location);
  const missing = options.missingChunks ?? 'fill';
  const cache = chunkCache(options.chunkCacheBytes ?? 32 << 20);
  const store: CountingStore = {
    location,
    bytesRead: 0,
    async get(key, opts) {
      if (METADATA_KEY.test(key) || !cache)
        return counted(key, await base.read(key, undefined, opts?.signal ?? options.signal));
      // Shared by every read of this chunk, so it runs under the store's signal; a caller's own abort still ends its wait.
      const bytes = await abortable(
        cache.get(key, async () => counted(key, await base.read(key, undefined, options.signal))),
        opts?.signal,
      );
      return bytes?.slice(); // a copy: decoders may work in place
    },
    async getRange(key, range, opts) {
      const bytes = await base.read(key, range, opts?.signal ?? options.signal);
      return counted(key, bytes);
    },
  };
  function counted(key: string, bytes: Uint8Array | undefined): Uint8Array | undefined {
    if (bytes === undefined) {
      // Metadata keys are probed (v3 zarr.json, then v2 .zarray/.zgroup): absent is an answer.
      if (!METADATA_KEY.test(key) && missing === 'error')
        throw new LoaderError(
          'not-found',
          `${location}: chunk ${key} is missing (the store answered "not found"); ` +
            "zarr.missingChunks is 'error' (strict); the default 'fill' reads it as the fill value",
        );
      return undefined;
    }
    store.bytesRead += bytes.length;
    options.onBytes?.(bytes.length);
    return bytes;
  }
  return store;
}

interface Reader {
  read(
    key: string,
    range: { offset: number; length: number } | { suffixLength: number } | undefined,
    signal: AbortSignal | undefined,
  ): Promise<Uint8Array | undefined>;
}

function httpReader(location: string, options: ZarrStoreOptions): Reader {
  // Every key resolves under the store's folder and keeps its query (a signed URL's token).
  const base = new URL(location.replace(/#.*$/, ''));
  if (!base.pathname.endsWith('/')) base.pathname += '/';
  // Core's one request policy; the older shorthands set its stall timeout and retries.
  const policy: Partial<RequestPolicy> = {
    ...options.request,
    ...(options.requestTimeoutMs !== undefined ? { stallTimeoutMs: options.requestTimeoutMs } : {}),
    ...(options.retries !== undefined ? { retries: options.retries } : {}),
  };
  return {
    async read(key, range, signal) {
      const target = new URL(key.replace(/^\/+/, ''), base);
      target.search = base.search;
      const url = target.href;
      const headers: Record<string, string> = {};
      if (range) {
        headers.Range =
          'suffixLength' in range
            ? `bytes=-${range.suffixLength}`
            : `bytes=${range.offset}-${range.offset + range.length - 1}`;
      }
      let answer: FetchedBytes;
      try {
        answer = await fetchWithPolicy(url, { headers, signal, policy, maxBytes: MAX_OBJECT_BYTES });
      } catch (e) {
        // 403: object stores answer it for absent keys of a private listing.
        if (e instanceof RequestError && (e.reason === 'not-found' || e.status === 403)) return undefined;
        if (e instanceof RequestError) throw new LoaderError(e.reason, e.message, { cause: e });
        throw e;
      }
      const { bytes, status } = answer;
      if (status !== 200 && status !== 206)
        throw new LoaderError('network', `Fetching ${url} failed with HTTP ${status}`);
      // A server that ignores Range sends the whole object: cut the range out here.
      if (range && status === 200) {
        if ('suffixLength' in range) return bytes.subarray(Math.max(0, bytes.length - range.suffixLength));
        return bytes.subarray(range.offset, range.offset + range.length);
      }
      return bytes;
    },
  };
}

/** The few Node functions the folder reader uses (this package is built without Node's types). */
interface NodeFs {
  stat(p: string): Promise<{ isDirectory(): boolean }>;
  readFile(p: string): Promise<Uint8Array>;
}
interface NodePath {
  resolve(...p: string[]): string;
  join(...p: string[]): string;
}
interface NodeUrl {
  fileURLToPath(u: string): string;
}

/** A folder in Node (a path or file: URL). node:fs is imported by a computed name so browser bundles never see it. */
async function fileReader(location: string): Promise<Reader> {
  const names = ['node:fs/promises', 'node:path', 'node:url'];
  let fs: NodeFs, path: NodePath, url: NodeUrl;
  try {
    [fs, path, url] = (await Promise.all(names.map((n) => import(/* @vite-ignore */ n)))) as [
      NodeFs,
      NodePath,
      NodeUrl,
    ];
  } catch (e) {
    throw new LoaderError(
      'unsupported',
      `${location}: a path can be read only in Node; in a browser give an http(s) URL of the store`,
      { cause: e },
    );
  }
  const root = /^file:/i.test(location) ? url.fileURLToPath(location) : path.resolve(location);
  try {
    if (!(await fs.stat(root)).isDirectory())
      throw new LoaderError('bad-header', `${location} is a file; an OME-Zarr store is a folder`);
  } catch (e) {
    if (e instanceof LoaderError) throw e;
    throw new LoaderError('not-found', `${location}: no such folder`, { cause: e });
  }
  return {
    async read(key, range, signal) {
      if (signal?.aborted) throw new LoaderError('aborted', `Loading ${location} was aborted`);
      const file = path.join(root, ...key.split('/').filter((p) => p && p !== '..' && p !== '.'));
      let bytes: Uint8Array;
      try {
        bytes = new Uint8Array(await fs.readFile(file));
      } catch (e) {
        const code = (e as { code?: string }).code;
        if (code === 'ENOENT' || code === 'ENOTDIR' || code === 'EISDIR') return undefined;
        throw new LoaderError('network', `${file}: ${(e as Error).message}`, { cause: e });
      }
      if (!range) return bytes;
      if ('suffixLength' in range) return bytes.subarray(Math.max(0, bytes.length - range.suffixLength));
      return bytes.subarray(range.offset, range.offset + range.length);
    },
  };
}
