/**
 * The one request policy for every URL vpt fetches (volumes, sidecars, environments,
 * OME-Zarr chunks; in the loaders, the viewer and the headless page): a stall timeout on
 * the headers and on the body, a total bound on the whole request, retries of transient
 * failures that start only while the total bound leaves room for them, and a size bound.
 * A request therefore ends — with the bytes or with a RequestError — within
 * `totalTimeoutMs`, whatever the server does.
 */
import { VptError } from '../errors.js';

export interface RequestPolicy {
  /**
   * Longest wait for the response headers, and the window in which the body must bring at
   * least `stallBytes` bytes (or end), in ms. A server that never answers, or that sends
   * headers and then nothing, fails after this long.
   */
  stallTimeoutMs: number;
  /** Bytes the body must bring in every stall window: a 1-byte-per-second trickle counts as a stall. */
  stallBytes: number;
  /** Longest time for the whole request, every attempt and pause included, in ms. */
  totalTimeoutMs: number;
  /** Further attempts after a transient failure (connection error, HTTP 408/429/5xx, a broken or stalled transfer). */
  retries: number;
  /** Pause before the first retry in ms, doubled for each further one. */
  retryDelayMs: number;
}

/** The defaults: a stalled server fails after about 3 × 10 s, any request after 5 minutes at most. */
export const DEFAULT_REQUEST_POLICY: Readonly<RequestPolicy> = Object.freeze({
  stallTimeoutMs: 10_000,
  stallBytes: 1024,
  totalTimeoutMs: 300_000,
  retries: 2,
  retryDelayMs: 200,
});

/** Why a request failed (the subset of the loaders' reasons a transfer can have). */
export type RequestFailure = 'not-found' | 'network' | 'truncated' | 'limit' | 'aborted';

/** A failed request. `timedOut`: a stall or the total bound ended it; `status`: the HTTP status, when one came. */
export class RequestError extends VptError {
  readonly reason: RequestFailure;
  readonly timedOut: boolean;
  readonly status?: number;
  constructor(
    reason: RequestFailure,
    message: string,
    options: { cause?: unknown; timedOut?: boolean; status?: number } = {},
  ) {
    super(reason === 'limit' ? 'limit-exceeded' : 'load-failed', message, { cause: options.cause });
    this.name = 'RequestError';
    this.reason = reason;
    this.timedOut = options.timedOut === true;
    if (options.status !== undefined) this.status = options.status;
  }
}

export interface FetchOptions {
  signal?: AbortSignal;
  headers?: Record<string, string>;
  method?: 'GET' | 'HEAD';
  /** Overrides of DEFAULT_REQUEST_POLICY (undefined fields keep the default). */
  policy?: Partial<RequestPolicy>;
  /** Largest body accepted in bytes: a larger content-length fails before reading, a longer body once it passes the bound. */
  maxBytes?: number;
  /** Bytes read so far and the announced total (undefined when unknown), as they arrive. */
  onProgress?: (loaded: number, total: number | undefined) => void;
}

export interface FetchedBytes {
  bytes: Uint8Array;
  status: number;
  headers: Headers;
}

const POLICY_KEYS = Object.keys(DEFAULT_REQUEST_POLICY) as (keyof RequestPolicy)[];

/**
 * Defaults filled in and every field checked: a policy from a scene file, an environment
 * variable or an element property must not turn into an unbounded request.
 */
export function resolveRequestPolicy(policy: Partial<RequestPolicy> = {}): RequestPolicy {
  if (typeof policy !== 'object' || policy === null)
    throw new VptError('invalid-scene', `request policy: must be an object, got ${JSON.stringify(policy)}`);
  const unknown = Object.keys(policy).filter((k) => !(POLICY_KEYS as string[]).includes(k));
  if (unknown.length)
    throw new VptError(
      'invalid-scene',
      `request policy: unknown key${unknown.length > 1 ? 's' : ''} ${unknown.join(', ')} (known: ${POLICY_KEYS.join(', ')})`,
    );
  const out = { ...DEFAULT_REQUEST_POLICY };
  for (const k of POLICY_KEYS) {
    const v = policy[k];
    if (v === undefined) continue;
    const integer = k === 'retries' || k === 'stallBytes';
    const ok = typeof v === 'number' && Number.isFinite(v) && v >= (k === 'retries' || k === 'retryDelayMs' ? 0 : 1);
    if (!ok || (integer && !Number.isInteger(v)) || (k === 'retries' && v > 10))
      throw new VptError(
        'invalid-scene',
        `request policy: ${k} must be a finite ${integer ? 'integer' : 'number'} ${k === 'retries' ? 'in [0, 10]' : k === 'retryDelayMs' ? '≥ 0' : '≥ 1'}, got ${JSON.stringify(v)}`,
      );
    out[k] = v;
  }
  return out;
}

/** The statuses worth another attempt: the server or a proxy may answer next time. */
function transientStatus(status: number): boolean {
  return status === 408 || status === 429 || status >= 500;
}

function transient(e: RequestError): boolean {
  return (e.reason === 'network' || e.reason === 'truncated') && (e.status === undefined || transientStatus(e.status));
}

/**
 * Fetch a URL's body into one buffer under the request policy. Resolves with the bytes of a
 * 2xx answer; anything else rejects with a RequestError: 'not-found' (HTTP 404/410),
 * 'network' (no connection, another status, a stall, the total bound; `timedOut` says
 * which), 'truncated' (fewer bytes than announced), 'limit' (larger than maxBytes),
 * 'aborted' (the caller's signal).
 */
export async function fetchWithPolicy(url: string, options: FetchOptions = {}): Promise<FetchedBytes> {
  const policy = resolveRequestPolicy(options.policy);
  const deadline = Date.now() + policy.totalTimeoutMs;
  if (typeof fetch !== 'function')
    throw new RequestError('network', `Cannot fetch ${url}: this environment has no fetch()`);
  for (let attempt = 0; ; attempt++) {
    try {
      return await attemptOnce(url, options, policy, deadline);
    } catch (e) {
      const err = e as RequestError;
      const pause = policy.retryDelayMs * 2 ** attempt;
      // A retry starts only when it can still wait out one stall window inside the total bound.
      const room = deadline - Date.now() - pause >= Math.min(policy.stallTimeoutMs, policy.totalTimeoutMs / 4);
      if (!transient(err) || attempt >= policy.retries || !room || options.signal?.aborted) throw err;
      await sleep(pause, options.signal);
    }
  }
}

function sleep(ms: number, signal: AbortSignal | undefined): Promise<void> {
  return new Promise((resolve) => {
    const timer = setTimeout(done, ms);
    signal?.addEventListener('abort', done, { once: true });
    function done() {
      clearTimeout(timer);
      signal?.removeEventListener('abort', done);
      resolve();
    }
  });
}

type StopReason = 'stall-headers' | 'stall-body' | 'total' | 'limit' | null;

async function attemptOnce(
  url: string,
  options: FetchOptions,
  policy: RequestPolicy,
  deadline: number,
): Promise<FetchedBytes> {
  const { signal } = options;
  if (signal?.aborted) throw new RequestError('aborted', `Loading ${url} was aborted`, { cause: signal.reason });
  // One controller for the caller's abort, the stall windows and the total bound, so that
  // each of them also ends a body read in progress.
  const controller = new AbortController();
  let stop: StopReason = null;
  const end = (why: StopReason) => {
    stop ??= why;
    controller.abort();
  };
  const onAbort = () => controller.abort();
  signal?.addEventListener('abort', onAbort, { once: true });
  let complete = false;
  const totalTimer = setTimeout(() => end('total'), Math.max(0, deadline - Date.now()));
  let stallTimer = setTimeout(() => end('stall-headers'), policy.stallTimeoutMs);
  const started = Date.now();
  const fail = (e: unknown, loaded?: number): RequestError => {
    if (e instanceof RequestError) return e;
    if (signal?.aborted) return new RequestError('aborted', `Loading ${url} was aborted`, { cause: e });
    const ms = Date.now() - started;
    if (stop === 'stall-headers')
      return new RequestError('network', `${url}: no answer within ${policy.stallTimeoutMs} ms (timed out)`, {
        cause: e,
        timedOut: true,
      });
    if (stop === 'stall-body')
      return new RequestError(
        'network',
        `${url}: the transfer stalled after ${loaded ?? 0} bytes (fewer than ${policy.stallBytes} bytes in ${policy.stallTimeoutMs} ms; timed out)`,
        { cause: e, timedOut: true },
      );
    if (stop === 'total')
      return new RequestError(
        'network',
        `${url}: not complete within the request bound of ${policy.totalTimeoutMs} ms (${loaded ?? 0} bytes in ${ms} ms; timed out)`,
        { cause: e, timedOut: true },
      );
    const scheme = /^([a-z][a-z0-9+.-]*):/i.exec(url)?.[1]?.toLowerCase();
    const hint =
      scheme === 'file'
        ? "; file: URLs cannot be fetched here, pass the file's bytes or a File instead"
        : loaded === undefined
          ? '; check the address, that the server is running, that it allows cross-origin requests (CORS), and that it does not redirect in a loop'
          : '';
    const what = loaded === undefined ? 'Could not fetch' : `Reading ${url} broke off after ${loaded} bytes:`;
    return new RequestError(
      loaded === undefined ? 'network' : 'truncated',
      `${loaded === undefined ? `${what} ${url}:` : what} ${(e as Error)?.message ?? e}${hint}`,
      { cause: e },
    );
  };
  try {
    let response: Response;
    try {
      response = await fetch(url, {
        signal: controller.signal,
        ...(options.headers ? { headers: options.headers } : {}),
        ...(options.method ? { method: options.method } : {}),
      });
    } catch (e) {
      throw fail(e);
    }
    const { status } = response;
    if (status < 200 || status > 299) {
      void response.body?.cancel().catch(() => {});
      if (status === 404 || status === 410)
        throw new RequestError('not-found', `${url} was not found (HTTP ${status}); check the path and file name`, {
          status,
        });
      throw new RequestError('network', `Fetching ${url} failed with HTTP ${status} ${response.statusText}`.trim(), {
        status,
      });
    }
    const encoded = response.headers.get('content-encoding');
    const lengthHeader = response.headers.get('content-length');
    // With a content-encoding the header counts compressed bytes, not what the body yields.
    const total =
      lengthHeader !== null && !encoded && /^\d+$/.test(lengthHeader.trim()) ? Number(lengthHeader) : undefined;
    const maxBytes = options.maxBytes ?? Infinity;
    if (total !== undefined && total > maxBytes) {
      void response.body?.cancel().catch(() => {});
      throw limitError(url, maxBytes, `it announces ${total}`);
    }
    clearTimeout(stallTimer);
    if (options.method === 'HEAD' || !response.body) {
      // No stream to watch (HEAD, or an old engine): the total bound still applies.
      let bytes: Uint8Array;
      try {
        bytes = options.method === 'HEAD' ? new Uint8Array(0) : new Uint8Array(await response.arrayBuffer());
      } catch (e) {
        throw fail(e, 0);
      }
      if (bytes.length > maxBytes) throw limitError(url, maxBytes, `it holds ${bytes.length}`);
      options.onProgress?.(bytes.length, bytes.length);
      return { bytes, status, headers: response.headers };
    }
    // The bytes are read natively (arrayBuffer) and a clone of the body is read by script, only
    // to count bytes for progress, the stall windows and the size bound. Chromium cancels the URL
    // loader (logged as a failed request, net::ERR_ABORTED) when a body stream read by script
    // ends before the network's completion message arrives, which happens in most loads; a
    // native read waits for that message, and the clone's end cancels only its own tee branch.
    const counted = response.clone().body;
    const whole = response.arrayBuffer();
    whole.catch(() => {}); // awaited below; a stop or a broken transfer is reported from there
    if (!counted) throw new RequestError('network', `${url}: the answer's body cannot be read twice`);
    const reader = counted.getReader();
    controller.signal.addEventListener('abort', () => void reader.cancel().catch(() => {}), { once: true });
    let loaded = 0;
    let windowStart = 0;
    const armStall = (): void => {
      stallTimer = setTimeout(() => {
        if (loaded - windowStart < policy.stallBytes) end('stall-body');
        else {
          windowStart = loaded;
          armStall();
        }
      }, policy.stallTimeoutMs);
    };
    armStall();
    options.onProgress?.(0, total);
    for (;;) {
      let chunk: ReadableStreamReadResult<Uint8Array>;
      try {
        chunk = await reader.read();
      } catch (e) {
        throw fail(e, loaded);
      }
      if (stop || signal?.aborted) throw fail(new Error('stopped'), loaded);
      if (chunk.done) break;
      if (loaded + chunk.value.length > maxBytes) {
        end('limit');
        throw limitError(url, maxBytes, 'the body is longer');
      }
      loaded += chunk.value.length;
      options.onProgress?.(loaded, total);
    }
    // The network is done (the clone has ended); the native read only has its copy left.
    clearTimeout(stallTimer);
    let bytes: Uint8Array;
    try {
      bytes = new Uint8Array(await whole);
    } catch (e) {
      throw fail(e, loaded);
    }
    if (stop || signal?.aborted) throw fail(new Error('stopped'), loaded);
    if (total !== undefined && bytes.length < total)
      throw new RequestError(
        'truncated',
        `${url}: the transfer ended after ${bytes.length} of ${total} bytes; try again or check the connection`,
      );
    if (bytes.length > maxBytes) throw limitError(url, maxBytes, `it holds ${bytes.length}`);
    complete = true;
    return { bytes, status, headers: response.headers };
  } finally {
    // A failed attempt leaves nothing running (the native read of a refused body included).
    if (!complete) controller.abort();
    clearTimeout(stallTimer);
    clearTimeout(totalTimer);
    signal?.removeEventListener('abort', onAbort);
  }
}

function limitError(url: string, maxBytes: number, what: string): RequestError {
  return new RequestError('limit', `${url}: larger than the ${maxBytes} bytes allowed for it (${what})`);
}
