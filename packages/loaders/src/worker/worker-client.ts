import { LoaderError } from '../errors.js';
import type { LoadedVolume, LoadOptions, VolumeSource } from '../types.js';
import type { LoadRequest, WorkerMessage, WorkerOptions } from './protocol.js';

/** Thrown (internally) when the worker cannot start; the caller then loads in-thread. */
export class WorkerUnavailable extends Error {}

/** How long a started worker may take to say it is ready before the load falls back in-thread. */
const READY_TIMEOUT_MS = 20_000;

export function workersAvailable(): boolean {
  return typeof Worker === 'function' && typeof URL === 'function';
}

/** Make the source cloneable and independent of the caller's base URL. */
function portable(source: VolumeSource): VolumeSource {
  if (typeof source === 'string') {
    const base =
      (globalThis as { document?: { baseURI: string }; location?: { href: string } }).document?.baseURI ??
      (globalThis as { location?: { href: string } }).location?.href;
    try {
      return new URL(source, base).href;
    } catch {
      return source;
    }
  }
  if (source instanceof URL) return source.href;
  if (ArrayBuffer.isView(source)) {
    // Copy only the viewed bytes (the caller's buffer stays usable: it is cloned, not transferred).
    return source.buffer.slice(source.byteOffset, source.byteOffset + source.byteLength) as ArrayBuffer;
  }
  return source;
}

/**
 * Load in a fresh module worker (one per load, terminated afterwards, so a huge or hostile
 * file cannot leave memory behind and an abort stops the parse at once).
 */
export function loadInWorker(source: VolumeSource, options: LoadOptions): Promise<LoadedVolume> {
  return new Promise<LoadedVolume>((resolve, reject) => {
    let worker: Worker;
    try {
      worker = new Worker(new URL('./loader-worker.js', import.meta.url), { type: 'module', name: 'vpt-loader' });
    } catch (e) {
      reject(new WorkerUnavailable(String(e)));
      return;
    }
    let ready = false;
    let settled = false;
    const finish = (f: () => void) => {
      if (settled) return;
      settled = true;
      clearTimeout(readyTimer);
      options.signal?.removeEventListener('abort', onAbort);
      worker.terminate();
      f();
    };
    const readyTimer = setTimeout(
      () => finish(() => reject(new WorkerUnavailable('the loader worker did not start in time'))),
      READY_TIMEOUT_MS,
    );
    const onAbort = () =>
      finish(() => reject(new LoaderError('aborted', 'Loading was aborted', { cause: options.signal?.reason })));
    options.signal?.addEventListener('abort', onAbort, { once: true });

    worker.onmessage = (event: MessageEvent<WorkerMessage>) => {
      const m = event.data;
      if (m.type === 'ready') {
        ready = true;
        clearTimeout(readyTimer);
        const { signal: _s, onProgress, worker: _w, ...rest } = options;
        const request: LoadRequest = {
          type: 'load',
          source: portable(source),
          options: { ...rest, progress: !!onProgress } as WorkerOptions,
        };
        try {
          worker.postMessage(request);
        } catch (e) {
          finish(() =>
            reject(new WorkerUnavailable(`the source cannot be sent to a worker (${(e as Error).message})`)),
          );
        }
      } else if (m.type === 'progress') {
        try {
          options.onProgress?.(m.progress);
        } catch {
          /* a throwing callback must not break the load */
        }
      } else if (m.type === 'result') {
        finish(() => resolve(m.volume));
      } else if (m.type === 'error') {
        finish(() => reject(new LoaderError(m.reason, m.message)));
      }
    };
    worker.onerror = (event: ErrorEvent) => {
      event.preventDefault?.();
      if (!ready) finish(() => reject(new WorkerUnavailable(event.message || 'the loader worker failed to start')));
      else
        finish(() =>
          reject(
            new LoaderError(
              'invalid-data',
              `The loader worker crashed (${event.message || 'no message'}); the file may be too large for memory`,
            ),
          ),
        );
    };
    worker.onmessageerror = () =>
      finish(() => reject(new LoaderError('invalid-data', 'The loader worker sent a message that could not be read')));
  });
}
