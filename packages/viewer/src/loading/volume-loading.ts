/**
 * Loading the element's `src` (or a `load()` source): one volume, or a multiscale store
 * level by level up to the finest that fits the context's budget, then level 0 streamed as
 * bricks when it does not fit (multiscale.ts); the loading status, bar and `vpt-progress`
 * events on the way; and the context's warnings about a streamed volume's bricks. Each
 * load has a generation token, so a load that lands after `src` moved on is dropped. The
 * element is reached through a small host (VolumeLoadingHost); the methods read it under
 * the element's own names, so they read as they did in viewer-element.ts.
 */
import type { MultiscaleSource, RenderWarning, RequestPolicy } from '@vpt/core';
import type { RenderSession } from '../session.js';
import type { ViewerLoadDetail, ViewerProgressDetail } from './load-events.js';
import { finestFittingLevel, isProgressiveSource, refinementPlan, sourceAtLevel, type Dims } from './multiscale.js';
import type { LoadedVolumeLike, VolumeSource } from './types.js';
import { loadVolumeSource, openMultiscaleSource } from './volume-source.js';

const BYTES_PER_VOXEL: Record<string, number> = { uint8: 1, uint16: 2, int16: 2, float32: 4 };

/** A multiscale volume's levels: shown, how many, the one that fits the budget, the one loading (null: none). */
export interface DataLevel {
  shown: number;
  count: number;
  target: number;
  loading: number | null;
  bricked?: boolean;
}

/** What loading reads and writes of the element. */
export interface VolumeLoadingHost {
  /** The open render session, if any. */
  session(): RenderSession | null;
  /** The context being opened, if one is (its budget and limits decide the levels). */
  opening(): Promise<void> | null;
  /** The volume on display. */
  volume(): LoadedVolumeLike | null;
  /** The status line. */
  setStatus(status: string): void;
  /** The loading bar's fraction (null: not loading; NaN: size unknown). */
  setLoading(loading: number | null): void;
  /** The levels of the multiscale volume being shown (null: none). */
  dataLevel(): DataLevel | null;
  setDataLevel(level: DataLevel | null): void;
  /** Show a loaded volume (`level` for the levels of a multiscale store). */
  applyVolume(volume: LoadedVolumeLike, source: VolumeSource, level: ViewerLoadDetail['level'] | null): void;
  /** Report a load failure (`vpt-error`, source 'src'). */
  fail(error: unknown): void;
  dispatchEvent(event: Event): boolean;
  requestUpdate(): void;
  /** Bounds on every fetch of a load (core's RequestPolicy overrides). */
  requestPolicy(): Partial<RequestPolicy>;
}

export class VolumeLoading {
  /**
   * A level 0 streamed as bricks: the stand-in volume the scene holds and its source
   * (registered on every new context); `draw`, for a store's channels: the channels a scene
   * about to be set draws (the source reads only those, StreamedChannels); `pane`: the panes'.
   */
  streamed: {
    standIn: LoadedVolumeLike;
    source: MultiscaleSource;
    draw?: (channels: readonly number[]) => void;
    /** For a store's channels: what the slice panes stream, channel 0 under the element's scalar view. */
    pane?: { standIn: LoadedVolumeLike; source: MultiscaleSource };
  } | null = null;
  private brickFailureWarned = false;
  private tokens = { src: 0 };
  private srcAbort: AbortController | null = null;

  constructor(private readonly host: VolumeLoadingHost) {}

  /** Abandon the load under way (the element was removed). */
  abort(): void {
    this.srcAbort?.abort();
  }

  // The element's state under its own names (see the header).
  private get session(): RenderSession | null {
    return this.host.session();
  }
  private get opening(): Promise<void> | null {
    return this.host.opening();
  }
  private get volume(): LoadedVolumeLike | null {
    return this.host.volume();
  }
  private set _status(status: string) {
    this.host.setStatus(status);
  }
  private set _loading(loading: number | null) {
    this.host.setLoading(loading);
  }
  private get _dataLevel(): DataLevel | null {
    return this.host.dataLevel();
  }
  private set _dataLevel(level: DataLevel | null) {
    this.host.setDataLevel(level);
  }
  private applyVolume(volume: LoadedVolumeLike, source: VolumeSource, level: ViewerLoadDetail['level'] | null): void {
    this.host.applyVolume(volume, source, level);
  }
  private fail(e: unknown, _source: 'src'): void {
    this.host.fail(e);
  }
  private dispatchEvent(event: Event): boolean {
    return this.host.dispatchEvent(event);
  }
  private requestUpdate(): void {
    this.host.requestUpdate();
  }

  /** Load `source` (null or '': nothing), replacing any load under way. */
  async loadSource(source: VolumeSource | null): Promise<void> {
    const token = ++this.tokens.src;
    this.srcAbort?.abort();
    this._dataLevel = null;
    this.streamed = null;
    if (source === null || source === '') return;
    const abort = new AbortController();
    this.srcAbort = abort;
    if (isProgressiveSource(source)) return this.loadLevels(source, token, abort.signal);
    try {
      const volume = await this.loadOnce(source, token, abort.signal);
      if (token !== this.tokens.src) return;
      this.applyVolume(volume, source, null);
    } catch (e) {
      if (token !== this.tokens.src) return;
      this._status = '';
      this._loading = null;
      this.fail(e, 'src');
    }
  }

  /** One volume load with the loading status, bar and `vpt-progress` events. */
  private async loadOnce(source: VolumeSource, token: number, signal: AbortSignal): Promise<LoadedVolumeLike> {
    this._status = this._dataLevel ? `Refining data… level ${this._dataLevel.loading}` : 'Loading…';
    this._loading = NaN;
    const prefix = this._dataLevel ? `Refining data… level ${this._dataLevel.loading}: ` : 'Loading… ';
    const limits = this.session
      ? { maxTextureDimension3D: this.session.ctx.backend.limits.maxTextureDimension3D }
      : undefined;
    return loadVolumeSource(source, {
      signal,
      limits,
      request: this.host.requestPolicy(),
      onProgress: (p) => {
        if (token !== this.tokens.src) return;
        this._status = p.total
          ? `${prefix}${Math.round((100 * p.loaded) / p.total)}%`
          : `${prefix}${(p.loaded / 1048576).toFixed(1)} MB`;
        this._loading = p.total ? Math.min(1, p.loaded / p.total) : NaN;
        this.dispatchEvent(
          new CustomEvent<ViewerProgressDetail>('vpt-progress', { detail: { phase: 'loading', ...p } }),
        );
      },
    });
  }

  /**
   * A multiscale store (OME-Zarr without a level in its URL): the coarsest level first, then
   * finer ones up to the finest that fits the GPU memory budget (loading/multiscale.ts).
   * Each level replaces the volume; the camera stays. A finer level that fails to load
   * leaves the coarser one on screen and reports the error.
   */
  private async loadLevels(source: string, token: number, signal: AbortSignal): Promise<void> {
    let shown = false;
    try {
      const t0 = performance.now();
      const first = await this.loadOnce(sourceAtLevel(source, 'coarsest'), token, signal);
      if (token !== this.tokens.src) return;
      const zarr = first.meta?.zarr as { level: number; levels: { dims: Dims }[] } | undefined;
      const levels = zarr?.levels.map((l) => l.dims) ?? [first.dims];
      const ms = Math.max(1, performance.now() - t0);
      // The budget and the texture limit are the context's: wait for one that is opening.
      if (this.opening) await this.opening;
      if (token !== this.tokens.src) return;
      // A store's channels (channels.ts) count as the texture's components: it holds every drawn
      // one (at most MAX_ENABLED_CHANNELS), two as rg, three or four as rgba (planChannelUpload).
      const mc = first.multichannel?.volume.channels ?? 1;
      const components = mc === 1 ? 1 : mc === 2 ? 2 : 4;
      const perVoxel = BYTES_PER_VOXEL[first.type] * components;
      const target = finestFittingLevel(levels, perVoxel, this.volumeBudget(), this.max3D());
      const plan = refinementPlan(levels, target, (first.dims[0] * first.dims[1] * first.dims[2]) / ms);
      // Level 0 beyond the budget streams as bricks after the last level that fits (every channel's, see streamLevel0).
      const bricks = target > 0;
      this._dataLevel = { shown: levels.length - 1, count: levels.length, target, loading: plan[0] ?? null };
      this.applyVolume(first, source, this.levelDetail(levels.length - 1, levels, plan.length === 0 && !bricks));
      shown = true;
      for (const [i, level] of plan.entries()) {
        this._dataLevel = { ...this._dataLevel, loading: level };
        const volume = await this.loadOnce(sourceAtLevel(source, level), token, signal);
        if (token !== this.tokens.src) return;
        this._dataLevel = { ...this._dataLevel, shown: level, loading: plan[i + 1] ?? null };
        this.applyVolume(volume, source, this.levelDetail(level, levels, i === plan.length - 1 && !bricks));
      }
      if (bricks) await this.streamLevel0(source, token, levels);
    } catch (e) {
      if (token !== this.tokens.src) return;
      this._status = '';
      this._loading = null;
      if (shown && this._dataLevel) this._dataLevel = { ...this._dataLevel, loading: null };
      this.fail(e, 'src');
    }
  }

  /**
   * Level 0 of a store that does not fit the budget: the brick cache streams it from the
   * store's chunks (RenderContext.setVolumeSource), starting from the level on screen, which
   * becomes the stand-in (histogram, transfer function, renderer defaults). Bricks the view
   * needs load at level 0, nearest first; a chunk that fails warns once and its region keeps
   * the coarser level. Reads are not aborted by a new src: the cache drops them with the volume.
   */
  private async streamLevel0(source: string, token: number, levels: readonly Dims[]): Promise<void> {
    const shown = this.volume;
    if (!shown || !this._dataLevel) return;
    this._dataLevel = { ...this._dataLevel, loading: 0 };
    const request = this.host.requestPolicy();
    const mc = shown.multichannel;
    // A store's channels: channel 0's source first, the others opened when first drawn.
    const multiscale = await openMultiscaleSource(source, request, mc ? 0 : undefined);
    if (token !== this.tokens.src || this.volume !== shown) return;
    if (!multiscale) {
      this._dataLevel = { ...this._dataLevel, loading: null };
      return;
    }
    let standIn: LoadedVolumeLike, view: LoadedVolumeLike, streamedSource: MultiscaleSource;
    let draw: ((channels: readonly number[]) => void) | undefined;
    let pane: { standIn: LoadedVolumeLike; source: MultiscaleSource } | undefined;
    if (mc) {
      // The scene's volume (the multichannel one, sceneNow) is the stand-in, streamed from
      // every channel's source as one interleaved source; the element keeps channel 0's
      // scalar view (histogram, slice panes, probe), now carrying the stand-in's channels.
      const { StreamedChannels } = await import('../channels.js');
      if (token !== this.tokens.src || this.volume !== shown) return;
      const channels = new StreamedChannels(multiscale, mc.volume.channels ?? 1, async (k) => {
        const part = await openMultiscaleSource(source, request, k);
        if (!part) throw new Error(`${source}: channel ${k} could not be opened`);
        return part;
      });
      standIn = { ...mc.volume };
      view = { ...shown, multichannel: mc.over(standIn) };
      streamedSource = channels;
      draw = (ks) => channels.draw(ks);
      // The panes draw the scalar view: channel 0's source, without its own value range, so
      // they map values as the view does (core takes a source's range over its stand-in's).
      pane = {
        standIn: view,
        source: {
          type: multiscale.type,
          levels: multiscale.levels,
          readRegion: (l, min, max, signal) => multiscale.readRegion(l, min, max, signal),
          readLevel: (l, signal) => multiscale.readLevel(l, signal),
        },
      };
    } else {
      // A new object: the context fits it afresh, as bricks, instead of reusing the upload of `shown`.
      standIn = { ...shown };
      view = standIn;
      streamedSource = multiscale;
    }
    this.streamed = { standIn, source: streamedSource, ...(draw ? { draw } : {}), ...(pane ? { pane } : {}) };
    this.brickFailureWarned = false;
    this.session?.ctx.setVolumeSource(standIn, streamedSource);
    this._dataLevel = { ...this._dataLevel, shown: 0, loading: null, bricked: true };
    this.applyVolume(view, source, { ...this.levelDetail(0, levels, true)!, bricked: true });
  }

  /**
   * The context's warnings go to the console as before, except that a streamed volume's
   * failed bricks warn once: one bad chunk fails every brick whose apron reaches it, and the
   * stats line counts them.
   */
  onContextWarning(warning: RenderWarning): void {
    if (warning.code === 'brick-load-failed') {
      this.requestUpdate(); // the stats line's count of failed bricks
      if (this.brickFailureWarned) return;
      this.brickFailureWarned = true;
      console.warn(
        `vpt: ${warning.message} (its region keeps a coarser level; the stats line counts further failed bricks)`,
      );
      return;
    }
    console.warn(`vpt: ${warning.message}`);
  }

  private levelDetail(index: number, levels: readonly Dims[], final: boolean): ViewerLoadDetail['level'] {
    return { index, count: levels.length, dims: [...levels[index]] as Dims, final };
  }

  /**
   * Bytes a volume may take: the context's own budget (RenderContext.volumeBudgetBytes, the
   * rule its fit applies), so a level chosen here is not downsampled there; 1 GiB before a
   * context exists.
   */
  private volumeBudget(): number {
    return this.session?.ctx.volumeBudgetBytes ?? 1 << 30;
  }

  private max3D(): number {
    return this.session?.ctx.backend.limits.maxTextureDimension3D ?? 2048;
  }
}
