/**
 * WebGPU reports validation and shader-compiler results asynchronously (error scopes,
 * getCompilationInfo), while createPass() and draw() are synchronous. Their verdicts are
 * collected here, and the next finish() / readTexture() waits for them and rejects with
 * the first error, so a broken kernel surfaces where the caller already awaits.
 */
export class DeferredErrors {
  private readonly pending = new Set<Promise<void>>();
  private errors: Error[] = [];

  /** Follow an asynchronous check that resolves to an error, or null when all was well. */
  track(check: Promise<Error | null>): void {
    const p: Promise<void> = check
      .then(
        (e) => {
          if (e && !this.errors.includes(e)) this.errors.push(e);
        },
        // A check that itself fails (device lost mid-way) has no verdict to report.
        () => undefined,
      )
      .finally(() => this.pending.delete(p));
    this.pending.add(p);
  }

  /** Wait for every check so far; throw (and forget) the first error they found. */
  async flush(): Promise<void> {
    while (this.pending.size > 0) await Promise.all([...this.pending]);
    const first = this.errors[0];
    this.errors = [];
    if (first) throw first;
  }
}
