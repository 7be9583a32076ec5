/**
 * What both GpuBackends share beside the checks of validation.ts: the owner's loss
 * callbacks, canvas resizing, and the guards every call starts with (not disposed, an
 * object made by this backend, an object of the current context/device generation). The
 * backends extend it and keep only their API's own work.
 */
import { VptError } from '../errors.js';
import { checkCanvasSize } from './validation.js';

export interface BackendNames {
  /** 'WebGL 2' | 'WebGPU', in "this … backend". */
  backend: string;
  /** 'WebGL context' | 'WebGPU device', in "… was lost". */
  lossTarget: string;
}

export abstract class BackendBase {
  /** Bumped on every restore: objects from an older generation point at objects of a dead context/device. */
  protected generation = 0;
  protected disposed = false;
  protected readonly lostCallbacks: Array<() => void> = [];
  protected readonly restoredCallbacks: Array<() => void> = [];
  abstract readonly canvas: HTMLCanvasElement | OffscreenCanvas;

  constructor(private readonly names: BackendNames) {}

  onLost(callback: () => void): void {
    this.lostCallbacks.push(callback);
  }

  onRestored(callback: () => void): void {
    this.restoredCallbacks.push(callback);
  }

  /** A WebGPU context picks up the new size at its next getCurrentTexture(); WebGL's drawing buffer follows the canvas. */
  resizeCanvas(width: number, height: number): void {
    this.assertNotDisposed();
    checkCanvasSize(width, height);
    if (this.canvas.width !== width) this.canvas.width = width;
    if (this.canvas.height !== height) this.canvas.height = height;
  }

  protected own<T>(obj: unknown, cls: abstract new (...args: never[]) => T, what: string): T {
    if (!(obj instanceof cls)) throw new TypeError(`this ${what} was not made by this ${this.names.backend} backend`);
    return obj;
  }

  protected assertCurrent(obj: { generation: number }, what: string): void {
    if (obj.generation !== this.generation) {
      throw new VptError(
        'context-lost',
        `${what} was made before the ${this.names.lossTarget} was lost; re-create it after onRestored`,
      );
    }
  }

  protected assertNotDisposed(): void {
    if (this.disposed) throw new VptError('disposed', `This ${this.names.backend} backend was disposed`);
  }
}

/** Run owner callbacks; one that throws must not stop the others or the backend's own bookkeeping. */
export function runCallbacks(
  callbacks: ReadonlyArray<() => void>,
  what: 'context-loss' | 'device-loss' = 'context-loss',
): void {
  for (const cb of callbacks) {
    try {
      cb();
    } catch (e) {
      console.error(`vpt: a ${what} callback threw`, e);
    }
  }
}
