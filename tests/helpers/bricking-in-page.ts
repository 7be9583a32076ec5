/**
 * In-page helpers for the bricked-volume tests (`window.bt`): the test volume and one render
 * with or without bricking. Typed TypeScript sent with `page.evaluate`: it may use nothing
 * from this module's scope, only `window.vpt` and `window.t`.
 */
import type { Page } from 'puppeteer-core';
import type { BrickingStats, MultiscaleSource, RenderContext, Scene, Volume, VolumeSampling } from '@vpt/core';
import type { TestContextOptions } from './in-page.js';

export interface BrickRenderOptions {
  backend: TestContextOptions['backend'];
  renderer: string;
  params?: Record<string, unknown>;
  sampling: VolumeSampling;
  bricking: 'off' | 'force' | 'auto';
  brickSize?: number;
  /** Budget for the volume's bricks, exactly (maxGpuBytes = this + what the context counts for the targets and the TF). */
  volumeBytes?: number;
  size: number;
  iterations: number;
  /** The test volume (BrickingInPageHelpers.volume). */
  dims: [number, number, number];
  radius: number;
  /** Bricks written per frame (RenderContextOptions.brickUploadsPerFrame). */
  uploadsPerFrame?: number;
  /** Read every frame and return per-pixel mean and standard error (MCRT). */
  frames?: boolean;
  densityScale?: number;
  seed?: number;
}

export interface BrickRenderResult {
  hdr: number[];
  mean: number[] | null;
  se: number[] | null;
  bricking: BrickingStats | null;
  gpuVolumeBytes: number;
  plainVolumeBytes: number;
  nonFinite: boolean;
  dims: number[];
}

export interface BrickingInPageHelpers {
  context(opts: BrickRenderOptions): Promise<RenderContext>;
  /** The test scene: the volume of opts.dims and opts.radius, a TF that hides the smallest values, a light and a sky. */
  scene(opts: BrickRenderOptions): Scene;
  /** A uint8 volume, spacing [1, 1, 1.25]: a smooth lumpy ball of the given radius (box = 1), exactly 0 outside it (so bricks away from it are constant). */
  volume(dims: [number, number, number], radius: number): Volume;
  render(opts: BrickRenderOptions): Promise<BrickRenderResult>;
  /**
   * Set the scene and run one iteration per frame (yielding between frames so bricks arrive)
   * until the bricks are settled, logging per frame the accumulated iterations, the bricks
   * uploaded so far and the bricks held (slots and constants); then renders `iterations`. Returns the log and the final image.
   */
  /**
   * Render the test volume streamed through RenderContext.setVolumeSource: a source that reads
   * the in-memory levels a millisecond later and fails the level-0 brick read at `failAt` (its
   * region's min corner), with the coarsest level as the scene's stand-in.
   */
  streamed(
    opts: BrickRenderOptions,
    failAt: [number, number, number] | null,
  ): Promise<{ hdr: number[]; warnings: string[]; codes: string[]; bricking: BrickingStats | null; reads: number }>;
  stream(
    opts: BrickRenderOptions,
  ): Promise<{ log: { iterations: number; uploaded: number; held: number }[]; hdr: number[] }>;
}

declare global {
  interface Window {
    bt: BrickingInPageHelpers;
  }
}

function installBrickingInPage(): void {
  window.bt = {
    volume(dims, radius) {
      const { core } = window.vpt;
      const data = new Uint8Array(dims[0] * dims[1] * dims[2]);
      let i = 0;
      for (let z = 0; z < dims[2]; z++)
        for (let y = 0; y < dims[1]; y++)
          for (let x = 0; x < dims[0]; x++, i++) {
            const u = (x + 0.5) / dims[0] - 0.5,
              v = (y + 0.5) / dims[1] - 0.5,
              w = (z + 0.5) / dims[2] - 0.5;
            const r = Math.hypot(u, v, w);
            if (r > radius) continue;
            const lumps = 0.5 + 0.25 * Math.sin(19 * u + 3 * w) * Math.cos(15 * v - 7 * u) + 0.2 * Math.sin(31 * w);
            data[i] = Math.max(1, Math.min(255, Math.round(255 * lumps * (1 - r / radius) ** 0.5)));
          }
      return core.createVolume(dims, 'uint8', data, [1, 1, 1.25]);
    },
    context(o) {
      const W = o.size;
      // What RenderContext counts beside the volume: frame, 2 × accumulation and HDR targets (no post chain) and the TF.
      const r = window.vpt.createRenderer(o.renderer, o.params || {});
      const targets = W * W * 16 * (r.frameFormats.length + 2 * r.accumulationFormats.length + 1) + 256 * 256 * 16;
      return window.t.context({
        backend: o.backend,
        renderer: o.renderer,
        params: o.params,
        width: W,
        height: W,
        sampling: o.sampling,
        bricking: o.bricking,
        brickSize: o.brickSize ?? 16,
        brickUploadsPerFrame: o.uploadsPerFrame,
        ...(o.volumeBytes ? { maxGpuBytes: targets + o.volumeBytes } : {}),
      });
    },
    scene(o) {
      const volume = window.bt.volume(o.dims, o.radius);
      return {
        ...window.t.scene({ volume, sampling: o.sampling, densityScale: o.densityScale ?? 30, seed: o.seed ?? 1 }),
        transferFunction: {
          dimensions: '1d',
          points: [
            { value: 0.02, color: [0.2, 0.5, 0.9], opacity: 0 },
            { value: 0.35, color: [0.9, 0.6, 0.3], opacity: 0.4 },
            { value: 0.8, color: [1, 0.95, 0.9], opacity: 1 },
          ],
        },
        camera: { position: [0.9, 0.5, 1.7], target: [0, 0, 0], up: [0, 1, 0], fovy: 0.62 },
        lights: [{ type: 'directional', direction: [-0.4, 1, 0.3], irradiance: [2, 1.8, 1.5] }],
        environment: { type: 'constant', radiance: [0.3, 0.35, 0.45] },
      };
    },
    async streamed(o, failAt) {
      const { core } = window.vpt;
      const ctx = await window.bt.context(o);
      try {
        const mem = core.inMemoryMultiscaleSource(window.bt.volume(o.dims, o.radius), {
          coarsestSide: o.brickSize ?? 16,
        });
        let reads = 0;
        const source: MultiscaleSource = {
          type: mem.type,
          levels: mem.levels,
          readLevel: (level) => mem.readLevel(level),
          async readRegion(level, min, max) {
            reads++;
            await new Promise((resolve) => setTimeout(resolve, 1));
            if (failAt && level === 0 && min.every((m, a) => m === failAt[a])) throw new Error('HTTP 404 (test)');
            return mem.readRegion(level, min, max);
          },
        };
        const standIn = await source.readLevel(mem.levels.length - 1);
        const warnings: string[] = [];
        const codes: string[] = [];
        ctx.onWarning((w) => {
          warnings.push(w.message);
          codes.push(w.code);
        });
        ctx.setVolumeSource(standIn, source);
        ctx.setScene({ ...window.bt.scene(o), volume: standIn });
        const bricking = await ctx.whenBricksSettled();
        await ctx.renderIterations(o.iterations);
        return { hdr: Array.from(await ctx.readHDR()), warnings, codes, bricking, reads };
      } finally {
        ctx.dispose();
      }
    },
    async stream(o) {
      const ctx = await window.bt.context(o);
      try {
        ctx.setScene(window.bt.scene(o));
        const log: { iterations: number; uploaded: number; held: number }[] = [];
        for (let frame = 0; frame < 1000 && !ctx.stats.bricking?.complete; frame++) {
          ctx.iterate(1);
          const b = ctx.stats.bricking!;
          log.push({ iterations: ctx.stats.iterations, uploaded: b.uploaded, held: b.resident + b.constant });
          await new Promise((resolve) => setTimeout(resolve, 0)); // let requested bricks arrive
        }
        await ctx.renderIterations(o.iterations);
        return { log, hdr: Array.from(await ctx.readHDR()) };
      } finally {
        ctx.dispose();
      }
    },
    async render(o) {
      const t = window.t;
      const W = o.size;
      const ctx = await window.bt.context(o);
      try {
        const volume = window.bt.volume(o.dims, o.radius);
        ctx.setScene({ ...window.bt.scene(o), volume });
        await ctx.whenBricksSettled();
        const n = W * W * 4;
        let mean: number[] | null = null,
          se: number[] | null = null,
          nonFinite = false;
        if (o.frames) {
          ctx.reset();
          const sum = new Float64Array(n),
            sum2 = new Float64Array(n);
          for (let k = 0; k < o.iterations; k++) {
            ctx.iterate(1);
            const f = await ctx.readFrame();
            for (let j = 0; j < n; j++) {
              if (!Number.isFinite(f[j])) nonFinite = true;
              sum[j] += f[j];
              sum2[j] += f[j] * f[j];
            }
          }
          if (ctx.stats.iterations !== o.iterations) throw new Error('accumulation restarted during the measurement');
          mean = Array.from(sum, (s) => s / o.iterations);
          se = Array.from(sum2, (s2, j) =>
            Math.sqrt(Math.max(0, s2 / o.iterations - mean![j] ** 2) / (o.iterations - 1)),
          );
        } else await ctx.renderIterations(o.iterations);
        const hdr = await ctx.readHDR();
        return {
          hdr: Array.from(hdr),
          mean,
          se,
          bricking: ctx.stats.bricking,
          gpuVolumeBytes: ctx.stats.gpuBytes.volume,
          plainVolumeBytes: volume.data.length,
          nonFinite: nonFinite || t.hasNonFinite(hdr),
          dims: ctx.getScene()!.volume.dims,
        };
      } finally {
        ctx.dispose();
      }
    },
  };
}

export async function installBrickingHelpers(page: Page): Promise<void> {
  await page.evaluate(installBrickingInPage);
}
