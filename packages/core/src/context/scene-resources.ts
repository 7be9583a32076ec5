import type { GpuBackend, GpuTexture, RenderTarget } from '../gpu/backend.js';
import type { AuxiliaryPass, AuxiliaryTexture, Renderer } from '../renderer.js';
import type { Scene } from '../scene/scene.js';
import { rasterizeTransferFunction, TF_RESOLUTION, transferFunctionSize } from '../scene/transfer-function.js';
import { normalizedData } from '../scene/volume.js';
import { buildGradientVolume, destroyGradientVolume, type GradientVolume } from '../gradient/gradient-volume.js';

/**
 * The GPU resources a scene needs beside the renderer's targets, and their lifetimes: the
 * volume texture (rebuilt when the volume changes, by identity), the transfer function
 * (by content), the gradient-magnitude volume (when a 2D TF or the renderer asks for it,
 * until the volume changes) and the renderer's auxiliary textures (by key). RenderContext
 * owns one and asks it to sync before a frame, to release everything on dispose and to
 * forget the lost handles after a context loss.
 */
export class SceneResources {
  volumeTexture: GpuTexture | null = null;
  private volumeSource: Scene['volume'] | null = null;
  tfTexture: GpuTexture | null = null;
  private tfSource: string | null = null;
  // The volume's gradient magnitude (gradient/), built on the GPU the first time a 2D TF or
  // a renderer with needsGradient asks for it, kept until the volume changes.
  gradient: GradientVolume | null = null;
  private gradientSource: Scene['volume'] | null = null;
  // Renderer-declared textures by name; `target` is set for GPU-made ones (AuxiliaryPass).
  readonly auxTextures = new Map<string, AuxEntry>();
  private auxFor: { scene: Scene | null; renderer: Renderer | null; version: number } = { scene: null, renderer: null, version: -1 };

  constructor(private readonly backend: GpuBackend, private readonly current: () => { scene: Scene | null; renderer: Renderer }) {}

  private get scene(): Scene | null { return this.current().scene; }
  private get _renderer(): Renderer { return this.current().renderer; }

  /** Upload the volume and transfer function when they changed (by identity / content). */
  sync(): void {
    const scene = this.scene!;
    if (this.volumeSource !== scene.volume || !this.volumeTexture) {
      if (this.volumeTexture) this.backend.destroyTexture(this.volumeTexture);
      this.volumeTexture = null;
      this.dropGradient();
      const [width, height, depth] = scene.volume.dims;
      this.volumeTexture = this.backend.createTexture({ dimension: '3d', width, height, depth, format: 'r32float', data: normalizedData(scene.volume), label: 'volume' });
      this.volumeSource = scene.volume;
    }
    const tfKey = JSON.stringify(scene.transferFunction);
    if (this.tfSource !== tfKey || !this.tfTexture) {
      const data = rasterizeTransferFunction(scene.transferFunction, TF_RESOLUTION);
      const [width, height] = transferFunctionSize(scene.transferFunction, TF_RESOLUTION);
      if (this.tfTexture && (this.tfTexture.width !== width || this.tfTexture.height !== height)) {
        this.backend.destroyTexture(this.tfTexture);
        this.tfTexture = null;
      }
      if (this.tfTexture) this.backend.writeTexture(this.tfTexture, data);
      else this.tfTexture = this.backend.createTexture({ dimension: '2d', width, height, format: 'rgba32float', data, label: 'transfer function' });
      this.tfSource = tfKey;
    }
    this.syncGradient();
  }

  /** A 2D transfer function reads the gradient magnitude, and so does a renderer that asks for it. */
  wantsGradient(scene: Scene): boolean {
    return scene.transferFunction.dimensions === '2d' || this._renderer.needsGradient === true;
  }

  /** Build the gradient-magnitude volume when the scene first needs it (GPU passes, no read-back). */
  syncGradient(): void {
    const scene = this.scene!;
    if (!this.wantsGradient(scene) || !this.volumeTexture || this.backend.isLost) return;
    if (this.gradient && this.gradientSource === scene.volume) return;
    this.dropGradient();
    this.gradient = buildGradientVolume(this.backend, this.volumeTexture, scene.volume);
    this.gradientSource = scene.volume;
  }

  dropGradient(): void {
    if (this.gradient) destroyGradientVolume(this.backend, this.gradient);
    this.gradient = null;
    this.gradientSource = null;
  }

  /** The gradient volume of the current scene, built now if the scene had not needed it yet. */
  ensureGradient(): GradientVolume {
    const scene = this.scene!;
    if (!this.gradient || this.gradientSource !== scene.volume) {
      this.dropGradient();
      this.gradient = buildGradientVolume(this.backend, this.volumeTexture!, scene.volume);
      this.gradientSource = scene.volume;
    }
    return this.gradient;
  }

  /** Build, reuse or free the renderer's auxiliary textures (only when scene or renderer changed). */
  syncAuxiliaryTextures(): void {
    const r = this._renderer;
    if (this.auxFor.scene === this.scene && this.auxFor.renderer === r && this.auxFor.version === r.version) return;
    const specs: readonly AuxiliaryTexture[] = r.auxiliaryTextures?.(this.scene!) ?? [];
    const wanted = new Set(specs.map((a) => a.name));
    for (const [name, aux] of this.auxTextures) {
      if (!wanted.has(name)) { this.releaseAux(aux); this.auxTextures.delete(name); }
    }
    for (const spec of specs) {
      const have = this.auxTextures.get(spec.name);
      if (have && have.key === spec.key) continue;
      if (have) { this.releaseAux(have); this.auxTextures.delete(spec.name); }
      this.auxTextures.set(spec.name, spec.render ? this.renderAux(spec, spec.render) : { key: spec.key, texture: this.backend.createTexture(this.auxDescriptor(spec)), dimension: spec.dimension, bind: spec.bind !== false });
    }
    this.auxFor = { scene: this.scene, renderer: r, version: r.version };
  }

  private auxDescriptor(spec: AuxiliaryTexture) {
    if (!spec.create) throw new RangeError(`auxiliary texture "${spec.name}" has neither create() nor render`);
    return spec.create();
  }

  /** Run an AuxiliaryPass into a new 2D target, reading the scene's textures and earlier auxiliary ones. */
  private renderAux(spec: AuxiliaryTexture, p: AuxiliaryPass): AuxEntry {
    if (spec.dimension !== '2d') throw new RangeError(`auxiliary texture "${spec.name}": a GPU-made texture is 2D`);
    const textures: Record<string, GpuTexture> = {};
    for (const b of p.inputs) {
      const t = b.name === 'volume' ? this.volumeTexture : b.name === 'transferFunction' ? this.tfTexture : this.auxTextures.get(b.name)?.texture;
      if (!t) throw new RangeError(`auxiliary pass "${p.label}" reads "${b.name}", which is not the volume, the transfer function or an earlier auxiliary texture`);
      textures[b.name] = t;
    }
    const pass = this.backend.createPass({ label: p.label, glsl: p.glsl, wgsl: p.wgsl, uniforms: p.uniforms, textures: p.inputs, outputs: [p.format] });
    const target = this.backend.createRenderTarget(p.width, p.height, [p.format], p.label);
    this.backend.draw(pass, { uniforms: p.uniforms.pack(p.values), textures, target });
    return { key: spec.key, texture: target.textures[0], dimension: '2d', target, bind: spec.bind !== false };
  }

  releaseAux(aux: AuxEntry): void {
    if (aux.target) this.backend.destroyRenderTarget(aux.target);
    else this.backend.destroyTexture(aux.texture);
  }

  /** Destroy every texture (dispose, or before rebuilding all). */
  release(): void {
    if (this.volumeTexture) this.backend.destroyTexture(this.volumeTexture);
    if (this.tfTexture) this.backend.destroyTexture(this.tfTexture);
    this.volumeTexture = null;
    this.tfTexture = null;
    this.dropGradient();
    this.auxTextures.forEach((a) => this.releaseAux(a));
    this.auxTextures.clear();
    this.auxFor = { scene: null, renderer: null, version: -1 };
  }

  /** After a context/device loss: the old handles belong to the lost context; forget them without calling destroy. */
  forget(): void {
    this.volumeTexture = null; this.volumeSource = null; this.tfTexture = null; this.tfSource = null;
    this.gradient = null; this.gradientSource = null;
    this.auxTextures.clear(); this.auxFor = { scene: null, renderer: null, version: -1 };
  }
}

export interface AuxEntry {
  key: string;
  texture: GpuTexture;
  dimension: '2d' | '3d';
  /** Bound to the generate pass (AuxiliaryTexture.bind). */
  bind: boolean;
  /** The render target a GPU-made texture lives in (destroyed with it). */
  target?: RenderTarget;
}
