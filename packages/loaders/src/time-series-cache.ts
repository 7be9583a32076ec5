import { VptError, type TimeSeriesSource, type Volume } from '@vpt/core';

export interface TimeSeriesCacheOptions {
  /** Bytes of voxel data the cache may hold, the step on display included. */
  budgetBytes: number;
  /** How many steps after the one asked for to read ahead (default 4), as the budget allows. */
  prefetch?: number;
  /** Play backwards or forwards: the steps read ahead are index + 1, + 2… (1) or index − 1… (−1). */
  direction?: 1 | -1;
}

/** The bytes a volume's voxels take in memory. */
export function volumeBytes(v: Volume): number {
  return v.data.byteLength;
}

/** Is this a TimeSeriesSource (an object with an integer `steps` and a `loadStep` function)? */
export function isTimeSeriesSource(s: unknown): s is TimeSeriesSource {
  const o = s as TimeSeriesSource;
  return !!o && typeof o === 'object' && typeof o.loadStep === 'function' && Number.isInteger(o.steps);
}

interface Entry<V> {
  volume: V;
  bytes: number;
  lastUsed: number;
}

/**
 * The steps of a time series held in memory: `get(i)` returns step i (read once), then reads
 * the next steps in the background while their bytes fit the budget, dropping the least
 * recently used steps that are not among those wanted next. Playback wraps around, so the
 * steps read ahead of the last one are the first ones. Step sizes are counted from the data
 * read (the first step's size stands in for a step not yet read), and a step being read
 * counts as held, so `bytesHeld() ≤ budgetBytes` holds at every moment once the budget
 * holds one step; a budget smaller than one step holds just the step asked for.
 */
export class TimeSeriesCache<V extends Volume = Volume> {
  private readonly resident = new Map<number, Entry<V>>();
  private readonly pending = new Map<number, { promise: Promise<V>; bytes: number }>();
  private clock = 0;
  private current = -1;
  private generation = 0;
  private stepBytes = 0;
  private first: Volume | null = null;
  private disposed = false;
  private readonly budget: number;
  private readonly ahead: number;
  private direction: 1 | -1;
  /** The background reads' progress (for tests and benchmarks: resolves when the read-ahead is done). */
  private prefetching: Promise<void> = Promise.resolve();

  constructor(
    readonly source: TimeSeriesSource<V>,
    options: TimeSeriesCacheOptions,
  ) {
    if (!isTimeSeriesSource(source) || source.steps < 1)
      throw new VptError('invalid-scene', `TimeSeriesCache: the source must have steps ≥ 1 and loadStep()`);
    if (!(options.budgetBytes >= 0) || !Number.isFinite(options.budgetBytes))
      throw new VptError(
        'invalid-scene',
        `TimeSeriesCache: budgetBytes must be a finite number ≥ 0, got ${options.budgetBytes}`,
      );
    const ahead = options.prefetch ?? 4;
    if (!Number.isInteger(ahead) || ahead < 0)
      throw new VptError('invalid-scene', `TimeSeriesCache: prefetch must be an integer ≥ 0, got ${options.prefetch}`);
    this.budget = options.budgetBytes;
    this.ahead = Math.min(ahead, source.steps - 1);
    this.direction = options.direction ?? 1;
  }

  get steps(): number {
    return this.source.steps;
  }

  /** Steps in memory, in index order. */
  residentSteps(): number[] {
    return [...this.resident.keys()].sort((a, b) => a - b);
  }

  /** Bytes of the steps in memory plus those being read. */
  bytesHeld(): number {
    let n = 0;
    for (const e of this.resident.values()) n += e.bytes;
    for (const p of this.pending.values()) n += p.bytes;
    return n;
  }

  has(index: number): boolean {
    return this.resident.has(index);
  }

  /** Resolves once the reads ahead of the last `get` are done (or given up). */
  whenPrefetched(): Promise<void> {
    return this.prefetching;
  }

  /** Which way playback goes (the steps read ahead). */
  setDirection(direction: 1 | -1): void {
    this.direction = direction;
  }

  /** Step `index`, from memory or read now; the steps after it are then read ahead. */
  async get(index: number, signal?: AbortSignal): Promise<V> {
    this.checkIndex(index);
    this.current = index;
    const generation = ++this.generation;
    const volume = await this.read(index, signal, true);
    if (this.disposed) return volume;
    const entry = this.resident.get(index);
    if (entry) entry.lastUsed = ++this.clock;
    // Only the newest get reads ahead: a get that lands late must not undo a newer plan.
    if (generation === this.generation) this.prefetching = this.readAhead(generation);
    return volume;
  }

  /** Drop every step; reads under way are left to finish and are then forgotten. */
  dispose(): void {
    this.disposed = true;
    this.generation++;
    this.resident.clear();
    this.pending.clear();
  }

  private checkIndex(index: number): void {
    if (!Number.isInteger(index) || index < 0 || index >= this.source.steps)
      throw new VptError(
        'invalid-scene',
        `time step ${index} does not exist: the series has ${this.source.steps} step${this.source.steps === 1 ? '' : 's'} (0 to ${this.source.steps - 1})`,
      );
  }

  /** The steps wanted after the current one, nearest first. */
  private wanted(): number[] {
    const n = this.source.steps;
    const out: number[] = [];
    for (let k = 1; k <= this.ahead; k++) out.push((((this.current + k * this.direction) % n) + n) % n);
    return out;
  }

  private async readAhead(generation: number): Promise<void> {
    for (const step of this.wanted()) {
      if (generation !== this.generation || this.disposed) return;
      if (this.resident.has(step)) continue;
      if (!this.makeRoom(this.stepBytes, step)) return;
      try {
        await this.read(step, undefined, false);
      } catch {
        // A step that fails to read ahead is read again (and its error reported) when asked for.
        return;
      }
    }
  }

  /**
   * Frees bytes for a step about to be read: drops steps that are neither on display nor
   * wanted before `step`, those not wanted at all first (least recently used first), then
   * the wanted ones farthest ahead. False when the room cannot be made.
   */
  private makeRoom(bytes: number, step: number): boolean {
    const wanted = this.wanted();
    const at = wanted.indexOf(step);
    const keep = new Set([this.current, ...(at < 0 ? [] : wanted.slice(0, at))]);
    while (this.bytesHeld() + bytes > this.budget) {
      let victim = -1,
        best = Infinity;
      for (const [i, e] of this.resident) {
        if (keep.has(i) || i === step) continue;
        const w = wanted.indexOf(i);
        // Not wanted: by last use (older first); wanted: after every unwanted one, farthest first.
        const score = w < 0 ? e.lastUsed : Number.MAX_SAFE_INTEGER - w;
        if (score < best) {
          best = score;
          victim = i;
        }
      }
      if (victim < 0) return false;
      this.resident.delete(victim);
    }
    return true;
  }

  private read(index: number, signal: AbortSignal | undefined, asked: boolean): Promise<V> {
    const hit = this.resident.get(index);
    if (hit) return Promise.resolve(hit.volume);
    const on = this.pending.get(index);
    if (on) return on.promise;
    const promise = this.source.loadStep(index, signal).then(
      (volume) => {
        this.pending.delete(index);
        if (this.disposed) return volume;
        this.checkGrid(volume, index);
        const bytes = volumeBytes(volume);
        this.stepBytes = Math.max(this.stepBytes, bytes);
        // The step asked for is always held; one read ahead only if it still fits.
        if (asked || index === this.current) {
          this.makeRoom(bytes, index);
          this.resident.set(index, { volume, bytes, lastUsed: ++this.clock });
        } else if (this.makeRoom(bytes, index)) {
          this.resident.set(index, { volume, bytes, lastUsed: 0 });
        }
        return volume;
      },
      (e) => {
        this.pending.delete(index);
        throw e;
      },
    );
    this.pending.set(index, { promise, bytes: asked ? 0 : this.stepBytes });
    return promise;
  }

  /** Every step has step 0's grid: a step of another size or type is not the same series. */
  private checkGrid(v: Volume, index: number): void {
    if (!this.first) {
      this.first = v;
      return;
    }
    const f = this.first;
    if (v.type !== f.type || v.dims.some((d, i) => d !== f.dims[i]))
      throw new VptError(
        'load-failed',
        `time step ${index} is ${v.dims.join('×')} ${v.type}, unlike the series' ${f.dims.join('×')} ${f.type}: every step must have the same grid`,
      );
  }
}
