/**
 * In-page helpers for the MCRT browser tests (installed next to the helpers of in-page.ts):
 * `window.mt.run(opts)` renders with the MCRT renderer and returns per-pixel statistics of
 * the single-iteration frames (mean and variance of the mean), so tests can state their
 * tolerance in units of the Monte Carlo error actually measured. Typed TypeScript sent by
 * `page.evaluate`: it may use nothing from this module's scope.
 */
import type { Page } from 'puppeteer-core';
import type { Camera, DirectionalLight, Environment, RenderContext, Scene } from '@vpt/core';
import type { TestContextOptions } from './in-page.js';

export interface McrtRunOptions {
  backend: TestContextOptions['backend'];
  width: number;
  height: number;
  params?: Record<string, unknown>;
  scene: Scene;
  iterations: number;
  /** Read every frame for the per-pixel statistics (default true). */
  frames?: boolean;
}

export interface McrtRunResult {
  /** Per channel (RGBA, top row first), from every frame; null when frames is false. */
  mean: number[] | null;
  se: number[] | null;
  /** The context's own running mean. */
  hdr: number[];
  nonFinite: boolean;
  iterations: number;
  ms: number;
  err: Awaited<ReturnType<RenderContext['estimateError']>>;
  /** The renderer's choices for the scene (RenderContext.stats.renderer: the estimator MCRT chose). */
  renderer: Record<string, string>;
}

export interface CubeSceneOptions {
  albedo: [number, number, number];
  density: number;
  camera?: Camera;
  lights?: DirectionalLight[];
  environment?: Environment;
  seed?: number;
}

export interface McrtInPageHelpers {
  run(opts: McrtRunOptions): Promise<McrtRunResult>;
  /** The same on an existing context (a series of scenes of one kernel variant compiles once); opts.params replace the renderer's. */
  measure(ctx: RenderContext, opts: Omit<McrtRunOptions, 'backend' | 'width' | 'height'>): Promise<McrtRunResult>;
  /** A homogeneous cube of side 1 (8³ voxels of value 1) with constant albedo and opacity 1. */
  cubeScene(o: CubeSceneOptions): Scene;
}

declare global {
  interface Window {
    mt: McrtInPageHelpers;
  }
}

function installMcrtInPage(): void {
  window.mt = {
    async run(opts) {
      const ctx = await window.t.context({
        backend: opts.backend,
        renderer: 'mcrt',
        width: opts.width,
        height: opts.height,
        params: opts.params || {},
      });
      try {
        return await window.mt.measure(ctx, opts);
      } finally {
        ctx.dispose();
      }
    },
    async measure(ctx, opts) {
      const t = window.t;
      if (opts.params)
        (ctx.renderer as unknown as { setParams(p: Record<string, unknown>): void }).setParams(opts.params);
      ctx.setScene(opts.scene);
      const n = ctx.size.width * ctx.size.height * 4;
      const N = opts.iterations;
      const t0 = performance.now();
      let mean: number[] | null = null,
        se: number[] | null = null,
        nonFinite = false;
      if (opts.frames === false) {
        await ctx.renderIterations(N);
      } else {
        ctx.reset();
        const sum = new Float64Array(n),
          sum2 = new Float64Array(n);
        for (let k = 0; k < N; k++) {
          ctx.iterate(1);
          const f = await ctx.readFrame();
          for (let i = 0; i < n; i++) {
            const x = f[i];
            if (!Number.isFinite(x)) nonFinite = true;
            sum[i] += x;
            sum2[i] += x * x;
          }
        }
        mean = new Array<number>(n);
        se = new Array<number>(n);
        for (let i = 0; i < n; i++) {
          const m = sum[i] / N;
          mean[i] = m;
          se[i] = Math.sqrt(Math.max(0, sum2[i] / N - m * m) / Math.max(1, N - 1));
        }
      }
      const ms = performance.now() - t0;
      const hdr = await ctx.readHDR();
      const err = await ctx.estimateError();
      return {
        mean,
        se,
        hdr: Array.from(hdr),
        nonFinite: nonFinite || t.hasNonFinite(hdr),
        iterations: ctx.stats.iterations,
        ms,
        err,
        renderer: ctx.stats.renderer,
      };
    },
    cubeScene(o) {
      const { core } = window.vpt;
      return {
        volume: core.createProceduralVolume('cube', 8),
        transferFunction: { dimensions: '1d', points: [{ value: 0, color: o.albedo, opacity: 1 }] },
        camera: o.camera || { position: [0, 0, 2], target: [0, 0, 0], up: [0, 1, 0], fovy: 0.4 },
        lights: o.lights || [],
        environment: o.environment || { type: 'constant', radiance: [1, 1, 1] },
        densityScale: o.density,
        seed: o.seed ?? 1,
      };
    },
  };
}

export async function installMcrtHelpers(page: Page): Promise<void> {
  await page.evaluate(installMcrtInPage);
}
