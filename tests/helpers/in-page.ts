/**
 * Helpers that run inside the headless page, installed once per page with
 * `page.evaluate(installInPageHelpers)` so each test's evaluate body stays short. Typed
 * TypeScript: puppeteer sends the function's compiled source, so it may use nothing from
 * this module's scope, only `window.vpt` (the headless page's API).
 */
import type {
  RenderContext,
  Scene,
  Volume,
  VoxelType,
  Camera,
  Environment,
  TransferFunction,
  VolumeSampling,
} from '@vpt/core';

export interface TestContextOptions {
  backend: 'webgl2' | 'webgpu' | 'auto';
  /** A renderer of core's RENDERER_CATALOG (default 'eam'). */
  renderer?: string;
  width: number;
  height: number;
  params?: Record<string, unknown>;
  /** A post chain as JSON (none when omitted). */
  post?: unknown;
  /** 'exact' for tests that compare with CPU twins or across backends bit for bit. */
  sampling?: VolumeSampling;
  /** The GPU memory budget in bytes (RenderContextOptions.maxGpuBytes). */
  maxGpuBytes?: number;
  /** A canvas to present to (RenderContextOptions.canvas); none when omitted. */
  canvas?: HTMLCanvasElement;
  /** RenderContextOptions.bricking / brickSize / brickUploadsPerFrame. */
  bricking?: 'off' | 'auto' | 'force';
  brickSize?: number;
  brickUploadsPerFrame?: number;
}

/** The shared test scene: a ramp TF, the default camera, no lights, a black sky, density 1, seed 1. */
export interface TestSceneSpec {
  volume: Volume;
  transferFunction?: TransferFunction;
  camera?: Camera;
  environment?: Environment;
  densityScale?: number;
  seed?: number;
  sampling?: VolumeSampling;
}

export interface InPageHelpers {
  context(opts: TestContextOptions): Promise<RenderContext>;
  scene(spec: TestSceneSpec): Scene;
  /** `camera` orbited by `angle` radians about the vertical (y) axis through its target. */
  orbit(camera: Camera, angle: number): Camera;
  /** A 1D transfer function from [value, color, opacity] stops (Node-side twin: `tf1d` in test-scene.ts). */
  tf1d(...stops: [value: number, color: [number, number, number], opacity: number][]): TransferFunction;
  loadRaw(url: string, dims: [number, number, number], type: VoxelType): Promise<Volume>;
  /** Render `iterations` more, read the HDR image back (as numbers, for the trip to Node) and dispose of the context. */
  finalHDR(ctx: RenderContext, iterations: number): Promise<number[]>;
  /** How many 32-bit words differ (−1 when the lengths differ). */
  sameBits(a: ArrayBufferView, b: ArrayBufferView): number;
  hasNonFinite(a: ArrayLike<number>): boolean;
}

declare global {
  interface Window {
    t: InPageHelpers;
  }
}

export function installInPageHelpers(): void {
  window.t = {
    async context(opts) {
      const { core, post } = window.vpt;
      const renderer = window.vpt.createRenderer(opts.renderer || 'eam', opts.params || {});
      const steps = opts.post ? post.postChainFromJSON(opts.post) : [];
      // sampling: 'exact' for tests that compare with CPU twins or across backends bit for bit.
      return core.RenderContext.create({
        backend: opts.backend,
        width: opts.width,
        height: opts.height,
        renderer,
        post: steps,
        sampling: opts.sampling,
        maxGpuBytes: opts.maxGpuBytes,
        canvas: opts.canvas,
        bricking: opts.bricking,
        brickSize: opts.brickSize,
        brickUploadsPerFrame: opts.brickUploadsPerFrame,
      });
    },
    orbit(c, a) {
      const [x, z] = [c.position[0] - c.target[0], c.position[2] - c.target[2]];
      return {
        ...c,
        position: [
          c.target[0] + x * Math.cos(a) + z * Math.sin(a),
          c.position[1],
          c.target[2] - x * Math.sin(a) + z * Math.cos(a),
        ],
      };
    },
    scene(spec) {
      const { core } = window.vpt;
      return {
        volume: spec.volume,
        transferFunction: spec.transferFunction || core.rampTransferFunction(),
        camera: spec.camera || core.defaultCamera(),
        lights: [],
        environment: spec.environment || { type: 'constant', radiance: [0, 0, 0] },
        densityScale: spec.densityScale ?? 1,
        seed: spec.seed ?? 1,
        ...(spec.sampling ? { sampling: spec.sampling } : {}),
      };
    },
    tf1d(...stops) {
      return { dimensions: '1d', points: stops.map(([value, color, opacity]) => ({ value, color, opacity })) };
    },
    // The headless page's own raw reader (one place reads raw files in the page).
    loadRaw(url, dims, type) {
      return window.vpt.loadVolume({ raw: url, dims, type });
    },
    async finalHDR(ctx, iterations) {
      await ctx.renderIterations(iterations);
      const hdr = await ctx.readHDR();
      ctx.dispose();
      return Array.from(hdr);
    },
    sameBits(a, b) {
      const x = new Uint32Array(a.buffer, a.byteOffset, a.byteLength / 4),
        y = new Uint32Array(b.buffer, b.byteOffset, b.byteLength / 4);
      if (x.length !== y.length) return -1;
      let diff = 0;
      for (let i = 0; i < x.length; i++) if (x[i] !== y[i]) diff++;
      return diff;
    },
    hasNonFinite(a) {
      for (let i = 0; i < a.length; i++) if (!Number.isFinite(a[i])) return true;
      return false;
    },
  };
}
