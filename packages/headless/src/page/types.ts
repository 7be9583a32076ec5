/**
 * Types shared by the Node side and the in-browser page: what `window.vpt` holds, so
 * tests can write `page.evaluate(() => { const { core, mip } = window.vpt; ... })`
 * with full types.
 */
import type * as CoreModule from '@vpt/core';
import type { BrickingStats, PostStep, Scene, Volume } from '@vpt/core';
import type { SceneDescription, VolumeDescription } from '../scene-description.js';
import type { RendererModules } from '../renderers.generated.js';

/** The part of @vpt/post the page relies on. */
export interface PostModule {
  postChainFromJSON(json: unknown): PostStep[];
  /** The denoise step (typed for tests that run its pass alone). */
  DenoiseStep: new (params?: Record<string, number>) => PostStep;
  [name: string]: unknown;
}

export interface RenderTimings {
  /** Wall-clock ms of the timed iterations plus the render and post passes. */
  totalMs: number;
  iterations: number;
  /** Mean ms per iteration as measured by the render context (GPU synchronised). */
  msPerIteration: number;
  /** Context creation, volume load and upload, kernel compilation (warm-up iteration). */
  setupMs: number;
  /** Set when the time limit stopped the render: `iterations` is then fewer than requested. */
  timeLimited?: boolean;
}

/** Options of `renderDescription` (all optional). */
export interface PageRenderCallOptions {
  baseUrl?: string;
  warmup?: boolean;
  request?: Partial<CoreModule.RequestPolicy>;
  /** Stop the iterations after this many ms (the image then holds those done); default: none. */
  timeLimitMs?: number;
  /** The render context's temporal reuse (RenderContextOptions.temporal); default off. */
  temporal?: boolean;
  /** Run the iterations in batches and call `window.__vptRenderProgress(done, total, ms)` after each. */
  progress?: boolean;
}

export interface BackendSummary {
  kind: 'webgl2' | 'webgpu';
  /** WebGL UNMASKED_RENDERER / WebGPU adapter description. */
  renderer: string;
}

/** What `renderDescription` returns inside the page: images as base64 to cross the DevTools wire. */
export interface PageRenderResult {
  width: number;
  height: number;
  /** Float32 RGBA, top row first, after the post steps named in hdrPostSteps. */
  hdr: string;
  /** The leading post steps that keep linear radiance (e.g. 'denoise') and were applied to `hdr`. */
  hdrPostSteps: string[];
  /** RGBA8, top row first; null when the post chain is empty. */
  ldr: string | null;
  timings: RenderTimings;
  backend: BackendSummary;
  /** GPU memory the context held after rendering (RenderContext.stats.gpuBytes). */
  gpuBytes: { volume: number; gradient: number; auxiliary: number; targets: number; total: number };
  /** The dims of the volume as uploaded (smaller than the scene's when it was downsampled to fit). */
  volumeDims: [number, number, number];
  /** The context's warnings (a downsampled volume, a brick that failed to load). */
  warnings: string[];
  /** What the renderer chose for the scene (RenderContext.stats.renderer, e.g. MCRT auto's estimator and reasons). */
  rendererStats: Record<string, string>;
  /**
   * A bricked volume's residency once settled, before the iterations (RenderContext.stats.bricking):
   * an OME-Zarr volume whose level 0 exceeds the budget streams as bricks. Null: not bricked.
   */
  bricking: BrickingStats | null;
}

/** Also each renderer package's module by renderer name (`window.vpt.mcrt`; RendererModules is generated from the catalog). */
export interface VptPageApi extends RendererModules {
  core: typeof CoreModule;
  /** Each renderer package of core's RENDERER_CATALOG, by renderer name. */
  renderers: Record<string, Record<string, unknown>>;
  /** A renderer of the catalog by name, constructed with its parameter object. */
  createRenderer(name: string, params?: Record<string, unknown>): CoreModule.Renderer;
  post: PostModule;
  renderDescription(desc: SceneDescription, options?: PageRenderCallOptions): Promise<PageRenderResult>;
  buildScene(desc: SceneDescription, baseUrl?: string, request?: Partial<CoreModule.RequestPolicy>): Promise<Scene>;
  loadVolume(desc: VolumeDescription, baseUrl?: string, request?: Partial<CoreModule.RequestPolicy>): Promise<Volume>;
}

declare global {
  interface Window {
    vpt: VptPageApi;
    __vptReady?: boolean;
    /** Set by the Node side (page.exposeFunction) to receive iteration progress. */
    __vptRenderProgress?: (done: number, total: number, ms: number) => void;
    __vptError?: string;
  }
}
