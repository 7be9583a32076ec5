import type { LoaderErrorReason } from '../errors.js';
import type { LoadedVolume, LoadOptions, LoadProgress, VolumeSource } from '../types.js';

/** Options that cross the worker boundary (the signal and the callback stay on the caller's side). */
export type WorkerOptions = Omit<LoadOptions, 'signal' | 'onProgress' | 'worker'> & { progress: boolean };

export interface LoadRequest {
  type: 'load';
  source: VolumeSource;
  options: WorkerOptions;
}

export type WorkerMessage =
  | { type: 'ready' }
  | { type: 'progress'; progress: LoadProgress }
  | { type: 'result'; volume: LoadedVolume }
  | { type: 'error'; reason: LoaderErrorReason; message: string };
