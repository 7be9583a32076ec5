/**
 * Lat-long HDR environments from a URL: Radiance .hdr (RGBE) and OpenEXR, decoded by
 * Three.js' loaders, converted to core's Environment (RGB floats, row 0 at the top).
 */
import { RequestError, VptError, fetchWithPolicy, type Environment, type RequestPolicy } from '@vpt/core';
import type { DecodedEnvironment } from './environment-decode.js';

/**
 * Longest decode of an environment file, in ms (also bounded by the request policy's
 * totalTimeoutMs when that is shorter): an 8k × 4k EXR decodes in seconds; a hostile file on
 * which a decoder loops is stopped here, its worker terminated.
 */
export const ENVIRONMENT_DECODE_TIMEOUT_MS = 60_000;

/**
 * Decode in a fresh module worker (environment-worker.ts), so the page's main thread stays
 * responsive however long the decoder runs; terminated after its answer or at the time bound
 * (VptError 'limit-exceeded'). Where no worker can start, decodes in this thread.
 */
async function decode(url: string, buffer: ArrayBuffer, timeoutMs: number): Promise<DecodedEnvironment> {
  let worker: Worker | undefined;
  try {
    if (typeof Worker === 'function')
      worker = new Worker(new URL('./environment-worker.js', import.meta.url), {
        type: 'module',
        name: 'vpt-environment',
      });
  } catch {
    worker = undefined;
  }
  if (!worker) {
    const { decodeEnvironment } = await import('./environment-decode.js');
    return decodeEnvironment(url, buffer);
  }
  const w = worker;
  return new Promise<DecodedEnvironment>((resolve, reject) => {
    const timer = setTimeout(
      () =>
        finish(() =>
          reject(
            new VptError(
              'limit-exceeded',
              `environment: decoding ${url} took longer than ${timeoutMs} ms and was stopped (a damaged or hostile .hdr/.exr file?)`,
            ),
          ),
        ),
      timeoutMs,
    );
    function finish(f: () => void) {
      clearTimeout(timer);
      w.terminate();
      f();
    }
    w.onmessage = (e: MessageEvent) => {
      const m = e.data as
        ({ type: 'result' } & DecodedEnvironment) | { type: 'error'; code: VptError['code'] | null; message: string };
      if (m.type === 'result')
        finish(() => resolve({ width: m.width, height: m.height, data: m.data, bottomUp: m.bottomUp }));
      else if (m.code) finish(() => reject(new VptError(m.code!, m.message)));
      else finish(() => reject(new Error(m.message)));
    };
    w.onerror = (e: ErrorEvent) => {
      e.preventDefault();
      finish(() => reject(new Error(`the environment decoder failed (${e.message || 'worker error'})`)));
    };
    w.postMessage({ url, buffer }, [buffer]);
  });
}

/** Largest environment file fetched: an 8k × 4k float RGBA EXR, uncompressed. */
export const MAX_ENVIRONMENT_BYTES = 512 * 1024 * 1024;

export interface EnvironmentLoadOptions {
  signal?: AbortSignal;
  /** Bounds on the request (core's RequestPolicy overrides). */
  request?: Partial<RequestPolicy>;
}

export async function loadEnvironment(
  url: string,
  scale = 1,
  options: EnvironmentLoadOptions = {},
): Promise<Environment> {
  const href = new URL(url, globalThis.document?.baseURI).href;
  let buffer: ArrayBuffer;
  try {
    const { bytes } = await fetchWithPolicy(href, {
      signal: options.signal,
      policy: options.request,
      maxBytes: MAX_ENVIRONMENT_BYTES,
    });
    const whole = bytes.byteOffset === 0 && bytes.byteLength === bytes.buffer.byteLength;
    buffer = (whole ? bytes.buffer : bytes.slice().buffer) as ArrayBuffer;
  } catch (e) {
    // A size bound stays limit-exceeded; everything else is a failed load naming the URL.
    const code = e instanceof RequestError ? e.code : 'load-failed';
    throw new VptError(code, `environment: could not fetch ${href} (${(e as Error).message})`, { cause: e });
  }
  let d: DecodedEnvironment;
  const policyBound = options.request?.totalTimeoutMs;
  const timeoutMs = Math.min(ENVIRONMENT_DECODE_TIMEOUT_MS, policyBound ?? Infinity);
  try {
    d = await decode(href, buffer, timeoutMs);
  } catch (e) {
    if (e instanceof VptError) throw e; // the header checks' own, naming what is wrong
    throw new VptError(
      'load-failed',
      `environment: ${href} is not a readable .hdr/.exr image (${(e as Error).message})`,
      { cause: e },
    );
  }
  const channels = d.data.length / (d.width * d.height);
  if (!d.width || !d.height || !Number.isInteger(channels) || channels < 1)
    throw new VptError('load-failed', `environment: ${href} decoded to an unexpected layout`);
  const rgb = new Float32Array(d.width * d.height * 3);
  for (let row = 0; row < d.height; row++) {
    const srcRow = d.bottomUp ? d.height - 1 - row : row;
    for (let x = 0; x < d.width; x++) {
      const s = (srcRow * d.width + x) * channels;
      const o = (row * d.width + x) * 3;
      for (let c = 0; c < 3; c++) {
        const v = d.data[s + Math.min(c, channels - 1)];
        rgb[o + c] = Number.isFinite(v) && v > 0 ? v : 0;
      }
    }
  }
  return { type: 'latlong', width: d.width, height: d.height, data: rgb, scale };
}
