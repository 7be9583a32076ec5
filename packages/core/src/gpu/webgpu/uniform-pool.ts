/**
 * Uniform buffers for draws. Each draw takes a buffer, writes its uniforms into it, and
 * the buffer returns to the pool only once the GPU has finished the submission that
 * reads it. So a buffer is never rewritten while a queued draw may still read it, and
 * two draws in a row with different uniforms each see their own values even if draws
 * are later batched into one submit. Sizes are bucketed to 256 bytes so buffers are
 * shared across passes.
 */
const BUCKET = 256;

export class UniformBufferPool {
  private readonly free = new Map<number, GPUBuffer[]>();
  private readonly all = new Set<GPUBuffer>();
  private inUse: GPUBuffer[] = [];
  private destroyed = false;

  constructor(private readonly device: GPUDevice) {}

  /** A uniform buffer of at least `byteSize` bytes for the next submission. */
  acquire(byteSize: number): GPUBuffer {
    const size = Math.ceil(byteSize / BUCKET) * BUCKET;
    let buffer = this.free.get(size)?.pop();
    if (!buffer) {
      buffer = this.device.createBuffer({
        label: `vpt uniforms (${size} B)`,
        size,
        usage: GPUBufferUsage.UNIFORM | GPUBufferUsage.COPY_DST,
      });
      this.all.add(buffer);
    }
    this.inUse.push(buffer);
    return buffer;
  }

  /** Call right after queue.submit(): the buffers acquired since go back once that work is done. */
  submitted(): void {
    const batch = this.inUse;
    this.inUse = [];
    if (batch.length === 0) return;
    this.device.queue.onSubmittedWorkDone().then(
      () => {
        if (this.destroyed) return;
        for (const b of batch) {
          const list = this.free.get(b.size);
          if (list) list.push(b);
          else this.free.set(b.size, [b]);
        }
      },
      () => undefined,
    );
  }

  /** Destroy every buffer (dispose, or a device that was lost). */
  destroy(): void {
    this.destroyed = true;
    for (const b of this.all) b.destroy();
    this.all.clear();
    this.free.clear();
    this.inUse = [];
  }
}
