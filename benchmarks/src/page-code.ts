/**
 * Code installed into the headless page as `window.bench` (it uses the page's `window.vpt`:
 * core, post, createRenderer, loadVolume). Images stay in the page: only curves and timings
 * travel back to Node.
 * Timing: every measured span ends with backend.finish() (a blocking 1-texel readback on
 * WebGL 2 — gl.finish() does not wait in Chrome — and onSubmittedWorkDone on WebGPU), and
 * read-backs for error measurement are excluded from the clock.
 * An ES module of the benchmarks' build (dist/page-code.js), which the page imports from
 * where run.ts mounts dist/ (installInPage): it may import modules that run in a browser
 * (the anchor scene) and types, nothing that needs Node.
 */
import type { VptPageApi } from '@vpt/headless';
import type { RendererConfig, SceneSpec } from './configs.js';
import { anchorVolume as anchorVoxels } from './vpt-side/anchor-scene.js';

// Core's types as the page API exposes them (this package depends on @vpt/headless only).
type Volume = Awaited<ReturnType<VptPageApi['loadVolume']>>;
type Scene = Awaited<ReturnType<VptPageApi['buildScene']>>;
type Renderer = ReturnType<VptPageApi['createRenderer']>;
type RenderContext = Awaited<ReturnType<VptPageApi['core']['RenderContext']['create']>>;
type VoxelType = Parameters<VptPageApi['core']['createVolume']>[1];

type Vec3 = [number, number, number];
type RawSpec = Extract<SceneSpec['volume'], { kind: 'raw' }>;
/** A renderer configuration on one backend, with the context's volume sampling and GPU memory budget. */
type PageConfig = RendererConfig & { backend: 'webgl2' | 'webgpu'; sampling?: 'fast' | 'exact'; maxGpuBytes?: number };
interface Reference {
  hdr: Float32Array;
  ldr: Uint8Array;
  peak: number;
  noiseMse: number;
  info: Record<string, unknown>;
}
interface GpuTimer {
  kind: string;
  begin(): void;
  end(): void;
  result(): Promise<number | null>;
  dispose(): void;
}

declare const window: Window & { vpt: VptPageApi };

export function installBenchPage(): void {
  const vpt = window.vpt;
  const refs = new Map<string, Reference>();
  const costContexts: RenderContext[] = [];

  // A deterministic 128³-style test cloud: Gaussian blobs at positions from a fixed-seed
  // LCG, modulated by hashed value noise, about half of the box empty.
  function cloudVolume(size: number, seed = 1234): Volume {
    let s = seed >>> 0;
    const rnd = () => (s = (Math.imul(s, 1664525) + 1013904223) >>> 0) / 4294967296;
    const blobs = Array.from({ length: 12 }, () => ({
      c: [rnd() - 0.5, rnd() - 0.5, rnd() - 0.5].map((v) => v * 0.6),
      r: 0.06 + 0.12 * rnd(),
      w: 0.5 + 0.5 * rnd(),
    }));
    const hash = (x: number, y: number, z: number) => {
      let h = Math.imul(x, 374761393) ^ Math.imul(y, 668265263) ^ Math.imul(z, 2147483647) ^ seed;
      h = Math.imul(h ^ (h >>> 13), 1274126177);
      return ((h ^ (h >>> 16)) >>> 0) / 4294967296;
    };
    const data = new Float32Array(size * size * size);
    for (let z = 0; z < size; z++)
      for (let y = 0; y < size; y++)
        for (let x = 0; x < size; x++) {
          const p = [(x + 0.5) / size - 0.5, (y + 0.5) / size - 0.5, (z + 0.5) / size - 0.5];
          let v = 0;
          for (const b of blobs) {
            const d2 = (p[0] - b.c[0]) ** 2 + (p[1] - b.c[1]) ** 2 + (p[2] - b.c[2]) ** 2;
            v += b.w * Math.exp(-d2 / (2 * b.r * b.r));
          }
          const n = hash(x >> 2, y >> 2, z >> 2);
          v = v * (0.75 + 0.5 * n);
          data[x + size * (y + size * z)] = v < 0.15 ? 0 : Math.min(1, v);
        }
    const vol = vpt.core.createVolume([size, size, size], 'float32', data);
    vol.valueRange = [0, 1];
    vol.name = 'cloud-' + size;
    return vol;
  }

  // A solid ball of the given radius (box units): everything outside it is empty space.
  function ballVolume(size: number, radius: number): Volume {
    const data = new Float32Array(size * size * size);
    for (let z = 0; z < size; z++)
      for (let y = 0; y < size; y++)
        for (let x = 0; x < size; x++) {
          const r = Math.hypot((x + 0.5) / size - 0.5, (y + 0.5) / size - 0.5, (z + 0.5) / size - 0.5);
          data[x + size * (y + size * z)] = r < radius ? 1 : 0;
        }
    const vol = vpt.core.createVolume([size, size, size], 'float32', data);
    vol.valueRange = [0, 1];
    return vol;
  }

  // The VPT anchor scene's volume (docs/benchmarks.md, "Side by side with VPT"): the
  // side-by-side suite's own voxels (vpt-side/anchor-scene.ts), as a uint8 volume.
  function anchorVolume(size: number): Volume {
    const vol = vpt.core.createVolume([size, size, size], 'uint8', anchorVoxels(size));
    vol.name = 'vpt-anchor-' + size;
    return vol;
  }

  const volumes = new Map<string, Volume>();
  const BUNDLED_HEAD: RawSpec = {
    kind: 'raw',
    url: '/data/mri_head_volpack_brainsmall_128x128x84_uint8.raw',
    dims: [128, 128, 84],
    type: 'uint8',
    spacing: [1, 1, 1],
  };

  // A bundled or fetched dataset: raw voxels (x fastest) as its sidecar describes them, read
  // by the headless page's one raw reader.
  async function rawVolume(spec: RawSpec): Promise<Volume> {
    return vpt.loadVolume({
      raw: spec.url,
      dims: spec.dims as Vec3,
      type: spec.type as VoxelType,
      spacing: spec.spacing as Vec3,
      valueRange: spec.valueRange as [number, number] | undefined,
    });
  }

  async function volume(spec: SceneSpec['volume']): Promise<Volume> {
    const key = JSON.stringify(spec);
    if (!volumes.has(key)) {
      volumes.set(
        key,
        spec.kind === 'raw'
          ? await rawVolume(spec)
          : spec.kind === 'head'
            ? await rawVolume(BUNDLED_HEAD)
            : spec.kind === 'cloud'
              ? cloudVolume(spec.size ?? 128)
              : spec.kind === 'ball'
                ? ballVolume(spec.size ?? 64, spec.radius ?? 0.25)
                : spec.kind === 'anchor'
                  ? anchorVolume(spec.size ?? 128)
                  : vpt.core.createProceduralVolume(spec.kind, spec.size),
      );
    }
    return volumes.get(key)!;
  }

  // A lat-long map's texels cross from Node as a plain array: the scene wants a Float32Array.
  function environment(spec: unknown): Scene['environment'] {
    const env = (spec || { type: 'constant', radiance: [1, 1, 1] }) as Scene['environment'];
    return env.type === 'latlong' && Array.isArray(env.data) ? { ...env, data: new Float32Array(env.data) } : env;
  }

  async function scene(spec: SceneSpec): Promise<Scene> {
    const vol = await volume(spec.volume);
    return {
      volume: vol,
      transferFunction: spec.transferFunction as Scene['transferFunction'],
      camera: spec.camera as Scene['camera'],
      lights: (spec.lights || []) as Scene['lights'],
      environment: environment(spec.environment),
      densityScale: spec.densityScale,
      seed: spec.seed ?? 1,
    };
  }

  function renderer(config: PageConfig): Renderer {
    if (!vpt.renderers[config.renderer])
      throw new Error('renderer ' + config.renderer + ' is not available in this build');
    return vpt.createRenderer(config.renderer, config.params || {});
  }

  async function context(config: PageConfig, width: number, height: number, denoise = false): Promise<RenderContext> {
    const chain = [{ type: 'tonemap', operator: 'aces' }, { type: 'srgb' }];
    return vpt.core.RenderContext.create({
      backend: config.backend,
      width,
      height,
      renderer: renderer(config),
      // With `denoise`, the denoise step first (the denoise suite reads the HDR image after it).
      post: vpt.post.postChainFromJSON(denoise ? [{ type: 'denoise' }, ...chain] : chain),
      sampling: config.sampling,
      maxGpuBytes: config.maxGpuBytes,
    });
  }

  /** The plain scene the memory measurements render: ramp TF, default camera, no lights, a white sky. */
  function rampScene(volume: Volume, densityScale: number): Scene {
    return {
      volume,
      transferFunction: vpt.core.rampTransferFunction(),
      camera: vpt.core.defaultCamera(),
      lights: [],
      environment: { type: 'constant', radiance: [1, 1, 1] },
      densityScale,
      seed: 1,
    };
  }

  function errors(hdr: Float32Array, ldr: Uint8Array, ref: Reference) {
    let se = 0,
      seL = 0,
      n = 0,
      nonFinite = 0;
    for (let i = 0; i < hdr.length; i += 4)
      for (let c = 0; c < 3; c++) {
        const d = hdr[i + c] - ref.hdr[i + c];
        if (!Number.isFinite(hdr[i + c])) nonFinite++;
        se += d * d;
        const dl = ldr[i + c] - ref.ldr[i + c];
        seL += dl * dl;
        n++;
      }
    // E[(x - ref)^2] = MSE(x) + Var(ref): subtract the reference's own noise, estimated from
    // its even/odd half-accumulations, so a reference only a few times longer than the curve
    // does not flatten it (HDR only: the tone-mapped error is not additive).
    const rawMse = se / n;
    const rmse = Math.sqrt(Math.max(rawMse - ref.noiseMse, rawMse * 1e-6)),
      rmseLdr = Math.sqrt(seL / n);
    return {
      rmse,
      rmseRaw: Math.sqrt(rawMse),
      psnr: 20 * Math.log10(ref.peak / Math.max(rmse, 1e-12)),
      rmseLdr,
      psnrLdr: 20 * Math.log10(255 / Math.max(rmseLdr, 1e-12)),
      nonFinite,
    };
  }

  /**
   * A GPU timer around a batch of work, or null where none is offered.
   * WebGL 2: EXT_disjoint_timer_query_webgl2 TIME_ELAPSED on the backend's own context (a
   * canvas returns the context it already has); a disjoint event discards the sample.
   * WebGPU: 'timestamp-query' (the backend requests it where the adapter has it): an empty
   * compute pass writes a timestamp before the batch and another after it; the queue runs
   * submissions in order, so the difference spans the batch.
   */
  // `any`: reaches into the backends' own GL context / GPU device.
  function gpuTimer(backend: any): GpuTimer | null {
    if (backend.kind === 'webgl2') {
      const gl = backend.canvas.getContext('webgl2') as WebGL2RenderingContext | null;
      const ext = gl && gl.getExtension('EXT_disjoint_timer_query_webgl2');
      if (!ext) return null;
      let query: WebGLQuery | null = null;
      return {
        kind: 'EXT_disjoint_timer_query_webgl2',
        begin() {
          query = gl.createQuery();
          gl.beginQuery(ext.TIME_ELAPSED_EXT, query!);
        },
        end() {
          gl.endQuery(ext.TIME_ELAPSED_EXT);
        },
        async result() {
          const q = query!;
          query = null;
          for (let tries = 0; tries < 2000 && !gl.getQueryParameter(q, gl.QUERY_RESULT_AVAILABLE); tries++)
            await new Promise((r) => setTimeout(r, 1));
          const ok = gl.getQueryParameter(q, gl.QUERY_RESULT_AVAILABLE) && !gl.getParameter(ext.GPU_DISJOINT_EXT);
          const ns = ok ? gl.getQueryParameter(q, gl.QUERY_RESULT) : null;
          gl.deleteQuery(q);
          return ns === null ? null : ns / 1e6;
        },
        dispose() {},
      };
    }
    const device = backend.device as GPUDevice | undefined;
    if (!device || !device.features.has('timestamp-query')) return null;
    const querySet = device.createQuerySet({ type: 'timestamp', count: 2 });
    const resolve = device.createBuffer({ size: 16, usage: GPUBufferUsage.QUERY_RESOLVE | GPUBufferUsage.COPY_SRC });
    const read = device.createBuffer({ size: 16, usage: GPUBufferUsage.MAP_READ | GPUBufferUsage.COPY_DST });
    const stamp = (writes: Omit<GPUComputePassTimestampWrites, 'querySet'>) => {
      const enc = device.createCommandEncoder();
      enc.beginComputePass({ timestampWrites: { querySet, ...writes } }).end();
      return enc;
    };
    return {
      kind: 'timestamp-query',
      begin() {
        device.queue.submit([stamp({ beginningOfPassWriteIndex: 0 }).finish()]);
      },
      end() {
        const enc = stamp({ endOfPassWriteIndex: 1 });
        enc.resolveQuerySet(querySet, 0, 2, resolve, 0);
        enc.copyBufferToBuffer(resolve, 0, read, 0, 16);
        device.queue.submit([enc.finish()]);
      },
      async result() {
        await read.mapAsync(GPUMapMode.READ);
        const [t0, t1] = new BigUint64Array(read.getMappedRange().slice(0));
        read.unmap();
        return t1 > t0 ? Number(t1 - t0) / 1e6 : null;
      },
      dispose() {
        querySet.destroy();
        resolve.destroy();
        read.destroy();
      },
    };
  }

  (window as unknown as { bench: unknown }).bench = {
    /** Render and keep a converged reference (HDR peak = max over RGB, for PSNR). */
    async reference(
      key: string,
      config: PageConfig,
      sceneSpec: SceneSpec,
      width: number,
      height: number,
      iterations: number,
    ) {
      if (refs.has(key)) return refs.get(key)!.info;
      const ctx = await context(config, width, height);
      ctx.setScene(await scene({ ...sceneSpec, seed: 987654 }));
      const t0 = performance.now();
      const chunk = 32;
      ctx.reset();
      for (let done = 0; done < iterations; done += chunk) {
        ctx.iterate(Math.min(chunk, iterations - done));
        await ctx.backend.finish();
      }
      const hdr = await ctx.readHDR(),
        ldr = await ctx.readLDR();
      let peak = 0;
      for (let i = 0; i < hdr.length; i += 4) peak = Math.max(peak, hdr[i], hdr[i + 1], hdr[i + 2]);
      const est = await ctx.estimateError();
      const noiseMse = est ? est.rmse * est.rmse : 0;
      const info = {
        iterations,
        ms: performance.now() - t0,
        peak,
        backend: ctx.backend.kind,
        rmse: est ? est.rmse : null,
      };
      refs.set(key, { hdr, ldr, peak, noiseMse, info });
      ctx.dispose();
      return info;
    },

    /** HDR PSNR of one stored reference against another (peak = the second's maximum): the bias between two converged images. */
    referencePsnr(key: string, againstKey: string) {
      const a = refs.get(key)!,
        b = refs.get(againstKey)!;
      let se = 0;
      for (let i = 0; i < a.hdr.length; i += 4) for (let c = 0; c < 3; c++) se += (a.hdr[i + c] - b.hdr[i + c]) ** 2;
      return 20 * Math.log10(b.peak / Math.max(Math.sqrt(se / ((3 * a.hdr.length) / 4)), 1e-12));
    },

    /** The renderer's own choices for a scene (RenderContext.stats.renderer: MCRT's estimator). */
    async rendererStats(config: PageConfig, sceneSpec: SceneSpec) {
      const ctx = await context(config, 8, 8);
      ctx.setScene(await scene(sceneSpec));
      await ctx.renderIterations(1); // the renderer chooses when the context first builds its passes
      const stats = ctx.stats.renderer;
      ctx.dispose();
      return stats;
    },

    /**
     * ms per iteration of several configurations on one scene, measured round-robin from
     * Node (error-vs-time.ts's interleavedCosts): costOpen makes a context per configuration
     * and compiles its kernels, costBatch runs one synchronised batch of one of them and
     * returns its wall ms (Node reads the GPU process's CPU time around it), costClose
     * disposes of them.
     */
    async costOpen(configs: PageConfig[], sceneSpec: SceneSpec, width: number, height: number) {
      const sc = await scene(sceneSpec);
      for (const c of configs) {
        const ctx = await context(c, width, height);
        ctx.setScene(sc);
        await ctx.renderIterations(1);
        costContexts.push(ctx);
      }
    },
    async costBatch(index: number, iterations: number) {
      const ctx = costContexts[index];
      await ctx.backend.finish();
      const t0 = performance.now();
      ctx.iterate(iterations);
      await ctx.backend.finish();
      return performance.now() - t0;
    },
    costClose() {
      for (const ctx of costContexts.splice(0)) ctx.dispose();
    },

    /**
     * Error against wall-clock time with or without the denoise step (denoise suite): like
     * errorCurve, but the clock also counts rendering the image (render pass and post chain,
     * the denoiser included), and the error is that of the HDR image after the denoiser.
     */
    async denoiseCurve(
      config: PageConfig,
      sceneSpec: SceneSpec,
      width: number,
      height: number,
      refKey: string,
      checkpoints: number[],
      denoise: boolean,
    ) {
      const ref = refs.get(refKey)!;
      const ctx = await context(config, width, height, denoise);
      ctx.setScene(await scene(sceneSpec));
      await ctx.renderIterations(1); // compile every kernel variant outside the clock
      ctx.reset();
      const points: Record<string, number | null>[] = [];
      let clock = 0,
        done = 0;
      for (const next of checkpoints) {
        const t0 = performance.now();
        ctx.iterate(next - done);
        ctx.renderImage();
        await ctx.backend.finish();
        clock += performance.now() - t0;
        done = next;
        const hdr = await ctx.readHDR({ afterPost: denoise }),
          ldr = await ctx.readLDR();
        points.push({ iterations: done, ms: clock, ...errors(hdr, ldr, ref) });
      }
      ctx.dispose();
      return points;
    },

    /**
     * The bias the denoiser leaves at convergence: the reference's own samples (same seed and
     * iterations as `reference`) through the denoiser, against the plain reference: PSNR (HDR,
     * peak = the reference's max) and the relative RMSE. That difference is the bias plus the
     * noise the filter removed, so it bounds the bias from above; `noiseRmse` (relative, from the
     * half accumulations) is the plain image's own noise, for comparison.
     */
    async denoiseBias(refKey: string, config: PageConfig, sceneSpec: SceneSpec, width: number, height: number) {
      const ref = refs.get(refKey)!;
      const iterations = ref.info.iterations as number;
      const ctx = await context(config, width, height, true);
      ctx.setScene(await scene({ ...sceneSpec, seed: 987654 }));
      ctx.reset();
      for (let done = 0; done < iterations; done += 32) {
        ctx.iterate(Math.min(32, iterations - done));
        await ctx.backend.finish();
      }
      const plain = await ctx.readHDR(),
        denoised = await ctx.readHDR({ afterPost: true });
      let se = 0,
        sum = 0,
        n = 0;
      for (let i = 0; i < plain.length; i += 4)
        for (let c = 0; c < 3; c++) {
          se += (denoised[i + c] - plain[i + c]) ** 2;
          sum += plain[i + c];
          n++;
        }
      const est = await ctx.estimateError();
      ctx.dispose();
      const rmse = Math.sqrt(se / n);
      return {
        iterations,
        psnr: 20 * Math.log10(ref.peak / Math.max(rmse, 1e-12)),
        relativeRmse: rmse / (sum / n),
        noiseRmse: est ? est.relativeRmse : null,
      };
    },

    /** Error against wall-clock time and iterations, at doubling iteration checkpoints. */
    async errorCurve(
      config: PageConfig,
      sceneSpec: SceneSpec,
      width: number,
      height: number,
      refKey: string,
      maxIterations: number,
      budgetMs: number,
      withEstimate: boolean,
    ) {
      const ref = refs.get(refKey)!;
      const ctx = await context(config, width, height);
      ctx.setScene(await scene(sceneSpec));
      await ctx.renderIterations(1); // compile every kernel variant outside the clock
      ctx.reset();
      const points: Record<string, number | null>[] = [];
      let clock = 0,
        done = 0,
        next = 1;
      while (done < maxIterations && clock < budgetMs) {
        const t0 = performance.now();
        ctx.iterate(next - done);
        await ctx.backend.finish();
        clock += performance.now() - t0;
        done = next;
        const hdr = await ctx.readHDR(),
          ldr = await ctx.readLDR();
        const e = errors(hdr, ldr, ref);
        const est = withEstimate ? await ctx.estimateError() : null;
        points.push({ iterations: done, ms: clock, ...e, estimatedRmse: est ? est.rmse : null });
        next = Math.min(maxIterations, done < 8 ? done + 1 : Math.ceil(done * 1.5));
      }
      ctx.dispose();
      return points;
    },

    /**
     * ms per iteration: repeated GPU-synchronised batches of iterations, after a warm-up.
     * Wall-clock samples always; GPU samples too where the backend offers a timer
     * (gpuTimer), the GPU time of the whole batch.
     */
    async frameTime(
      config: PageConfig,
      sceneSpec: SceneSpec,
      width: number,
      height: number,
      iterations: number,
      repeats: number,
    ) {
      const ctx = await context(config, width, height);
      ctx.setScene(await scene(sceneSpec));
      const tFirst = performance.now();
      await ctx.renderIterations(1); // compiles the kernels: outside the samples
      const firstMs = performance.now() - tFirst;
      const samples: number[] = [],
        gpuSamples: number[] = [];
      const timer = gpuTimer(ctx.backend);
      for (let r = 0; r < repeats; r++) {
        ctx.reset();
        await ctx.backend.finish();
        const t0 = performance.now();
        if (timer) timer.begin();
        ctx.iterate(iterations);
        if (timer) timer.end();
        await ctx.backend.finish();
        samples.push((performance.now() - t0) / iterations);
        const gpuMs = timer ? await timer.result() : null;
        if (gpuMs !== null) gpuSamples.push(gpuMs / iterations);
      }
      const info = ctx.backend.info;
      if (timer) timer.dispose();
      ctx.dispose();
      return { samples, gpuSamples, gpuTimer: timer ? timer.kind : 'none', firstMs, device: info.renderer };
    },

    /** GPU bytes per voxel of the volume texture for each voxel type, fast (default) and exact sampling. */
    async bytesPerVoxel(backend: 'webgl2' | 'webgpu', size: number) {
      const rows: {
        backend: string;
        type: VoxelType;
        sampling: 'fast' | 'exact';
        bytesPerVoxel: number;
        total: number;
      }[] = [];
      const C = { uint8: Uint8Array, uint16: Uint16Array, int16: Int16Array, float32: Float32Array };
      for (const type of ['uint8', 'uint16', 'int16', 'float32'] as const) {
        const data = new C[type](size * size * size);
        for (let i = 0; i < data.length; i++) data[i] = (i * 7919) % 251;
        const volume = vpt.core.createVolume([size, size, size], type, data);
        for (const sampling of ['fast', 'exact'] as const) {
          const ctx = await context({ label: 'eam', renderer: 'eam', backend, sampling }, 16, 16);
          ctx.setScene(rampScene(volume, 1));
          await ctx.renderIterations(1);
          const b = ctx.stats.gpuBytes;
          rows.push({ backend, type, sampling, bytesPerVoxel: b.volume / data.length, total: b.total });
          ctx.dispose();
        }
      }
      return rows;
    },

    /**
     * A synthetic 512 x 512 x depth int16 CT (HU: air, an elliptic body of soft tissue, a bone
     * ring, varying with z) generated in the page, then shown: setScene (upload) and the first
     * image. Times of each stage; the caller samples the JS heap meanwhile.
     */
    async ctLoad(backend: 'webgl2' | 'webgpu', depth: number) {
      const nx = 512,
        ny = 512,
        slice = nx * ny;
      const t0 = performance.now();
      const templates: Int16Array[] = [];
      for (let k = 0; k < 16; k++) {
        const t = new Int16Array(slice);
        const ra = 200 + 4 * k,
          rb = 150 + 3 * k;
        for (let y = 0; y < ny; y++)
          for (let x = 0; x < nx; x++) {
            const e = ((x - 256) / ra) ** 2 + ((y - 256) / rb) ** 2;
            t[x + nx * y] = e > 1 ? -1000 : e > 0.85 ? 700 + ((x * 31 + y * 17) % 200) : 40 + ((x * 13 + y * 7) % 60);
          }
        templates.push(t);
      }
      const data = new Int16Array(slice * depth);
      for (let z = 0; z < depth; z++) data.set(templates[Math.floor(8 + 7.5 * Math.sin(z / 20))], z * slice);
      const volume = vpt.core.createVolume([nx, ny, depth], 'int16', data, [0.7, 0.7, 1.25]);
      volume.valueRange = [-1024, 3071];
      const t1 = performance.now();
      const ctx = await context({ label: 'eam', renderer: 'eam', backend }, 64, 64);
      const warnings: string[] = [];
      ctx.onWarning((w) => warnings.push(w.message));
      const t2 = performance.now();
      ctx.setScene(rampScene(volume, 10));
      const t3 = performance.now();
      await ctx.renderIterations(1);
      const t4 = performance.now();
      const out = {
        backend,
        depth,
        generateMs: t1 - t0,
        setSceneMs: t3 - t2,
        firstImageMs: t4 - t3,
        loadMs: t4 - t2,
        gpuBytes: ctx.stats.gpuBytes,
        uploadedDims: ctx.getScene()!.volume.dims,
        warnings,
      };
      ctx.dispose();
      return out;
    },

    backendInfo: async (backend: 'webgl2' | 'webgpu') => {
      const b = await vpt.core.createBackend({ backend });
      const info = { ...b.info, limits: b.limits };
      b.dispose();
      return info;
    },
    available: () => vpt.core.RENDERER_CATALOG.map((e) => e.name).filter((r) => vpt.renderers[r]),
  };
}
