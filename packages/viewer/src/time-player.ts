/**
 * The element's time series player, loaded on first use (a lazy chunk of the one-file
 * bundle): the steps of the volume on display (a 4D NIfTI `src`, an OME-Zarr `src` with a
 * `t` axis), held in @vpt/loaders' TimeSeriesCache (every time series source needs that
 * package), which reads the next steps ahead within a byte budget, and playback at `fps` steps per second. A step
 * is shown only once it is read: playback waits for a step that is not yet in memory
 * rather than skip it, so every step is seen.
 */
import type { RequestPolicy, TimeSeriesSource } from '@vpt/core';
import type { LoadedVolumeLike, VolumeSource } from './loading/types.js';
import { sourceAtLevel } from './loading/multiscale.js';
import { loadVolumeSource } from './loading/volume-source.js';

/** The part of @vpt/loaders' TimeSeriesCache the player uses (restated: the package is optional to the viewer). */
interface StepCache {
  get(index: number): Promise<LoadedVolumeLike>;
  dispose(): void;
}
type CacheClass = new (source: TimeSeriesSource<LoadedVolumeLike>, options: { budgetBytes: number }) => StepCache;

/** What the player reads and calls of the element. */
export interface TimePlayerHost {
  /** The step asked for (the `time` property). */
  readonly time: number;
  readonly playing: boolean;
  /** Steps per second while playing. */
  readonly fps: number;
  /** Bounds on every request of a load. */
  readonly requestPolicy: Partial<RequestPolicy>;
  /** A viewer taken off the page stops playing. */
  readonly isConnected: boolean;
  /** Show step `index`'s volume (the scene's volume is swapped; accumulation restarts), or report its failure. */
  showStep(volume: LoadedVolumeLike | null, index: number, error?: unknown): void;
}

/**
 * The player for a volume just shown that is step 0 of `steps` (its `meta.timeSteps`): the
 * other steps are read from the same source with `time` (loaders' LoadOptions.time).
 */
export async function attachPlayer(
  host: TimePlayerHost,
  first: LoadedVolumeLike,
  source: VolumeSource,
  steps: number,
  budgetBytes: number,
  level?: number,
): Promise<TimePlayer> {
  // @ts-ignore -- optional package, may be absent when this is type-checked
  const { TimeSeriesCache } = (await import('@vpt/loaders')) as { TimeSeriesCache: CacheClass };
  // A multiscale store's steps are read at the level on display.
  const at = level === undefined ? source : sourceAtLevel(String(source), level);
  let firstTaken = false;
  const series: TimeSeriesSource<LoadedVolumeLike> = {
    steps,
    loadStep(i, signal) {
      if (i === 0 && !firstTaken) {
        firstTaken = true;
        return Promise.resolve(first);
      }
      return loadVolumeSource(at, { time: i, request: host.requestPolicy, ...(signal ? { signal } : {}) });
    },
  };
  return new TimePlayer(host, new TimeSeriesCache(series, { budgetBytes }), steps, 0);
}

export class TimePlayer {
  private shown: number;
  private wanted = -1;
  private timer: ReturnType<typeof setTimeout> | null = null;
  private lastStepAt = 0;
  private disposed = false;

  constructor(
    private readonly host: TimePlayerHost,
    readonly cache: StepCache,
    readonly steps: number,
    shownIndex: number,
  ) {
    this.shown = shownIndex;
  }

  /** The step on display (−1 before the first). */
  get shownStep(): number {
    return this.shown;
  }

  /** Follow the host's `time`, `playing` and `fps`. */
  update(): void {
    if (this.disposed) return;
    const t = Math.min(this.steps - 1, Math.max(0, Math.trunc(this.host.time || 0)));
    if (t !== this.wanted) void this.show(t);
    if (this.host.playing && this.steps > 1) this.schedule();
    else this.stopTimer();
  }

  dispose(): void {
    this.disposed = true;
    this.stopTimer();
    this.cache.dispose();
  }

  private async show(index: number): Promise<void> {
    this.wanted = index;
    try {
      const volume = await this.cache.get(index);
      if (this.disposed || this.wanted !== index) return;
      if (index !== this.shown) {
        this.shown = index;
        this.host.showStep(volume, index);
      }
      this.lastStepAt = performance.now();
      if (this.host.playing) this.schedule();
    } catch (e) {
      if (!this.disposed && this.wanted === index) this.host.showStep(null, index, e);
    }
  }

  /** The next step is due 1/fps after the last one was shown, and only once it is on display. */
  private schedule(): void {
    if (this.timer !== null || this.shown !== this.wanted) return;
    const fps = this.host.fps > 0 && Number.isFinite(this.host.fps) ? this.host.fps : 10;
    const wait = Math.max(0, this.lastStepAt + 1000 / fps - performance.now());
    this.timer = setTimeout(() => {
      this.timer = null;
      if (this.disposed || !this.host.playing || !this.host.isConnected) return;
      void this.show((this.shown + 1) % this.steps);
    }, wait);
  }

  private stopTimer(): void {
    if (this.timer !== null) clearTimeout(this.timer);
    this.timer = null;
  }
}
