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
  /** The learned rates: ms per iteration, and ms per frame of finishFrame (render, post chain, present). */
  onStats(msPerIteration: number, msPerFrame: number): void;
  /** Work for a converged frame (a bricked volume's arrived bricks); a reset it causes resumes the iterations. */
  idle?(): void;
  /**
   * Whether GPU work was queued outside the loop's frames since the last call (temporal reuse
   * resolves the history when the camera moves between frames); the call clears it. Such work
   * runs in the queue before or among the frame's iterations, so timing it as theirs would
   * inflate the learned rate: the loop waits for it first, or leaves that frame out of learning.
   */
  takeOutsideWork?(): boolean;
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
  private msFinish = 0;
  /** Outside work came in during the last frame's finish and may still be queued. */
  private outsidePending = false;
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
    try {
      await this.hooks.ready?.();
    } catch {
      return; // disposed or lost while compiling: the loss handler resumes us
    }
    if (!this.active || this.paused) return;
    // Work queued between frames (a camera move's history resolve) runs first: wait for it, so the
    // batch below times only its iterations, and take its time off this frame's budget.
    let outside = 0;
    // Both read: taking the flag clears it, so it is taken even when the last finish left work queued.
    const outsideQueued = this.takeOutsideWork() || this.outsidePending;
    this.outsidePending = false;
    if (outsideQueued) {
      const tw = performance.now();
      try {
        await this.hooks.sync();
      } catch {
        return;
      }
      outside = performance.now() - tw;
      if (!this.active || this.paused) return;
    }
    // First frame: one iteration to learn the rate; later, fill what the frame's finish (render,
    // post chain: the denoiser's share can exceed the iterations') leaves of the budget (at least one).
    const n = Math.max(
      1,
      Math.min(
        remaining,
        this.msPerIteration > 0 ? Math.floor(Math.max(0, budget - this.msFinish - outside) / this.msPerIteration) : 1,
        256,
      ),
    );
    const counted = this.options.currentIterations;
    const start = counted?.() ?? 0;
    const t0 = performance.now();
    let t1: number;
    // Whether the batch and the finish ran as timed: no reset (a camera change) and no outside work
    // came in while the loop awaited the GPU (WebGPU's sync is a real wait; WebGL 2's readPixels
    // blocks, so nothing comes in there); a part that had either teaches nothing.
    let batchClean: boolean;
    let finishClean: boolean;
    try {
      this.hooks.step(n);
      // Synchronised twice, so the iterations' time is learned apart from the finish's: a post step
      // costs once per frame, not per iteration (the element's adaptive resolution reads the rate).
      await this.hooks.sync();
      t1 = performance.now();
      batchClean = !this.takeOutsideWork() && (!counted || counted() === start + n);
      this.hooks.finishFrame();
      await this.hooks.sync();
      // Work that came in while the finish was awaited may still be queued: the next frame waits for it.
      this.outsidePending = this.takeOutsideWork();
      finishClean = batchClean && !this.outsidePending;
    } catch {
      // A lost context mid-frame: the backend's loss handler pauses us and restores later.
      return;
    }
    const ms = (t1 - t0) / n;
    const finish = performance.now() - t1;
    if (batchClean || !(this.msPerIteration > 0)) this.msPerIteration = learn(this.msPerIteration, ms);
    if (finishClean || !(this.msFinish > 0)) this.msFinish = learn(this.msFinish, finish);
    this.hooks.onStats(this.msPerIteration, this.msFinish);
    this.schedule();
  }

  private takeOutsideWork(): boolean {
    return this.hooks.takeOutsideWork?.() ?? false;
  }
}

/**
 * Smoothed rate: a frame under half the learned value replaces it at once (the value held a spike:
 * the first frame's compilation, a stall, which smoothing would drag through many frames and the
 * element's adaptive resolution would read as the cost of an iteration); otherwise 0.7 / 0.3.
 */
function learn(prev: number, ms: number): number {
  return prev > 0 && ms >= 0.5 * prev ? 0.7 * prev + 0.3 * ms : ms;
}
