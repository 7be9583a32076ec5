import { fetchWithPolicy, RequestError } from '@vpt/core';
import { LoaderError, isAbort } from '../errors.js';
import type { LoadContext } from '../context.js';

/** Largest text file fetched (a JSON sidecar, a detached NRRD header). */
export const MAX_TEXT_BYTES = 16 * 1024 * 1024;

/**
 * Largest data file fetched: twice the voxel bound (a float64 file becomes float32) plus a
 * header; with downsampling on, a file may hold more than the bound, up to 4 GiB.
 */
function dataFileBound(ctx: LoadContext): number {
  return ctx.downsample ? 4 * 1024 ** 3 : 2 * ctx.limits.maxBytes + (1 << 20);
}

/** Fetch a URL into one buffer under core's request policy, with 'fetch' progress. */
export async function fetchBytes(url: string, ctx: LoadContext, maxBytes = dataFileBound(ctx)): Promise<Uint8Array> {
  ctx.checkAborted();
  if (typeof fetch !== 'function')
    throw new LoaderError(
      'unsupported',
      `Cannot load ${url}: this environment has no fetch(); pass the bytes (ArrayBuffer or Blob) instead`,
    );
  try {
    const { bytes } = await fetchWithPolicy(url, {
      signal: ctx.signal,
      policy: ctx.request,
      maxBytes,
      onProgress: (loaded, total) => ctx.progress('fetch', loaded, total),
    });
    return bytes;
  } catch (e) {
    throw asLoaderRequestError(e);
  }
}

export async function fetchText(url: string, ctx: LoadContext): Promise<string> {
  const bytes = await fetchBytes(url, ctx, MAX_TEXT_BYTES);
  return new TextDecoder().decode(bytes);
}

/** Core's RequestError as a LoaderError with the same reason and message (a bound or a stall is reason 'network'). */
export function asLoaderRequestError(e: unknown): unknown {
  if (e instanceof RequestError) return new LoaderError(e.reason, e.message, { cause: e });
  return e;
}

/** Read a Blob or File with 'fetch' progress (Blob.stream where there is one). */
export async function readBlob(blob: Blob, ctx: LoadContext): Promise<Uint8Array> {
  ctx.checkAborted();
  const name = (blob as File).name || ctx.name;
  if (typeof blob.stream === 'function') return readStream(blob.stream(), blob.size, name, ctx);
  const buf = new Uint8Array(await guard(() => blob.arrayBuffer(), name, ctx));
  ctx.progress('fetch', buf.length, buf.length);
  return buf;
}

/**
 * Drain a byte stream. With a known length the chunks go straight into one preallocated
 * buffer (no second copy of a large volume); otherwise they are joined at the end.
 */
async function readStream(
  stream: ReadableStream<Uint8Array>,
  total: number | undefined,
  name: string,
  ctx: LoadContext,
): Promise<Uint8Array> {
  const reader = stream.getReader();
  const onAbort = () => {
    void reader.cancel().catch(() => {});
  };
  ctx.signal?.addEventListener('abort', onAbort, { once: true });
  let out = total !== undefined ? new Uint8Array(total) : undefined;
  const chunks: Uint8Array[] = [];
  let loaded = 0;
  ctx.progress('fetch', 0, total);
  try {
    for (;;) {
      const { done, value } = await guard(() => reader.read(), name, ctx);
      ctx.checkAborted();
      if (done) break;
      if (out && loaded + value.length <= out.length) {
        out.set(value, loaded);
      } else {
        // The body is longer than announced: fall back to collecting chunks.
        if (out) {
          chunks.push(out.subarray(0, loaded));
          out = undefined;
        }
        chunks.push(value);
      }
      loaded += value.length;
      ctx.progress('fetch', loaded, total);
    }
  } finally {
    ctx.signal?.removeEventListener('abort', onAbort);
  }
  if (out) {
    if (loaded < out.length) {
      throw new LoaderError(
        'truncated',
        `${name}: the transfer ended after ${loaded} of ${out.length} bytes; try again or check the connection`,
      );
    }
    return out;
  }
  return concat(chunks, loaded);
}

export function concat(chunks: Uint8Array[], length = chunks.reduce((n, c) => n + c.length, 0)): Uint8Array {
  if (chunks.length === 1) return chunks[0];
  const out = new Uint8Array(length);
  let at = 0;
  for (const c of chunks) {
    out.set(c, at);
    at += c.length;
  }
  return out;
}

async function guard<T>(f: () => Promise<T>, name: string, ctx: LoadContext): Promise<T> {
  try {
    return await f();
  } catch (e) {
    if (e instanceof LoaderError) throw e;
    if (isAbort(e) || ctx.signal?.aborted)
      throw new LoaderError('aborted', `Loading ${name} was aborted`, { cause: e });
    throw new LoaderError('network', `Reading ${name} failed: ${(e as Error)?.message ?? e}`, { cause: e });
  }
}

/** Bytes of an ArrayBuffer or view, as a Uint8Array over the same memory (no copy). */
export function bytesOf(data: ArrayBuffer | ArrayBufferView): Uint8Array {
  if (data instanceof ArrayBuffer) return new Uint8Array(data);
  return new Uint8Array(data.buffer, data.byteOffset, data.byteLength);
}
