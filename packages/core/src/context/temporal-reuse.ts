import type { GpuBackend, GpuPass, GpuTexture, RenderTarget, TextureFormat } from '../gpu/backend.js';
import { cameraBasis, dot, sub, type Camera } from '../scene/camera.js';
import { TEMPORAL_RESOLVE, TEMPORAL_UNIFORMS } from '../shaders/temporal.js';
import type { Scene } from '../scene/scene.js';
import { checkKnownKeys, checkNumber, checkObject, checkOneOf } from '../validation/checks.js';

// RenderContext imports this module only when temporal reuse is turned on (a lazy chunk in the
// viewer's bundle): the options' checks, the scene comparison and the resolve pass with its targets.

/**
 * Temporal reuse (docs/architecture.md, "Temporal reuse"): on a camera change the previous
 * view's image is reprojected into the new one through the depth guide and blended with the
 * new samples as history of a few samples' weight that fades as they accumulate.
 */
export interface TemporalOptions {
  /** The history counts as at most this many samples (SVGF's clamped history length; default 12). */
  maxHistory?: number;
  /** A history tap is kept when its depth differs from the new point's by at most this fraction of it (default 0.1). */
  depthTolerance?: number;
  /** ... and the cosine between the two normal guides is at least this (default 0: opposite normals are rejected). */
  normalCos?: number;
  /** The history's weight falls linearly to 0 at this many new samples (default 64), so the converged image is the plain estimate. */
  fadeSamples?: number;
  /** The history's weight decays as exp(−θ / viewDecay) with the view change θ in radians (default 1). */
  viewDecay?: number;
  /**
   * How the history image is resampled at the reprojected point: 'catmull-rom' (default: the
   * 4×4 bicubic taps where all four bilinear taps pass the consistency tests, an outer tap that
   * fails replaced by its nearest inner one, the result clamped to the four's range) or
   * 'bilinear' (the four taps alone, which blurs the history a little at every camera update).
   */
  historyFilter?: 'catmull-rom' | 'bilinear';
}

export const TEMPORAL_DEFAULTS: Required<TemporalOptions> = {
  maxHistory: 12,
  depthTolerance: 0.1,
  normalCos: 0,
  fadeSamples: 64,
  viewDecay: 1,
  historyFilter: 'catmull-rom',
};

export const HISTORY_FILTERS = ['catmull-rom', 'bilinear'] as const;

/** Checks temporal options (VptError 'invalid-scene' naming the field) and fills in the defaults; null for false. */
export function checkTemporalOptions(x: unknown): Required<TemporalOptions> | null {
  if (x === undefined || x === false) return null;
  if (x === true) return { ...TEMPORAL_DEFAULTS };
  const o = checkObject('temporal', x);
  checkKnownKeys('temporal', o, Object.keys(TEMPORAL_DEFAULTS));
  const get = (k: Exclude<keyof TemporalOptions, 'historyFilter'>, rule: Parameters<typeof checkNumber>[2]) =>
    o[k] === undefined ? TEMPORAL_DEFAULTS[k] : checkNumber(`temporal.${k}`, o[k], rule);
  return {
    maxHistory: get('maxHistory', { min: 0, max: 1024 }),
    depthTolerance: get('depthTolerance', { min: 0, max: 10 }),
    normalCos: get('normalCos', { min: -1, max: 1 }),
    fadeSamples: get('fadeSamples', { min: 1, max: 1e6, integer: true }),
    viewDecay: get('viewDecay', { min: 1e-6, max: 1e6, exclusiveMin: true }),
    historyFilter:
      o.historyFilter === undefined
        ? TEMPORAL_DEFAULTS.historyFilter
        : checkOneOf('temporal.historyFilter', o.historyFilter, HISTORY_FILTERS),
  };
}

/** Whether two scenes differ in the camera alone (the volume by identity, everything else by value). */
export function sameSceneButCamera(a: Scene, b: Scene): boolean {
  if (a.volume !== b.volume) return false;
  const keys = new Set([...Object.keys(a), ...Object.keys(b)]);
  for (const k of keys) {
    if (k === 'camera' || k === 'volume') continue;
    if (!sameValue((a as unknown as Record<string, unknown>)[k], (b as unknown as Record<string, unknown>)[k]))
      return false;
  }
  return true;
}

function sameValue(a: unknown, b: unknown): boolean {
  if (a === b) return true;
  if (typeof a !== 'object' || typeof b !== 'object' || a === null || b === null) return false;
  if (ArrayBuffer.isView(a) || ArrayBuffer.isView(b)) {
    if (!ArrayBuffer.isView(a) || !ArrayBuffer.isView(b) || a.constructor !== b.constructor) return false;
    const x = a as unknown as ArrayLike<number>,
      y = b as unknown as ArrayLike<number>;
    if (x.length !== y.length) return false;
    for (let i = 0; i < x.length; i++) if (x[i] !== y[i] && !(Number.isNaN(x[i]) && Number.isNaN(y[i]))) return false;
    return true;
  }
  if (Array.isArray(a) !== Array.isArray(b)) return false;
  const ka = Object.keys(a),
    kb = Object.keys(b);
  if (ka.length !== kb.length) return false;
  for (const k of ka)
    if (!sameValue((a as Record<string, unknown>)[k], (b as Record<string, unknown>)[k])) return false;
  return true;
}

/**
 * The view change between two cameras in radians: the angle between their view directions
 * plus the eye's displacement over its distance to the new target (an orbit by φ gives ≈ 2φ).
 */
export function viewChange(a: Camera, b: Camera): number {
  const fa = cameraBasis(a).forward,
    fb = cameraBasis(b).forward;
  const angle = Math.acos(Math.min(1, Math.max(-1, dot(fa, fb))));
  const d = sub(b.position, a.position);
  const dist = Math.hypot(...sub(b.target, b.position));
  return angle + Math.hypot(...d) / Math.max(dist, 1e-6);
}

const FORMATS: TextureFormat[] = ['rgba32float', 'rgba32float', 'rgba32float'];

/** The guide textures the resolve pass reads (GuideBuffers.textures()). */
export interface TemporalGuides {
  guideNormalDepth: GpuTexture;
  guideAlbedo: GpuTexture;
}

/**
 * The resolve pass and its two targets: `out` (this view's image, guide and state) and
 * `history` (the previous view's, at that view's size), with the camera it was made with.
 */
export class TemporalReuse {
  private pass: GpuPass | null = null;
  private out: RenderTarget | null = null;
  private history: RenderTarget | null = null;
  // The history before the current one, kept for the next resolve to draw into (see keep()); only
  // while there is no out, so the targets stay two sets, as before.
  private spare: RenderTarget | null = null;
  private historyCamera: Camera | null = null;
  private historyAspect = 1;
  private base = 0;

  constructor(
    private readonly backend: GpuBackend,
    readonly options: Required<TemporalOptions>,
    /** options.maxHistory was given (not the default), so it overrides a renderer's own. */
    private readonly ownMaxHistory = false,
  ) {}

  /** Whether a scene change is a camera change alone (sameSceneButCamera), which keeps the history. */
  cameraOnly(a: Scene, b: Scene): boolean {
    return sameSceneButCamera(a, b);
  }

  /** Whether a history is kept for the next images. */
  get hasHistory(): boolean {
    return this.history !== null;
  }

  /**
   * The view changes (camera or size) after `samples` samples of it, and the current resolve
   * (made with `camera` at `aspect`) becomes the history. Without a resolve since the last
   * change the history stays.
   */
  keep(camera: Camera, aspect: number, samples: number): void {
    this.base = (this.base + samples) >>> 0;
    if (!this.out) return;
    // The old history's targets become the next resolve's (same size in motion): no texture is
    // made or freed per camera update. There is no spare now: the resolve that made `out` took it.
    this.spare = this.history;
    this.history = this.out;
    this.out = null;
    this.historyCamera = { ...camera };
    this.historyAspect = aspect;
  }

  /** The image changed otherwise (scene, renderer, parameters): no history. */
  invalidate(): void {
    this.destroy();
  }

  /**
   * Where the new view's samples start in the sample sequence (the uniform u.sampleBase): the
   * samples of every view since the history was last dropped. Each view then continues the
   * sequence the history ended at instead of restarting it: with the streams restarted alike a
   * small move renders nearly the same error pattern again (EAM's jitter and march offset are
   * all its randomness, and blue noise repeats them exactly), and the mean of the history and
   * the new samples keeps the error of one view's. Continued, the PCG streams are new numbers
   * and blue noise's rank-1 sequence runs on at each pixel, so where the view moved by less
   * than a pixel the history and the new samples together are one low-discrepancy run
   * (docs/benchmarks.md, "Orbit: the history continues the sample sequence"). 0 with no move, so a
   * still image keeps its bits.
   */
  get sampleBase(): number {
    return this.base;
  }

  /** The history weight's factor at this view after `samples` new samples. */
  historyScale(camera: Camera, samples: number): number {
    if (!this.history || !this.historyCamera) return 0;
    const o = this.options;
    const fade = Math.max(0, 1 - samples / o.fadeSamples);
    return Math.exp(-viewChange(this.historyCamera, camera) / o.viewDecay) * fade;
  }

  /**
   * Draws the resolve of `current` (the renderer's HDR mean of `samples` samples at `camera`;
   * `normalTest` false leaves out the normal test and weighs a cut footprint's history by the
   * share that passed; `rendererMaxHistory` replaces the default maxHistory) and returns the image to show; out1/out2 keep its guide and state for the next view.
   */
  resolve(
    current: GpuTexture,
    guides: TemporalGuides,
    camera: Camera,
    width: number,
    height: number,
    samples: number,
    normalTest = true,
    rendererMaxHistory?: number,
  ): GpuTexture {
    if (this.out && (this.out.width !== width || this.out.height !== height)) {
      this.backend.destroyRenderTarget(this.out);
      this.out = null;
    }
    if (!this.out && this.spare) {
      if (this.spare.width === width && this.spare.height === height) this.out = this.spare;
      else this.backend.destroyRenderTarget(this.spare);
      this.spare = null;
    }
    this.out ??= this.backend.createRenderTarget(width, height, FORMATS, 'temporal resolve');
    this.pass ??= this.backend.createPass({
      label: 'temporal.resolve',
      glsl: TEMPORAL_RESOLVE.glsl,
      wgsl: TEMPORAL_RESOLVE.wgsl,
      uniforms: TEMPORAL_UNIFORMS,
      textures: [
        { name: 'current', dimension: '2d' },
        { name: 'guideNormalDepth', dimension: '2d' },
        { name: 'guideAlbedo', dimension: '2d' },
        { name: 'historyImage', dimension: '2d' },
        { name: 'historyGuide', dimension: '2d' },
        { name: 'historyState', dimension: '2d' },
      ],
      outputs: FORMATS,
    });
    const scale = this.historyScale(camera, samples);
    const nb = cameraBasis(camera);
    const old = this.historyCamera ?? camera;
    const ob = cameraBasis(old);
    // Without a history the pass reads none (historyScale 0); the inputs stand in for its bindings.
    const h = this.history?.textures ?? [current, guides.guideNormalDepth, guides.guideAlbedo];
    this.backend.draw(this.pass, {
      uniforms: TEMPORAL_UNIFORMS.pack({
        newPosition: camera.position,
        newTanHalfFovy: Math.tan(camera.fovy / 2),
        newForward: nb.forward,
        newAspect: width / height,
        newRight: nb.right,
        samples,
        newUp: nb.up,
        historyScale: scale,
        oldPosition: old.position,
        oldTanHalfFovy: Math.tan(old.fovy / 2),
        oldForward: ob.forward,
        oldAspect: this.historyCamera ? this.historyAspect : width / height,
        oldRight: ob.right,
        maxHistory:
          this.ownMaxHistory || rendererMaxHistory === undefined ? this.options.maxHistory : rendererMaxHistory,
        oldUp: ob.up,
        depthTolerance: this.options.depthTolerance,
        // −2: every cosine passes (the renderer's normal guide is no surface's, Renderer.temporalNormalTest).
        normalCos: normalTest ? this.options.normalCos : -2,
        historyFilter: this.options.historyFilter === 'catmull-rom' ? 1 : 0,
        // Without the normal test a tap fails only at a depth or hit/miss edge, and a cut footprint's
        // passed taps are a neighbour's: the history then counts by the share that passed. With it
        // (ISO's surface normals) a cut footprint is renormalised as in SVGF.
        footprintWeight: normalTest ? 0 : 1,
      }),
      textures: {
        current,
        guideNormalDepth: guides.guideNormalDepth,
        guideAlbedo: guides.guideAlbedo,
        historyImage: h[0],
        historyGuide: h[1],
        historyState: h[2],
      },
      target: this.out,
    });
    return this.out.textures[0];
  }

  /** The last resolve's outputs (image, guide, state), or null. */
  get output(): RenderTarget | null {
    return this.out;
  }

  get targets(): RenderTarget[] {
    return [this.out, this.history, this.spare].filter((t): t is RenderTarget => t !== null);
  }

  destroy(): void {
    this.targets.forEach((t) => this.backend.destroyRenderTarget(t));
    this.out = null;
    this.history = null;
    this.spare = null;
    this.historyCamera = null;
    this.base = 0;
  }

  /** After a context loss: the targets are gone with it. */
  forget(): void {
    this.pass = null;
    this.out = null;
    this.history = null;
    this.spare = null;
    this.historyCamera = null;
    this.base = 0;
  }
}
