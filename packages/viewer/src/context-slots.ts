/**
 * WebGL 2 context slots shared by every <vpt-viewer> on a page. Browsers keep only so many
 * live WebGL contexts per page (Chromium 16) and, past that, silently lose the oldest one
 * for good: with 20 viewers the 4 oldest stayed black until Retry. Here a viewer
 * takes a slot before it opens a WebGL 2 context; when all are taken, the least recently
 * used viewer that is off screen (else the least recently used one) releases its context
 * (keeping a still of its image) and waits; a freed slot goes to the waiting viewer that is
 * on screen and was used most recently. WebGPU contexts have no such cap and take no slot.
 */

/** What the slots need of a viewer. */
export interface SlotHolder {
  /** On screen (an IntersectionObserver says so). */
  readonly visible: boolean;
  /** Release the GPU context now (a still of the image stays); the holder then waits for resume(). */
  release(): Promise<void>;
  /** A slot is free again: open a context (the holder calls acquire() as it does). */
  resume(): void;
}

/** Below Chromium's 16, leaving room for contexts the page makes itself. */
export const DEFAULT_WEBGL_SLOTS = 12;

export class ContextSlots {
  /** Holders with a slot, least recently used first. */
  private live: SlotHolder[] = [];
  /** Holders that released their context for another one, oldest release first. */
  private waiting: SlotHolder[] = [];

  constructor(public limit = DEFAULT_WEBGL_SLOTS) {}

  get liveCount(): number {
    return this.live.length;
  }
  get waitingCount(): number {
    return this.waiting.length;
  }

  /** Take a slot for `holder` (most recently used), releasing another holder's context first if none is free. */
  async acquire(holder: SlotHolder): Promise<void> {
    this.waiting = this.waiting.filter((h) => h !== holder);
    this.live = this.live.filter((h) => h !== holder);
    this.live.push(holder);
    const releases: Promise<void>[] = [];
    while (this.live.length > this.limit) {
      const others = this.live.filter((h) => h !== holder);
      const victim = others.find((h) => !h.visible) ?? others[0];
      if (!victim) break;
      this.live = this.live.filter((h) => h !== victim);
      this.waiting.push(victim);
      releases.push(victim.release().catch(() => {}));
    }
    await Promise.all(releases);
  }

  /** `holder` was used (a frame refined, an interaction): it becomes the most recently used. */
  touch(holder: SlotHolder): void {
    const i = this.live.indexOf(holder);
    if (i < 0 || i === this.live.length - 1) return;
    this.live.splice(i, 1);
    this.live.push(holder);
  }

  /** `holder` gave its slot up (disconnected, disposed, or its context is WebGPU): hand the slot on. */
  drop(holder: SlotHolder): void {
    const had = this.live.includes(holder);
    this.live = this.live.filter((h) => h !== holder);
    this.waiting = this.waiting.filter((h) => h !== holder);
    if (had) this.wake();
  }

  /** Whether `holder` released its context and waits for a slot. */
  isWaiting(holder: SlotHolder): boolean {
    return this.waiting.includes(holder);
  }

  /**
   * `holder`'s visibility changed. A waiting holder that came on screen takes a free slot,
   * or the slot of a holder that is off screen.
   */
  visibilityChanged(holder: SlotHolder): void {
    if (!holder.visible || !this.waiting.includes(holder)) {
      this.wake();
      return;
    }
    if (this.live.length < this.limit || this.live.some((h) => !h.visible)) this.resume(holder);
  }

  /** Free slots go to waiting holders: on screen first, the most recently released first. */
  private wake(): void {
    while (this.live.length < this.limit && this.waiting.length) {
      const visible = this.waiting.filter((h) => h.visible);
      if (!visible.length) return; // off-screen holders wait until they are shown
      this.resume(visible[visible.length - 1]);
    }
  }

  private resume(holder: SlotHolder): void {
    // The slot is reserved now; the holder's acquire() (as it opens its context) keeps it.
    this.waiting = this.waiting.filter((h) => h !== holder);
    this.live.push(holder);
    if (this.live.length > this.limit) {
      const victim = this.live.find((h) => h !== holder && !h.visible);
      if (victim) {
        this.live = this.live.filter((h) => h !== victim);
        this.waiting.push(victim);
        void victim.release().catch(() => {});
      }
    }
    queueMicrotask(() => holder.resume());
  }
}

/** The page's slots (one module instance per page, so every viewer from this bundle shares them). */
export const webglSlots = new ContextSlots();
