/**
 * The progressive loop: each animation frame runs as many iterations as fit in a time
 * budget, then presents. The rate is learned from GPU-synchronised batches, because
 * submitting work is nearly free and says nothing about how long it takes to run.
 */
export interface ProgressiveLoopHooks {
  /** Work before a frame's iterations that may wait without blocking (compiling a new variant). */
  ready?(): Promise<void>;
  step(iterations: number): void;
  finishFrame(): void;
  sync(): Promise<void>;
  onStats(msPerIteration: number): void;
  /** Work for a converged frame (a bricked volume's arrived bricks); a reset it causes resumes the iterations. */
  idle?(): void;
}

export interface LoopOptions {
  frameBudgetMs?: number;
  maxIterations?: number;
  currentIterations?: () => number;
}

const raf: (cb: () => void) => unknown =
  typeof requestAnimationFrame === 'function' ? (cb) => requestAnimationFrame(cb) : (cb) => setTimeout(cb, 16);

export class ProgressiveLoop {
  private active = false;
  private paused = false;
  private scheduled = false;
  private msPerIteration = 0;
  private options: LoopOptions = {};

  constructor(private readonly hooks: ProgressiveLoopHooks) {}

  get running(): boolean {
    return this.active && !this.paused;
  }
  /** The iteration count the running loop stops at (Infinity when unlimited). */
  get maxIterations(): number {
    return this.options.maxIterations ?? Infinity;
  }

  start(options: LoopOptions = {}): void {
    this.options = options;
    this.active = true;
    this.schedule();
  }

  stop(): void {
    this.active = false;
  }
  pause(): void {
    this.paused = true;
  }
  resume(): void {
    this.paused = false;
    this.schedule();
  }

  private schedule(): void {
    if (!this.active || this.paused || this.scheduled) return;
    this.scheduled = true;
    raf(() => {
      this.scheduled = false;
      void this.tick();
    });
  }

  private async tick(): Promise<void> {
    if (!this.active || this.paused) return;
    const budget = this.options.frameBudgetMs ?? 12;
    const done = this.options.currentIterations?.() ?? 0;
    const remaining = (this.options.maxIterations ?? Infinity) - done;
    if (remaining <= 0) {
      // Converged: keep presenting (cheap, skipped when nothing changed) so that a reset
      // or a post-chain change after convergence is picked up on the next frame.
      this.hooks.idle?.();
      this.hooks.finishFrame();
      this.schedule();
      return;
    }
    // First frame: one iteration to learn the rate; later, fill the budget (at least one).
    const n = Math.max(
      1,
      Math.min(remaining, this.msPerIteration > 0 ? Math.floor(budget / this.msPerIteration) : 1, 256),
    );
    try {
      await this.hooks.ready?.();
    } catch {
      return; // disposed or lost while compiling: the loss handler resumes us
    }
    if (!this.active || this.paused) return;
    const t0 = performance.now();
    try {
      this.hooks.step(n);
      this.hooks.finishFrame();
      await this.hooks.sync();
    } catch {
      // A lost context mid-frame: the backend's loss handler pauses us and restores later.
      return;
    }
    const ms = (performance.now() - t0) / n;
    this.msPerIteration = this.msPerIteration > 0 ? 0.7 * this.msPerIteration + 0.3 * ms : ms;
    this.hooks.onStats(this.msPerIteration);
    this.schedule();
  }
}
