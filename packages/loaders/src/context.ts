import type { RequestPolicy } from '@vpt/core';
import { throwIfAborted } from './errors.js';
import { DEFAULT_LIMITS, type LoadLimits, type LoadOptions, type LoadProgress } from './types.js';

/** What every stage of one load shares: the caller's signal, throttled progress, the limits. */
export interface LoadContext {
  /** A name for messages: the file name or URL, or "the data". */
  name: string;
  signal?: AbortSignal;
  limits: Required<LoadLimits>;
  /** The caller's request-policy overrides, for every URL this load fetches. */
  request: Partial<RequestPolicy>;
  downsample: boolean;
  progress(stage: LoadProgress['stage'], loaded: number, total?: number): void;
  checkAborted(): void;
  /** A label volume (LoadOptions.labels): ids kept, downsampled by picking, never averaged. */
  labels: boolean;
  /** The time step to read (LoadOptions.time; 0 by default). */
  time: number;
  /** Human-readable notes collected along the way (meta.warnings). */
  warnings: string[];
  /**
   * The caller's own memory, when it passed bytes: voxels read from it are copied. Bytes the
   * loader read or inflated itself may become the volume's data as they are (a typed-array view).
   */
  borrowed?: ArrayBufferLike;
}

export function createContext(name: string, options: LoadOptions): LoadContext {
  const limits = { ...DEFAULT_LIMITS, ...definedOnly(options.limits ?? {}) };
  let lastStage = '';
  let lastLoaded = 0;
  const ctx: LoadContext = {
    name,
    signal: options.signal,
    limits,
    request: options.request ?? {},
    downsample: options.downsample === true,
    time: options.time ?? 0,
    labels: options.labels === true,
    warnings: [],
    // At most ~100 events per stage: a 64 KiB network chunk or a decoded slab would
    // otherwise flood a worker's message channel for a large file.
    progress(stage, loaded, total) {
      if (!options.onProgress) return;
      const step = total !== undefined && total > 0 ? total / 100 : 1 << 20;
      const final = total !== undefined && loaded >= total;
      if (stage === lastStage && !final && loaded - lastLoaded < step && loaded !== 0) return;
      lastStage = stage;
      lastLoaded = loaded;
      try {
        options.onProgress(total === undefined ? { stage, loaded } : { stage, loaded, total });
      } catch {
        // A throwing progress callback must not turn a good file into a failed load.
      }
    },
    checkAborted() {
      throwIfAborted(options.signal, name);
    },
  };
  return ctx;
}

function definedOnly<T extends object>(o: T): Partial<T> {
  return Object.fromEntries(Object.entries(o).filter(([, v]) => v !== undefined)) as Partial<T>;
}
