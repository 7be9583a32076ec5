import { LoaderError, isAbort } from '../errors.js';
import type { LoadContext } from '../context.js';

/** Fetch a URL into one buffer, streaming the body with 'fetch' progress. */
export async function fetchBytes(url: string, ctx: LoadContext): Promise<Uint8Array> {
  const response = await fetchResponse(url, ctx);
  const encoded = response.headers.get('content-encoding');
  const lengthHeader = response.headers.get('content-length');
  // With a content-encoding the header counts compressed bytes, not what the body yields.
  const total = lengthHeader !== null && !encoded && /^\d+$/.test(lengthHeader) ? Number(lengthHeader) : undefined;
  if (!response.body) {
    const buf = new Uint8Array(await guard(() => response.arrayBuffer(), url, ctx));
    ctx.progress('fetch', buf.length, buf.length);
    return buf;
  }
  return readStream(response.body, total, url, ctx);
}

export async function fetchText(url: string, ctx: LoadContext): Promise<string> {
  const bytes = await fetchBytes(url, ctx);
  return new TextDecoder().decode(bytes);
}

async function fetchResponse(url: string, ctx: LoadContext): Promise<Response> {
  ctx.checkAborted();
  if (typeof fetch !== 'function')
    throw new LoaderError(
      'unsupported',
      `Cannot load ${url}: this environment has no fetch(); pass the bytes (ArrayBuffer or Blob) instead`,
    );
  let response: Response;
  try {
    response = await fetch(url, { signal: ctx.signal });
  } catch (e) {
    if (isAbort(e) || ctx.signal?.aborted) throw new LoaderError('aborted', `Loading ${url} was aborted`, { cause: e });
    const scheme = safeProtocol(url);
    const hint =
      scheme === 'file:'
        ? "file: URLs cannot be fetched here; pass the file's bytes or a File instead"
        : 'check the address, that the server is running, and that it allows cross-origin requests (CORS)';
    throw new LoaderError('network', `Could not fetch ${url}: ${(e as Error)?.message ?? e}; ${hint}`, { cause: e });
  }
  if (response.status === 404 || response.status === 410) {
    void response.body?.cancel().catch(() => {});
    throw new LoaderError('not-found', `${url} was not found (HTTP ${response.status}); check the path and file name`);
  }
  if (!response.ok) {
    void response.body?.cancel().catch(() => {});
    throw new LoaderError(
      'network',
      `Fetching ${url} failed with HTTP ${response.status} ${response.statusText}`.trim(),
    );
  }
  return response;
}

function safeProtocol(url: string): string {
  try {
    return new URL(url).protocol;
  } catch {
    return '';
  }
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
