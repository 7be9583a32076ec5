/**
 * A vpt volume as a three.js Object3D. It draws with vpt's WebGL 2 backend on the
 * WebGLRenderer's own context (RenderContextOptions.gl): GL state is set by vpt before each
 * use and three's state cache is reset after (renderer.resetState()), so the volume reads
 * three's depth texture directly (no read-back) and writes into three's render target. With
 * a WebGPURenderer it draws with vpt's WebGPU backend on the renderer's own GPUDevice
 * (RenderContextOptions.device; connectDevice / refineDevice), which has no state to reset.
 */
import { Matrix4, Object3D, Quaternion, Vector3, type Camera, type PerspectiveCamera, type WebGLRenderer } from 'three';
import { RenderContext, VptError, type Renderer, type Scene } from '@vpt/core';

/** What a VptVolume holds: everything of a core Scene except the camera, which three's camera gives. */
export type VptVolumeScene = Omit<Scene, 'camera'>;

export interface VptVolumeOptions {
  /** Any renderer of the catalog (new EamRenderer(), new McrtRenderer()…). */
  renderer: Renderer;
  scene: VptVolumeScene;
  /** Iterations (samples per pixel) added per rendered frame; default 1. */
  iterationsPerFrame?: number;
  /** Stop refining after this many samples per pixel (the image stays); default 1024. */
  maxSamples?: number;
}

/** The view vpt renders: its camera in the volume's frame and the world scale of that frame. */
export interface VptView {
  scene: Scene;
  /** World units per vpt unit (the volume's box has a longest side of 1 at scale 1). */
  scale: number;
  /** The projection's P[10] and P[14] (three.js column-major elements 10 and 14). */
  p10: number;
  p14: number;
  /** vpt's frame (the volume's box) → three's world. */
  toWorld: Matrix4;
}

const EPS = 1e-9;

/**
 * The vpt scene of a volume seen by a three.js camera. The object's matrixWorld is taken as
 * translation · rotation · scale: a non-uniform scale becomes the volume's spacing (the box is
 * stretched along the object's axes), the rest is a rigid map times a uniform scale k, so the
 * camera is expressed in the volume's frame exactly (position and orientation mapped by the
 * inverse; rays keep their pixels). Optical depth is per vpt unit, so scaling the object
 * scales its look like a model's, not its density. Perspective cameras only.
 */
export function vptViewOf(object: Object3D, camera: Camera, base: VptVolumeScene): VptView {
  const P = camera.projectionMatrix.elements;
  if (!(camera as PerspectiveCamera).isPerspectiveCamera || Math.abs(P[11] + 1) > 1e-6)
    throw new VptError('invalid-scene', 'VptVolume: only perspective cameras are supported');
  if (Math.abs(P[8]) > 1e-6 || Math.abs(P[9]) > 1e-6)
    throw new VptError('invalid-scene', 'VptVolume: off-centre projections (setViewOffset) are not supported');
  const position = new Vector3();
  const rotation = new Quaternion();
  const scale = new Vector3();
  object.matrixWorld.decompose(position, rotation, scale);
  const s = [scale.x, scale.y, scale.z];
  if (s.some((v) => !(Math.abs(v) > EPS)))
    throw new VptError('invalid-scene', 'VptVolume: the object scale must be non-zero');
  const v = base.volume;
  const spacing = v.spacing.map((sp, i) => sp * Math.abs(s[i])) as [number, number, number];
  const ext0 = Math.max(...v.dims.map((d, i) => d * v.spacing[i]));
  const ext1 = Math.max(...v.dims.map((d, i) => d * spacing[i]));
  const k = ext1 / ext0;
  // Mirrored axes (negative scale) flip the rotation's handedness: fold the signs into it.
  const signs = new Matrix4().makeScale(Math.sign(s[0]), Math.sign(s[1]), Math.sign(s[2]));
  const toWorld = new Matrix4().compose(position, rotation, new Vector3(k, k, k)).multiply(signs);
  const toLocal = toWorld.clone().invert();
  const cm = camera.matrixWorld;
  const eye = new Vector3().setFromMatrixPosition(cm);
  const forward = new Vector3().setFromMatrixColumn(cm, 2).negate();
  const up = new Vector3().setFromMatrixColumn(cm, 1);
  const eyeL = eye.clone().applyMatrix4(toLocal);
  const targetL = eye.clone().add(forward.normalize()).applyMatrix4(toLocal);
  const upL = up.transformDirection(toLocal);
  const fovy = 2 * Math.atan(1 / P[5]);
  const sameVolume = spacing.every((sp, i) => sp === v.spacing[i]);
  const scene: Scene = {
    ...base,
    volume: sameVolume ? v : { ...v, spacing },
    camera: { position: eyeL.toArray(), target: targetL.toArray(), up: upL.toArray(), fovy },
  };
  return { scene, scale: k, p10: P[10], p14: P[14], toWorld };
}

/**
 * A progressive vpt volume in a three.js scene. Add it to the scene and draw the scene with
 * a VptCompositor (compositor.ts), which renders three's opaque meshes first, ends the
 * volume's camera rays at their depth, composites it, then draws the transparent meshes.
 * The estimate restarts whenever the object's transform, the camera, the size or the scene
 * changes (setScene); otherwise each frame adds `iterationsPerFrame` samples per pixel.
 */
export class VptVolume extends Object3D {
  readonly isVptVolume = true;
  readonly renderer: Renderer;
  iterationsPerFrame: number;
  maxSamples: number;
  private base: VptVolumeScene;
  private ctx: RenderContext | null = null;
  private creating: Promise<RenderContext> | null = null;
  private gl: WebGL2RenderingContext | null = null;
  private device: GPUDevice | null = null;
  private viewKey = '';
  private sceneVersion = 0;
  private appliedVersion = -1;
  /** The last view drawn (its box and scale), for the compositor's depth. */
  lastView: VptView | null = null;

  constructor(options: VptVolumeOptions) {
    super();
    this.renderer = options.renderer;
    this.base = options.scene;
    this.iterationsPerFrame = options.iterationsPerFrame ?? 1;
    this.maxSamples = options.maxSamples ?? 1024;
    // Nothing for three to draw itself: the compositor draws the volume.
    this.frustumCulled = false;
  }

  /** Replace the vpt scene (TF, lights, environment, volume…); restarts accumulation. */
  setScene(scene: VptVolumeScene): void {
    this.base = scene;
    this.sceneVersion++;
  }

  get scene(): VptVolumeScene {
    return this.base;
  }

  /** Samples per pixel in the current estimate. */
  get sampleCount(): number {
    return this.ctx?.stats.iterations ?? 0;
  }

  /** The vpt context (null until the first frame with this renderer made it). */
  get context(): RenderContext | null {
    return this.ctx;
  }

  /**
   * Make the vpt context on the renderer's WebGL 2 context (once). The compositor calls it;
   * await it (or the compositor's `ready`) before the first frame you need to see.
   */
  async connect(renderer: WebGLRenderer, width: number, height: number): Promise<RenderContext> {
    const gl = renderer.getContext();
    if (!(typeof WebGL2RenderingContext !== 'undefined' && gl instanceof WebGL2RenderingContext))
      throw new VptError('no-backend', 'VptVolume needs a WebGLRenderer on a WebGL 2 context');
    if (this.ctx && this.gl === gl) return this.ctx;
    if (this.creating && this.gl === gl) return this.creating;
    this.ctx?.dispose();
    this.ctx = null;
    this.viewKey = '';
    this.gl = gl;
    this.device = null;
    this.creating = RenderContext.create({ gl, backend: 'webgl2', width, height, renderer: this.renderer }).then(
      (ctx) => {
        renderer.resetState();
        this.ctx = ctx;
        return ctx;
      },
    );
    return this.creating;
  }

  /**
   * Make the vpt context on a WebGPURenderer's GPUDevice (`renderer.backend.device`), once:
   * vpt's WebGPU backend draws on that device (RenderContextOptions.device) and its images
   * are GPUTextures of it. The WebGPU compositor (`@vpt/three/webgpu`) calls it.
   */
  async connectDevice(device: GPUDevice, width: number, height: number): Promise<RenderContext> {
    if (this.ctx && this.device === device) return this.ctx;
    if (this.creating && this.device === device) return this.creating;
    this.ctx?.dispose();
    this.ctx = null;
    this.viewKey = '';
    this.device = device;
    this.gl = null;
    this.creating = RenderContext.create({ device, backend: 'webgpu', width, height, renderer: this.renderer }).then(
      (ctx) => {
        this.ctx = ctx;
        return ctx;
      },
    );
    return this.creating;
  }

  /**
   * Refine on a shared GPUDevice (connectDevice): camera rays end at `depth` (three's
   * depth32float depth texture of the opaque pass, WebGPU's clip depth in [0, 1]); returns
   * the HDR image's GPUTexture (null until the context exists).
   */
  refineDevice(camera: Camera, width: number, height: number, depth: GPUTexture | null): GPUTexture | null {
    if (!this.ctx || !this.device) return null;
    // WebGPU's clip depth d = P14 / f − P10 (forward distance f), written as vpt's a / (2d − 1 + b).
    this.advance(camera, width, height, depth, (v) => ({ a: (2 * v.p14) / v.scale, b: 2 * v.p10 + 1 }));
    return this.ctx.hdrGpuTexture();
  }

  /**
   * Refine the estimate for this camera, ending camera rays at `depth` (three's depth
   * texture of the opaque pass, the render size) and return the HDR image's GL texture (null
   * until the context exists). Called by the compositor between its passes; leaves three's
   * state reset.
   */
  refine(
    renderer: WebGLRenderer,
    camera: Camera,
    width: number,
    height: number,
    depth: WebGLTexture | null,
  ): WebGLTexture | null {
    if (!this.ctx || !this.gl) {
      void this.connect(renderer, width, height);
      return null;
    }
    try {
      this.advance(camera, width, height, depth, (v) => ({ a: v.p14 / v.scale, b: v.p10 }));
      return this.ctx.hdrGlTexture();
    } finally {
      renderer.resetState();
    }
  }

  /** setScene when the view changed, the depth limit, then the frame's iterations. */
  private advance(
    camera: Camera,
    width: number,
    height: number,
    depth: WebGLTexture | GPUTexture | null,
    depthMap: (v: VptView) => { a: number; b: number },
  ): void {
    const ctx = this.ctx!;
    const view = vptViewOf(this, camera, this.base);
    this.lastView = view;
    if (ctx.size.width !== width || ctx.size.height !== height) ctx.setSize(width, height);
    const key = JSON.stringify([view.scene.camera, view.scene.volume.spacing, width, height]);
    if (key !== this.viewKey || this.appliedVersion !== this.sceneVersion) {
      ctx.setScene(view.scene);
      this.viewKey = key;
      this.appliedVersion = this.sceneVersion;
    }
    const limit = depth ? { texture: depth, ...depthMap(view), depthGuide: true } : null;
    // A new depth texture restarts the estimate (the context resets itself).
    ctx.setDepthLimit(limit);
    const n = Math.min(this.iterationsPerFrame, this.maxSamples - ctx.stats.iterations);
    if (n > 0) ctx.iterate(n);
  }

  /** Free the vpt context (three's context stays). */
  dispose(): void {
    this.ctx?.dispose();
    this.ctx = null;
    this.creating = null;
    this.gl = null;
    this.device = null;
  }
}
