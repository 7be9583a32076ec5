/// <reference lib="webworker" />
/**
 * The loader's Web Worker: receives one load request, posts progress, and answers with the
 * volume (its voxel buffer transferred, not copied) or the error's reason and message.
 * Built as a self-contained bundle (dist/worker/) because workers get no import map.
 */
import { toLoaderError } from '../errors.js';
import { loadInThread, describeSource } from '../load-in-thread.js';
import type { LoadRequest, WorkerMessage } from './protocol.js';

const scope = self as unknown as DedicatedWorkerGlobalScope;
const post = (m: WorkerMessage, transfer: Transferable[] = []) => scope.postMessage(m, transfer);

scope.onmessage = async (event: MessageEvent<LoadRequest>) => {
  const { source, options } = event.data;
  try {
    const volume = await loadInThread(source, {
      ...options,
      worker: false,
      onProgress: options.progress ? (progress) => post({ type: 'progress', progress }) : undefined,
    });
    post({ type: 'result', volume }, [volume.data.buffer as ArrayBuffer]);
  } catch (e) {
    const err = toLoaderError(e, describeSource(source));
    post({ type: 'error', reason: err.reason, message: err.message });
  }
};

post({ type: 'ready' });
