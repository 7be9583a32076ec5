import { LoaderError } from './errors.js';
import type { LoadedVolume, LoadOptions, VolumeSource } from './types.js';
import { loadInThread } from './load-in-thread.js';
import { loadInWorker, workersAvailable, WorkerUnavailable } from './worker/worker-client.js';

/**
 * Load a volume from a URL, a File or Blob, bytes, or a set of files (a DICOM series, a
 * sidecar and its raw file). In browsers the parse runs in a Web Worker (options.worker,
 * default true); where there are no workers (Node), or the worker cannot start, it runs in
 * the calling thread. Every failure is a LoaderError with a `reason`.
 */
export async function loadVolume(source: VolumeSource, options: LoadOptions = {}): Promise<LoadedVolume> {
  if (options.signal?.aborted)
    throw new LoaderError('aborted', 'Loading was aborted before it started', { cause: options.signal.reason });
  const useWorker = options.worker ?? true;
  if (useWorker && workersAvailable()) {
    try {
      const volume = await loadInWorker(source, options);
      (volume.meta ??= {}).loadedIn = 'worker';
      return volume;
    } catch (e) {
      if (!(e instanceof WorkerUnavailable)) throw e;
      // No worker here (a strict CSP, an old browser, a bundler that dropped the file): parse in-thread.
    }
  }
  const volume = await loadInThread(source, options);
  // Set in place, not spread: a spread would read meta.dataRange's getter (a scan of every voxel).
  (volume.meta ??= {}).loadedIn = 'main';
  return volume;
}
