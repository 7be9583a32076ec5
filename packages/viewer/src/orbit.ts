/**
 * Orbit / pan / zoom for a canvas with Three.js OrbitControls (mouse and touch), plus a
 * keyboard binding of our own: arrows orbit, Shift+arrows pan, +/- zoom. Three.js only
 * does camera math here; the vpt Camera is the source of truth in and out.
 */
import type { Camera, Vec3 } from '@vpt/core';
import { PerspectiveCamera, Spherical, Vector3 } from 'three';
import { OrbitControls } from 'three/addons/controls/OrbitControls.js';

export interface OrbitCallbacks {
  /** The user moved the camera. */
  change(camera: Camera): void;
  /** An interaction began (pointer down, first key press, wheel). */
  start(): void;
  /** It ended (pointer up, key released for a moment, wheel idle). */
  end(): void;
}

const KEY_ORBIT = (5 * Math.PI) / 180;
const KEY_END_MS = 250;

export class OrbitCamera {
  private readonly camera3 = new PerspectiveCamera(40, 1, 0.001, 1000);
  private controls: OrbitControls | null = null;
  private element: HTMLElement | null = null;
  private up: Vec3 = [0, 1, 0];
  private keyTimer: ReturnType<typeof setTimeout> | null = null;
  /** The target while detached (OrbitControls holds it otherwise). */
  private savedTarget: Vector3 | null = null;
  private readonly listeners = {
    change: () => this.callbacks.change(this.get()),
    start: () => this.callbacks.start(),
    end: () => this.callbacks.end(),
  };

  constructor(private readonly callbacks: OrbitCallbacks) {}

  /** Listen to pointer, wheel and key events on `element` (the canvas); call again after replacing it. */
  attach(element: HTMLElement): void {
    this.detach();
    this.element = element;
    element.addEventListener('keydown', this.onKey);
    this.rebuildControls();
  }

  /**
   * Stop listening (the camera is kept). Call it while the element is still in its tree:
   * OrbitControls also listens on the element's root node (a shadow root here) and removes
   * that listener from whatever root the element has when disposed, so a canvas removed
   * first would leave the listener, and through it the canvas, behind.
   */
  detach(): void {
    this.element?.removeEventListener('keydown', this.onKey);
    if (this.controls) this.savedTarget = this.controls.target.clone();
    this.disposeControls();
    this.element = null;
  }

  /** Set the camera from outside (no change callback). */
  set(camera: Camera): void {
    const upChanged = camera.up.some((v, i) => v !== this.up[i]);
    this.up = [...camera.up];
    this.camera3.up.fromArray(camera.up).normalize();
    this.camera3.position.fromArray(camera.position);
    this.camera3.fov = (camera.fovy * 180) / Math.PI;
    this.camera3.lookAt(new Vector3().fromArray(camera.target));
    if (this.savedTarget) this.savedTarget.fromArray(camera.target);
    if (this.controls) {
      this.controls.target.fromArray(camera.target);
      // OrbitControls fixes its "up" when constructed: a new up needs new controls.
      if (upChanged) this.rebuildControls();
    }
  }

  get(): Camera {
    const target = this.controls ? this.controls.target : (this.savedTarget ?? new Vector3());
    return {
      position: round(this.camera3.position.toArray()),
      target: round(target.toArray()),
      up: [...this.up],
      fovy: (this.camera3.fov * Math.PI) / 180,
    };
  }

  set enabled(on: boolean) {
    if (this.controls) this.controls.enabled = on;
  }

  dispose(): void {
    this.element?.removeEventListener('keydown', this.onKey);
    this.disposeControls();
    if (this.keyTimer) clearTimeout(this.keyTimer);
  }

  private rebuildControls(): void {
    const target = this.controls?.target.clone() ?? this.savedTarget ?? undefined;
    this.savedTarget = null;
    this.disposeControls();
    if (!this.element) return;
    const c = new OrbitControls(this.camera3, this.element);
    c.enableDamping = false;
    c.zoomToCursor = false;
    c.screenSpacePanning = true;
    if (target) c.target.copy(target);
    c.addEventListener('change', this.listeners.change);
    c.addEventListener('start', this.listeners.start);
    c.addEventListener('end', this.listeners.end);
    this.controls = c;
  }

  private disposeControls(): void {
    if (!this.controls) return;
    this.controls.removeEventListener('change', this.listeners.change);
    this.controls.removeEventListener('start', this.listeners.start);
    this.controls.removeEventListener('end', this.listeners.end);
    this.controls.dispose();
    this.controls = null;
  }

  /** Arrows orbit around the target, Shift+arrows pan, +/- (and PageUp/PageDown) zoom. */
  private readonly onKey = (e: KeyboardEvent): void => {
    if (!this.controls || !this.controls.enabled) return;
    const cam = this.camera3;
    const target = this.controls.target;
    const offset = cam.position.clone().sub(target);
    let handled = true;
    const dx = e.key === 'ArrowLeft' ? -1 : e.key === 'ArrowRight' ? 1 : 0;
    const dy = e.key === 'ArrowUp' ? -1 : e.key === 'ArrowDown' ? 1 : 0;
    if ((dx || dy) && e.shiftKey) {
      // Pan in the view plane by 5% of the distance per press.
      const dist = offset.length() * 0.05;
      const right = new Vector3().setFromMatrixColumn(cam.matrixWorld, 0).multiplyScalar(dx * dist);
      const up = new Vector3().setFromMatrixColumn(cam.matrixWorld, 1).multiplyScalar(-dy * dist);
      target.add(right).add(up);
      cam.position.add(right).add(up);
    } else if (dx || dy) {
      // Orbit in the frame where `up` is +y (the same frame OrbitControls uses).
      const toYUp = new Vector3(0, 1, 0);
      const q = cam.quaternion.clone().setFromUnitVectors(cam.up.clone().normalize(), toYUp);
      offset.applyQuaternion(q);
      const s = new Spherical().setFromVector3(offset);
      s.theta -= dx * KEY_ORBIT;
      s.phi = Math.min(Math.PI - 1e-3, Math.max(1e-3, s.phi + dy * KEY_ORBIT));
      offset.setFromSpherical(s).applyQuaternion(q.invert());
      cam.position.copy(target).add(offset);
    } else if (e.key === '+' || e.key === '=' || e.key === 'PageUp') {
      cam.position.copy(target).add(offset.multiplyScalar(1 / 1.1));
    } else if (e.key === '-' || e.key === '_' || e.key === 'PageDown') {
      cam.position.copy(target).add(offset.multiplyScalar(1.1));
    } else {
      handled = false;
    }
    if (!handled) return;
    e.preventDefault();
    cam.lookAt(target);
    cam.updateMatrixWorld();
    if (!this.keyTimer) this.callbacks.start();
    else clearTimeout(this.keyTimer);
    this.keyTimer = setTimeout(() => {
      this.keyTimer = null;
      this.callbacks.end();
    }, KEY_END_MS);
    this.callbacks.change(this.get());
  };
}

/** Drop float noise below 1e-6 so reflected camera attributes stay readable. */
function round(v: number[]): Vec3 {
  return v.map((x) => Math.round(x * 1e6) / 1e6) as Vec3;
}
