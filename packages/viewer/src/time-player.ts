/**
 * The element's time series player, loaded on first use (a lazy chunk of the one-file
 * bundle): the steps of the volume on display (a 4D NIfTI `src`, an OME-Zarr `src` with a
 * `t` axis), held in @vpt/loaders' TimeSeriesCache (every time series source needs that
 * package), which reads the next steps ahead within a byte budget, and playback at `fps` steps per second. A step
 * is shown only once it is read: playback waits for a step that is not yet in memory
 * rather than skip it, so every step is seen. The player also draws the time toolbar (play/pause,
 * a step slider, the step readout), so a page without a time series carries none of it.
 */
import { html } from 'lit';
import type { TemplateResult } from 'lit';
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
  /** The step asked for (the `time` property; the toolbar's slider sets it). */
  time: number;
  /** The toolbar's button toggles it. */
  playing: boolean;
  /** Steps per second while playing. */
  readonly fps: number;
  /** Bounds on every request of a load. */
  readonly requestPolicy: Partial<RequestPolicy>;
  /** A viewer taken off the page stops playing. */
  readonly isConnected: boolean;
  /** Show step `index`'s volume (the scene's volume is swapped; accumulation restarts), or report its failure. */
  showStep(volume: LoadedVolumeLike | null, index: number, error?: unknown): void;
  /** Render again: the first update() draws the time toolbar. */
  requestUpdate(): void;
}

/**
 * The player for a volume just shown that is step 0 of its `meta.timeSteps` steps: the
 * other steps are read from the same source with `time` (loaders' LoadOptions.time); or,
 * where `src` (the attribute) lists several URLs separated by whitespace, the first `source`,
 * the series is that list and step i is file i read alone. Null: no series (one volume).
 */
export async function attachPlayer(
  host: TimePlayerHost,
  first: LoadedVolumeLike,
  source: VolumeSource,
  /** The context's volumeBudgetBytes; 1 GiB before a context exists. */
  budgetBytes = 1 << 30,
  level?: number,
  src?: string | null,
): Promise<TimePlayer | null> {
  const names = src?.trim().split(/\s+/);
  const list = names && names.length > 1 && names[0] === source ? names : undefined;
  const steps = list?.length ?? Number(first.meta?.timeSteps ?? 1);
  if (!(steps > 1)) return null;
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
      const options = { request: host.requestPolicy, ...(signal ? { signal } : {}) };
      return list ? loadVolumeSource(list[i], options) : loadVolumeSource(at, { ...options, time: i });
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
  private drawn = false;

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

  /** Follow the host's `time`, `playing` and `fps`; the first call also draws the toolbar (the host holds the player now). */
  update(): void {
    if (this.disposed) return;
    if (!this.drawn) this.host.requestUpdate();
    this.drawn = true;
    const t = Math.min(this.steps - 1, Math.max(0, Math.trunc(this.host.time || 0)));
    if (t !== this.wanted) void this.show(t);
    if (this.host.playing && this.steps > 1) this.schedule();
    else this.stopTimer();
  }

  /**
   * The time toolbar (top left of the view): play/pause, a slider over the steps and
   * "step / steps" (1-based; the `time` attribute is 0-based). Styled inline: the entry's
   * stylesheet stays as it is for pages without a series. Not `shown` (the element's panel
   * count: `panels="none"`): nothing, as for the element's other toolbar.
   */
  bar(shown: number): TemplateResult | undefined {
    if (!shown) return undefined;
    const h = this.host;
    const t = Math.min(this.steps - 1, Math.max(0, Math.trunc(h.time || 0)));
    return html`<div
      class="timebar"
      part="timebar"
      style="position:absolute;top:6px;left:6px;z-index:3;display:flex;gap:6px;align-items:center;max-width:60%;font-size:12px;color:#fff;text-shadow:0 0 2px #000"
    >
      <button
        type="button"
        part="time-play"
        aria-pressed=${h.playing ? 'true' : 'false'}
        title=${h.playing ? 'Pause the time series' : 'Play the time series'}
        @click=${() => {
          h.playing = !h.playing;
        }}
      >
        ${h.playing ? 'Pause' : 'Play'}
      </button>
      <input
        type="range"
        part="time-slider"
        aria-label="Time step"
        min="0"
        max=${this.steps - 1}
        step="1"
        .value=${String(t)}
        @input=${(e: Event) => {
          h.time = Number((e.target as HTMLInputElement).value);
        }}
      />
      <span part="time-readout">${t + 1} / ${this.steps}</span>
    </div>`;
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
