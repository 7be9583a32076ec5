/**
 * The render size of a <vpt-viewer>, as a Lit ReactiveController: the element's CSS size
 * (a ResizeObserver on the view) × devicePixelRatio (followed through a media query) ×
 * `resolution-scale`, shrunk while the camera moves so one iteration fits a 60 Hz frame,
 * and back to full size a moment after the movement stops. The host is told through
 * `onSizeChange` whenever the size it should render at may have changed.
 */
import type { ReactiveController, ReactiveControllerHost } from 'lit';

/** Interaction should leave time for at least one iteration per 60 Hz frame. */
export const INTERACTION_BUDGET_MS = 14;
/**
 * While moving, a side shrunk by less than this factor stays at full size: a nearest upscale from
 * a few pixels short misplaces every pixel by up to half of one, an error far above what the time
 * saved buys (EAM on the bundled head at 64², 57 px against 64: 2.1x the RMSE of plain resets as
 * shown; docs/benchmarks.md, "Orbit: the history continues the sample sequence"). A frame then
 * takes at most 1 / 0.8² ≈ 1.6x the budget.
 */
export const MIN_SHRINK = 0.8;
/** Full resolution returns this long after the last camera movement. */
export const SETTLE_MS = 180;

export interface AdaptiveResolutionHost extends ReactiveControllerHost {
  /** Render resolution relative to the element's device pixels. */
  readonly resolutionScale: number;
}

export class AdaptiveResolution implements ReactiveController {
  private cssSize = { width: 0, height: 0 };
  private interactingNow = false;
  private settleTimer: ReturnType<typeof setTimeout> | null = null;
  private resizeObserver: ResizeObserver | null = null;
  private observed: HTMLElement | null = null;
  private dprQuery: MediaQueryList | null = null;
  /** Milliseconds per iteration at full size, from the last progress report outside an interaction. */
  private fullResMs = 0;

  constructor(
    private readonly host: AdaptiveResolutionHost,
    private readonly onSizeChange: () => void,
  ) {
    host.addController(this);
  }

  /** Whether the camera is moving (the image is rendered smaller). */
  get interacting(): boolean {
    return this.interactingNow;
  }
  /** The observed element's CSS size in pixels. */
  get size(): { width: number; height: number } {
    return { ...this.cssSize };
  }

  hostConnected(): void {
    this.watchDevicePixelRatio();
    if (this.observed) this.observeNow(this.observed);
  }

  hostDisconnected(): void {
    this.resizeObserver?.disconnect();
    this.dprQuery?.removeEventListener('change', this.onDprChange);
    this.dprQuery = null;
    if (this.settleTimer) clearTimeout(this.settleTimer);
    this.settleTimer = null;
    this.interactingNow = false;
  }

  /** Follow this element's size (the view box the canvas fills). */
  observe(view: HTMLElement): void {
    this.observed = view;
    this.resizeObserver ??= new ResizeObserver((entries) => {
      const r = entries[0].contentRect;
      this.cssSize = { width: r.width, height: r.height };
      this.onSizeChange();
    });
    this.observeNow(view);
    const r = view.getBoundingClientRect();
    this.cssSize = { width: r.width, height: r.height };
  }

  private observeNow(view: HTMLElement): void {
    try {
      // The device-pixel box changes with the DPR too (zoom, moving to another screen): a callback then.
      this.resizeObserver?.observe(view, { box: 'device-pixel-content-box' });
    } catch {
      this.resizeObserver?.observe(view);
    }
  }

  /**
   * Device-pixel size to render at: CSS size × DPR × resolution-scale (× the interaction
   * factor while moving), each side in [1, maxDim], and at most `maxPixels` pixels in all
   * (the GPU memory budget's, RenderContext.maxRenderPixels), shrunk with its aspect kept.
   */
  renderSize(maxDim: number, maxPixels = Infinity): { width: number; height: number } {
    const dpr = globalThis.devicePixelRatio || 1;
    const base = { width: this.cssSize.width * dpr, height: this.cssSize.height * dpr };
    const scale = this.host.resolutionScale;
    let k = Number.isFinite(scale) ? scale : 1;
    if (this.interactingNow) k *= this.interactionFactor();
    const w = Math.max(1, (base.width || 1) * k);
    const h = Math.max(1, (base.height || 1) * k);
    const side = (px: number, s: number) => Math.max(1, Math.min(maxDim, Math.floor(px * s)));
    let s = 1;
    if (Math.round(w) * Math.round(h) > maxPixels) s = Math.sqrt(maxPixels / (w * h));
    if (s === 1) {
      const fit = (px: number) => Math.max(1, Math.min(maxDim, Math.round(px)));
      return { width: fit(w), height: fit(h) };
    }
    return { width: side(w, s), height: side(h, s) };
  }

  /** A progress report: the cost of a frame of one iteration while moving (the element's sum), learned at full size only. */
  recordIteration(msPerIteration: number): void {
    if (!this.interactingNow) this.fullResMs = msPerIteration;
  }

  /** The camera moved: render smaller until `interactionEnded()` plus the settle time. */
  interactionStarted(): void {
    if (this.settleTimer) clearTimeout(this.settleTimer);
    this.settleTimer = null;
    if (this.interactingNow) return;
    this.interactingNow = true;
    this.onSizeChange();
  }

  interactionEnded(): void {
    if (!this.interactingNow) return;
    if (this.settleTimer) clearTimeout(this.settleTimer);
    this.settleTimer = setTimeout(() => {
      this.settleTimer = null;
      this.interactingNow = false;
      this.onSizeChange();
    }, SETTLE_MS);
  }

  /**
   * While the camera moves, shrink the image so one iteration fits the frame budget:
   * the cost scales with the pixel count, so the side scales with the square root; a shrink
   * smaller than MIN_SHRINK is not made.
   */
  private interactionFactor(): number {
    const ms = this.fullResMs;
    if (!(ms > 0)) return 0.5;
    const factor = Math.min(1, Math.max(0.25, Math.sqrt(INTERACTION_BUDGET_MS / ms)));
    return factor > MIN_SHRINK ? 1 : factor;
  }

  private watchDevicePixelRatio(): void {
    this.dprQuery?.removeEventListener('change', this.onDprChange);
    if (typeof matchMedia !== 'function') return;
    this.dprQuery = matchMedia(`(resolution: ${globalThis.devicePixelRatio || 1}dppx)`);
    this.dprQuery.addEventListener('change', this.onDprChange);
  }

  private readonly onDprChange = (): void => {
    this.watchDevicePixelRatio();
    this.onSizeChange();
  };
}
