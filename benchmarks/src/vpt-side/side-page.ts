/**
 * In-page code of the side-by-side suite (`pnpm bench --vpt DIR`), installed with
 * `page.evaluate(installSidePage)` as `window.side` in the headless vpt page. It drives two
 * engines in the same page: the original VPT, through its own ES modules served read-only
 * from DIR's build under `vptBase` (renderers, Volume, buffers, scene nodes; one iteration =
 * its renderer's generate + integrate, as VPT's main loop runs them, without the display),
 * and vpt, through RenderContext on WebGL 2 (VPT's only backend). Images stay in the page;
 * only mean squared errors and timings travel back.
 * Typed TypeScript sent by puppeteer as the function's source: it may use nothing from this
 * module's scope (types only). VPT's modules are untyped (`any`).
 */
import type { VptPageApi } from '@vpt/headless';

type RenderContext = Awaited<ReturnType<VptPageApi['core']['RenderContext']['create']>>;
type Scene = Parameters<RenderContext['setScene']>[0];

/** One engine configuration: VPT's renderer by factory name with properties, or a vpt renderer with params. */
export type SideEngineConfig =
  | { engine: 'vpt-ref'; renderer: string; props: Record<string, unknown> }
  | { engine: 'vpt'; renderer: string; params: Record<string, unknown> };

export interface SideSceneConfig {
  /** URL of the N³ uint8 anchor volume. */
  volumeUrl: string;
  n: number;
  extinction: number;
  albedo: [number, number, number];
  cameraZ: number;
  fovy: number;
  skyRows: number;
}

/** A checkpoint of an error curve: wall ms of rendering so far (read-backs excluded) and the raw MSE against the reference. */
export interface SidePoint {
  iterations: number;
  ms: number;
  mse: number;
}

interface Runner {
  reset(seed: number): void;
  /** Queue n iterations. */
  iterate(n: number): void;
  /** Block until all queued GPU work is done. */
  sync(): Promise<void>;
  /** Linear RGBA of the current estimate, clamped to [0, 1] (the anchor's HDR PSNR uses peak 1). */
  readClamped(): Promise<Float32Array>;
  /** readClamped's first row is the bottom one (WebGL's readPixels order) rather than the top. */
  bottomUp: boolean;
  dispose(): void;
}

declare const window: Window & { vpt: VptPageApi };

export function installSidePage(): void {
  const vpt = window.vpt;
  const runners = new Map<string, Runner>();
  const refs = new Map<string, { image: Float32Array; iterations: number; bottomUp: boolean }>();
  let sceneConfig: SideSceneConfig | null = null;
  let voxels: Uint8Array | null = null;
  let vptModules: Record<string, any> | null = null;

  /** VPT's sky texture row values (8-bit, as its RGBA8 texture stores them). */
  function skyBytes(rows: number): number[] {
    const sky = (up: number) => 0.05 + 0.95 * ((1 + up) / 2) ** 2;
    return Array.from({ length: rows }, (_, j) => Math.round(255 * sky(Math.cos((Math.PI * (j + 0.5)) / rows))));
  }

  /**
   * The sky as a vpt lat-long map: 1024 rows, each holding VPT's bilinearly filtered 8-bit
   * texture at the row centre (vpt looks its map up by nearest texel), so both renderers
   * light the scene alike. Both map v = acos(d.y)/π.
   */
  function skyMap(rows: number): Scene['environment'] {
    const bytes = skyBytes(rows);
    const H = 1024,
      W = 4;
    const data = new Float32Array(W * H * 3);
    for (let j = 0; j < H; j++) {
      const t = Math.min(Math.max(((j + 0.5) / H) * rows - 0.5, 0), rows - 1);
      const j0 = Math.floor(t),
        j1 = Math.min(j0 + 1, rows - 1);
      const value = (bytes[j0] + (bytes[j1] - bytes[j0]) * (t - j0)) / 255;
      data.fill(value, 3 * W * j, 3 * W * (j + 1));
    }
    return { type: 'latlong', width: W, height: H, data };
  }

  function vptScene(c: SideSceneConfig, seed: number): Scene {
    const volume = vpt.core.createVolume([c.n, c.n, c.n], 'uint8', voxels!);
    // The points reproduce VPT's 256-texel ramp under its linear filter: 0 up to the first texel's centre, 1 from the last one's.
    const color = c.albedo;
    return {
      volume,
      transferFunction: {
        dimensions: '1d',
        points: [
          { value: 0, color, opacity: 0 },
          { value: 0.5 / 256, color, opacity: 0 },
          { value: 255.5 / 256, color, opacity: 1 },
          { value: 1, color, opacity: 1 },
        ],
      },
      camera: { position: [0, 0, c.cameraZ], target: [0, 0, 0], up: [0, 1, 0], fovy: c.fovy },
      lights: [],
      environment: skyMap(c.skyRows),
      densityScale: c.extinction,
      seed,
    };
  }

  async function ourRunner(config: Extract<SideEngineConfig, { engine: 'vpt' }>, size: number): Promise<Runner> {
    const c = sceneConfig!;
    const ctx: RenderContext = await vpt.core.RenderContext.create({
      backend: 'webgl2',
      width: size,
      height: size,
      renderer: vpt.createRenderer(config.renderer, config.params),
      post: [],
    });
    const volumeScene = vptScene(c, 1);
    ctx.setScene(volumeScene);
    await ctx.renderIterations(1); // compile outside the clock
    return {
      reset(seed) {
        ctx.updateScene({ seed });
        ctx.reset();
      },
      iterate(n) {
        ctx.iterate(n);
      },
      sync: () => ctx.backend.finish(),
      async readClamped() {
        const hdr = await ctx.readHDR();
        for (let i = 0; i < hdr.length; i++) hdr[i] = Math.min(Math.max(hdr[i], 0), 1);
        return hdr;
      },
      dispose: () => ctx.dispose(),
      bottomUp: false,
    };
  }

  async function vptRefRunner(config: Extract<SideEngineConfig, { engine: 'vpt-ref' }>, size: number): Promise<Runner> {
    const c = sceneConfig!;
    const m = vptModules!;
    const canvas = document.createElement('canvas');
    canvas.width = canvas.height = size;
    // VPT's own context attributes (its main.js).
    const gl = canvas.getContext('webgl2', {
      alpha: false,
      depth: false,
      stencil: false,
      antialias: false,
      preserveDrawingBuffer: true,
    })!;
    for (const ext of ['EXT_color_buffer_float', 'OES_texture_float_linear'])
      if (!gl.getExtension(ext)) throw new Error('VPT needs ' + ext);
    gl.pixelStorei(gl.PACK_ALIGNMENT, 1);
    gl.pixelStorei(gl.UNPACK_ALIGNMENT, 1);

    const cameraNode = new m.Node();
    cameraNode.addComponent(new m.Camera({ fovy: c.fovy, aspect: 1 }));
    cameraNode.addComponent(new m.Transform({ translation: [0, 0, c.cameraZ] }));
    const volumeNode = new m.Node();
    volumeNode.addComponent(new m.Transform());
    const volume = new m.Volume(gl, { size: [c.n, c.n, c.n], datatype: 'unorm8', filter: 'linear' });
    volume.writeData(voxels!.buffer.slice(0), [0, 0, 0], volume.size);
    volumeNode.addComponent(volume);
    const rows = skyBytes(c.skyRows);
    const sky = new Uint8Array(256 * c.skyRows * 4);
    for (let j = 0; j < c.skyRows; j++)
      for (let i = 0; i < 256; i++) sky.set([rows[j], rows[j], rows[j], 255], 4 * (256 * j + i));
    const envNode = new m.Node();
    envNode.addComponent(
      new m.EnvironmentMap({
        texture: m.createTexture(gl, {
          width: 256,
          height: c.skyRows,
          data: sky,
          min: gl.LINEAR,
          mag: gl.LINEAR,
          wrapS: gl.REPEAT,
          wrapT: gl.CLAMP_TO_EDGE,
        }),
      }),
    );
    const scene = [cameraNode, volumeNode, envNode];

    const Renderer = m.RendererFactory(config.renderer);
    const renderer = new Renderer(gl);
    for (const [k, v] of Object.entries(config.props)) renderer[k] = v;
    // The TF texture: alpha = i/255 (σ_t = extinction × normalized value), albedo as sRGB bytes.
    const srgb = (x: number) => Math.round(255 * (x <= 0.0031308 ? 12.92 * x : 1.055 * x ** (1 / 2.4) - 0.055));
    const tf = new Uint8ClampedArray(256 * 4);
    for (let i = 0; i < 256; i++) tf.set([srgb(c.albedo[0]), srgb(c.albedo[1]), srgb(c.albedo[2]), i], 4 * i);
    renderer.setTransferFunction(new ImageData(tf, 256, 1));

    const target = (f: string) => ({
      width: size,
      height: size,
      min: gl.NEAREST,
      mag: gl.NEAREST,
      wrapS: gl.CLAMP_TO_EDGE,
      wrapT: gl.CLAMP_TO_EDGE,
      ...m.formatToTextureType(gl, f),
    });
    const frameBuffer = new m.SingleBuffer(gl, renderer.frameBufferFormat.map(target));
    const accumulationBuffer = new m.DoubleBuffer(gl, renderer.accumulationBufferFormat.map(target));
    const renderBuffer = new m.SingleBuffer(gl, [target('rgba16float')]);
    const pixel = new Float32Array(4);
    const present = () => {
      renderer.render(accumulationBuffer, renderBuffer, scene);
      gl.bindFramebuffer(gl.FRAMEBUFFER, renderBuffer._framebuffer);
    };
    const runner: Runner = {
      reset() {
        renderer.needsReset = true; // VPT seeds from Math.random(): every run is independent
      },
      iterate(n) {
        for (let i = 0; i < n; i++) {
          renderer.generate(frameBuffer, scene);
          renderer.integrate(frameBuffer, accumulationBuffer, scene);
        }
      },
      async sync() {
        present();
        gl.readPixels(0, 0, 1, 1, gl.RGBA, gl.FLOAT, pixel); // blocks until the GPU is done
      },
      async readClamped() {
        present();
        const out = new Float32Array(size * size * 4);
        gl.readPixels(0, 0, size, size, gl.RGBA, gl.FLOAT, out);
        for (let i = 0; i < out.length; i++) out[i] = Math.min(Math.max(out[i], 0), 1);
        return out;
      },
      dispose() {
        renderer.destroy();
        frameBuffer.destroy();
        accumulationBuffer.destroy();
        renderBuffer.destroy();
        volume.destroy();
        gl.getExtension('WEBGL_lose_context')?.loseContext();
      },
      bottomUp: true,
    };
    runner.iterate(1); // compile outside the clock
    await runner.sync();
    return runner;
  }

  /** Mean squared error over RGB. */
  function mse(a: Float32Array, b: Float32Array): number {
    let se = 0,
      n = 0;
    for (let i = 0; i < a.length; i += 4)
      for (let ch = 0; ch < 3; ch++) {
        const d = a[i + ch] - b[i + ch];
        se += d * d;
        n++;
      }
    return se / n;
  }

  (window as unknown as { side: unknown }).side = {
    /** Load the anchor volume and VPT's modules (VPT fetches shaders.json relative to the document: served from vptBase). */
    async init(vptBase: string, config: SideSceneConfig) {
      sceneConfig = config;
      voxels = new Uint8Array(await (await fetch(config.volumeUrl)).arrayBuffer());
      const realFetch = window.fetch;
      window.fetch = ((input: RequestInfo | URL, init?: RequestInit) =>
        realFetch(
          typeof input === 'string' && /^(shaders|mixins)\.json$/.test(input) ? vptBase + input : input,
          init,
        )) as typeof fetch;
      try {
        const load = (p: string) => import(/* @vite-ignore */ vptBase + p);
        await load('lib/gl-matrix-min.js'); // the global glMatrix its module wrapper re-exports (VPT's index.html loads it first)
        const [node, camera, transform, vol, env, factory, single, double, formats, webgl] = await Promise.all([
          load('js/Node.js'),
          load('js/Camera.js'),
          load('js/Transform.js'),
          load('js/Volume.js'),
          load('js/EnvironmentMap.js'),
          load('js/renderers/RendererFactory.js'),
          load('js/SingleBuffer.js'),
          load('js/DoubleBuffer.js'),
          load('js/TextureFormats.js'),
          load('js/WebGL.js'),
        ]);
        vptModules = {
          ...node,
          ...camera,
          ...transform,
          ...vol,
          ...env,
          ...factory,
          ...single,
          ...double,
          ...formats,
          ...webgl,
        };
      } finally {
        window.fetch = realFetch;
      }
      let sum = 0;
      for (const v of voxels) sum += v;
      return { voxels: voxels.length, mean: sum / voxels.length };
    },

    async open(key: string, config: SideEngineConfig, size: number) {
      runners.get(key)?.dispose();
      runners.set(key, config.engine === 'vpt' ? await ourRunner(config, size) : await vptRefRunner(config, size));
    },

    close(key: string) {
      runners.get(key)?.dispose();
      runners.delete(key);
    },

    /** A converged image of `iterations` (another seed than any curve's). */
    async reference(key: string, refKey: string, iterations: number) {
      const r = runners.get(key)!;
      r.reset(987654);
      const t0 = performance.now();
      for (let done = 0; done < iterations; done += 16) {
        r.iterate(Math.min(16, iterations - done));
        await r.sync();
      }
      refs.set(refKey, { image: await r.readClamped(), iterations, bottomUp: r.bottomUp });
      return { ms: performance.now() - t0 };
    },

    /** A reference as sRGB 8-bit RGBA, top row first, base64 (to look at). */
    referenceImage(refKey: string) {
      const { image, bottomUp } = refs.get(refKey)!;
      const side = Math.round(Math.sqrt(image.length / 4));
      const out = new Uint8Array(image.length);
      const srgb = (x: number) => Math.round(255 * (x <= 0.0031308 ? 12.92 * x : 1.055 * x ** (1 / 2.4) - 0.055));
      for (let y = 0; y < side; y++)
        for (let x = 0; x < side; x++) {
          const from = 4 * ((bottomUp ? side - 1 - y : y) * side + x),
            to = 4 * (y * side + x);
          for (let ch = 0; ch < 3; ch++) out[to + ch] = srgb(image[from + ch]);
          out[to + 3] = 255;
        }
      let binary = '';
      for (let i = 0; i < out.length; i++) binary += String.fromCharCode(out[i]);
      return btoa(binary);
    },

    /** MSE against the reference at 1, 2, … 8, then ×1.5 iterations, until maxIterations or budgetMs of rendering. */
    async curve(key: string, refKey: string, seed: number, maxIterations: number, budgetMs: number) {
      const r = runners.get(key)!;
      const ref = refs.get(refKey)!;
      r.reset(seed);
      await r.sync();
      const points: SidePoint[] = [];
      let clock = 0,
        done = 0,
        next = 1;
      while (done < maxIterations && clock < budgetMs) {
        const t0 = performance.now();
        r.iterate(next - done);
        await r.sync();
        clock += performance.now() - t0;
        done = next;
        points.push({ iterations: done, ms: clock, mse: mse(await r.readClamped(), ref.image) });
        next = Math.min(maxIterations, done < 8 ? done + 1 : Math.ceil(done * 1.5));
      }
      return points;
    },

    /** ms per iteration: `repeats` batches of `iterations`, each between blocking syncs. */
    async msPerIteration(key: string, iterations: number, repeats: number) {
      const r = runners.get(key)!;
      const samples: number[] = [];
      for (let k = 0; k < repeats; k++) {
        await r.sync();
        const t0 = performance.now();
        r.iterate(iterations);
        await r.sync();
        samples.push((performance.now() - t0) / iterations);
      }
      return samples;
    },
  };
}
