/**
 * The orbit camera (orbit.ts) loaded on first attach: it was the one part of the entry that
 * needs Three.js (OrbitControls and its math), the largest part of the one-file bundle,
 * and nobody drags before the first image. Until the module lands this holds the element and
 * the camera it was given and hands them over in the same order (attach, then set).
 */
import type { Camera } from '@vpt/core';
import type { OrbitCallbacks, OrbitCamera } from './orbit.js';

export class LazyOrbitCamera {
  private real: OrbitCamera | null = null;
  private loading: Promise<void> | null = null;
  private element: HTMLElement | null = null;
  private camera: Camera | null = null;

  constructor(private readonly callbacks: OrbitCallbacks) {}

  /** Resolves once the controls are live (after the first attach); the element's whenSettled waits for it. */
  get ready(): Promise<void> {
    return this.loading ?? Promise.resolve();
  }

  attach(element: HTMLElement): void {
    this.element = element;
    if (this.real) {
      this.real.attach(element);
      return;
    }
    this.loading ??= import('./orbit.js').then((m) => {
      this.real = new m.OrbitCamera(this.callbacks);
      if (this.element) this.real.attach(this.element);
      if (this.camera) this.real.set(this.camera);
    });
  }

  detach(): void {
    this.element = null;
    this.real?.detach();
  }

  set(camera: Camera): void {
    this.camera = camera;
    this.real?.set(camera);
  }
}
