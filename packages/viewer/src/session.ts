/**
 * The GPU side of one <vpt-viewer>: a RenderContext plus what the element needs on top
 * of it — apply a scene only when it differs (so setting an attribute to its current
 * value keeps the accumulated samples), stop at max-samples or at a target error from
 * the live estimate, report progress once per batch, and surface context loss.
 */
import { RenderContext, type BackendPreference, type PostStep, type Renderer, type Scene } from '@vpt/core';
import { sameValue } from './attributes.js';

export interface RefinementStats {
  samples: number;
  msPerIteration: number;
  /** Relative RMSE from the half-accumulation estimate; null when the renderer keeps no halves (or too few samples). */
  error: number | null;
  width: number;
  height: number;
  /** The renderer's own choices for the scene (RenderContext.stats.renderer; MCRT: its estimator). */
  renderer: Record<string, string>;
}

export interface SessionCallbacks {
  progress(stats: RefinementStats): void;
  converged(stats: RefinementStats & { reason: 'max-samples' | 'target-error' }): void;
  lost(): void;
  restored(): void;
  /** A new error estimate landed (between progress reports): the stats with it. */
  estimated?(stats: RefinementStats): void;
}

/** How often (at most) the error estimate is read back; it costs a readback of two float images. */
const ERROR_ESTIMATE_INTERVAL_MS = 400;

export class RenderSession {
  private maxSamples = Infinity;
  private targetError = 0;
  private lastSamples = 0;
  private converged = false;
  private accumulation = 0; // bumped on every reset, so stale error estimates are dropped
  private error: number | null = null;
  private errorInFlight = false;
  private lastErrorAt = 0;
  private disposed = false;

  private constructor(
    readonly ctx: RenderContext,
    private readonly callbacks: SessionCallbacks,
  ) {
    ctx.onStats((s) => this.onStats(s.iterations, s.msPerIteration));
    ctx.backend.onLost(() => callbacks.lost());
    ctx.backend.onRestored(() => {
      this.markReset();
      this.rearm();
      callbacks.restored();
    });
  }

  static async create(
    opts: {
      canvas: HTMLCanvasElement;
      backend: BackendPreference;
      renderer: Renderer;
      post: PostStep[];
      width: number;
      height: number;
    },
    callbacks: SessionCallbacks,
  ): Promise<RenderSession> {
    const ctx = await RenderContext.create(opts);
    return new RenderSession(ctx, callbacks);
  }

  get samples(): number {
    return this.ctx.stats.iterations;
  }
  get isConverged(): boolean {
    return this.converged;
  }
  get lastError(): number | null {
    return this.error;
  }

  /**
   * Apply a scene; returns whether the image changes (and accumulation restarted).
   * Throws VptError for an invalid scene, keeping the previous one.
   */
  applyScene(scene: Scene): boolean {
    const current = this.ctx.getScene();
    if (current && sameScene(current, scene)) return false;
    this.ctx.setScene(scene);
    this.markReset();
    this.rearm();
    return true;
  }

  setRenderer(renderer: Renderer): void {
    this.ctx.setRenderer(renderer);
    this.markReset();
    this.rearm();
  }

  /** Renderer parameters changed in place (BaseRenderer.setParams): the context resets on the new version. */
  rendererParamsChanged(): void {
    this.markReset();
    this.rearm();
  }

  /** Post-processing does not touch the accumulation: the next frame re-runs only the post chain. */
  setPost(steps: PostStep[]): void {
    this.ctx.setPost(steps);
  }

  setSize(width: number, height: number): boolean {
    const { width: w, height: h } = this.ctx.size;
    if (w === width && h === height) return false;
    this.ctx.setSize(width, height);
    this.markReset();
    this.rearm();
    return true;
  }

  /** New stopping rule; raising max-samples resumes refinement, lowering it below the count converges. */
  setStopping(maxSamples: number, targetError: number): void {
    const changed = maxSamples !== this.maxSamples || targetError !== this.targetError;
    this.maxSamples = maxSamples;
    this.targetError = targetError;
    if (!changed) return;
    if (
      this.converged &&
      this.samples < maxSamples &&
      !(targetError > 0 && this.error !== null && this.error <= targetError)
    )
      this.converged = false;
    this.rearm();
    if (!this.converged && this.ctx.getScene() && this.samples >= maxSamples) this.finish('max-samples');
  }

  dispose(): void {
    this.disposed = true;
    this.ctx.dispose();
  }

  private rearm(): void {
    if (this.disposed || !this.ctx.getScene()) return;
    this.ctx.start({ maxIterations: Number.isFinite(this.maxSamples) ? this.maxSamples : undefined });
  }

  private markReset(): void {
    this.accumulation++;
    this.converged = false;
    this.error = null;
    this.lastSamples = 0;
    this.lastErrorAt = performance.now();
  }

  private stats(samples = this.samples, ms = this.ctx.stats.msPerIteration): RefinementStats {
    const { width, height } = this.ctx.size;
    return { samples, msPerIteration: ms, error: this.error, width, height, renderer: this.ctx.stats.renderer };
  }

  private onStats(samples: number, ms: number): void {
    if (this.disposed) return;
    if (samples < this.lastSamples) this.markReset(); // reset by the context itself (renderer version, restore)
    this.lastSamples = samples;
    this.callbacks.progress(this.stats(samples, ms));
    if (!this.converged && samples >= this.maxSamples) this.finish('max-samples');
    else this.maybeEstimateError();
  }

  private finish(reason: 'max-samples' | 'target-error'): void {
    this.converged = true;
    this.callbacks.converged({ ...this.stats(), reason });
  }

  private maybeEstimateError(): void {
    const now = performance.now();
    if (this.errorInFlight || this.converged || !this.ctx.renderer.halfAccumulations || this.samples < 2) return;
    if (now - this.lastErrorAt < ERROR_ESTIMATE_INTERVAL_MS) return;
    this.errorInFlight = true;
    this.lastErrorAt = now;
    const accumulation = this.accumulation;
    this.ctx
      .estimateError()
      .then((e) => {
        if (this.disposed || accumulation !== this.accumulation || !e) return;
        this.error = e.relativeRmse;
        this.callbacks.estimated?.(this.stats());
        if (this.targetError > 0 && e.relativeRmse <= this.targetError && !this.converged) {
          // Hold the accumulation where it is: the loop keeps presenting but adds no samples.
          this.ctx.start({ maxIterations: this.samples });
          this.finish('target-error');
        }
      })
      .catch(() => {
        // Targets can be replaced mid-read (resize, loss); the next estimate will do.
      })
      .finally(() => {
        this.errorInFlight = false;
      });
  }
}

/** Same image: same volume (and label volume) object, and equal transfer function, camera, lights, environment, clip, slice plane, channels, label table, density and seed. */
export function sameScene(a: Scene, b: Scene): boolean {
  return (
    a.volume === b.volume &&
    a.densityScale === b.densityScale &&
    a.seed === b.seed &&
    sameValue(a.transferFunction, b.transferFunction) &&
    sameValue(a.camera, b.camera) &&
    sameValue(a.lights, b.lights) &&
    sameValue(a.environment, b.environment) &&
    sameValue(a.clip ?? null, b.clip ?? null) &&
    sameValue(a.slicePlane ?? null, b.slicePlane ?? null) &&
    sameValue(a.channels ?? null, b.channels ?? null) &&
    a.labels?.volume === b.labels?.volume &&
    sameValue(a.labels?.table ?? null, b.labels?.table ?? null)
  );
}
