import fs from 'node:fs';
import { describe, expect, it } from 'vitest';
import { denoiseRef } from '../packages/post/src/index.js';
import { rgbRmse as rmse } from './helpers/mcrt-stats.js';
import { BACKENDS, usePage } from './helpers/session.js';

/**
 * The denoise post step (docs/architecture.md, "Denoising"): its pass against the CPU twin and
 * across backends, the guides' cost (none on the estimate), and on rendered images: a converged
 * image is left nearly unchanged, a sharp edge stays sharp, and the error at 4 samples falls.
 */
const page = usePage();

// Synthetic inputs for the pass alone: noise on a gradient, two depth layers, some misses.
const W = 16,
  H = 12;
function syntheticInputs() {
  let s = 7;
  const rnd = () => (s = (s * 16807) % 2147483647) / 2147483647;
  const image = new Float32Array(W * H * 4),
    normalDepth = new Float32Array(W * H * 4),
    albedo = new Float32Array(W * H * 4),
    moments = new Float32Array(W * H * 4);
  for (let y = 0; y < H; y++)
    for (let x = 0; x < W; x++) {
      const i = 4 * (y * W + x);
      const hit = x < 13 ? 1 : x === 13 ? 0.5 : 0;
      const near = y < 6;
      const v = (0.2 + x / W) * (1 + 0.6 * (rnd() - 0.5));
      image.set([v, 0.8 * v, 0.5 * v + 0.1, hit], i);
      const n = near ? [0, 0, 1] : [0.6, 0, 0.8];
      normalDepth.set([n[0] * hit, n[1] * hit, n[2] * hit, (near ? 1.5 : 2.5) * hit], i);
      albedo.set([0.8 * hit, (near ? 0.7 : 0.2) * hit, 0.3 * hit, hit], i);
      const l = 0.2126 * v + 0.7152 * 0.8 * v + 0.0722 * (0.5 * v + 0.1);
      // Some pixels with zero variance (m2 = m1²), the rest with the noise's own; the last row has one sample.
      moments.set([l, x % 5 === 0 ? l * l : l * l + 0.01 * l * l, y === H - 1 ? 1 : 4, 0], i);
    }
  return { image, normalDepth, albedo, moments };
}

describe('the denoise pass', () => {
  it('matches its CPU twin within float tolerance and is bit-identical on WebGL 2 and WebGPU', async () => {
    const inputs = syntheticInputs();
    const outputs: number[][] = [];
    for (const backend of BACKENDS) {
      const out = await page().page.evaluate(
        async (backend, W, H, arrays) => {
          const { core, post } = window.vpt;
          const b = await core.createBackend({ backend });
          const tex = (data: number[]) =>
            b.createTexture({
              dimension: '2d',
              width: W,
              height: H,
              format: 'rgba32float',
              data: new Float32Array(data),
            });
          const guides = {
            guideNormalDepth: tex(arrays.normalDepth),
            guideAlbedo: tex(arrays.albedo),
            guideMoments: tex(arrays.moments),
          };
          const step = new post.DenoiseStep();
          const pass = b.createPass({
            label: 'denoise',
            glsl: step.glsl,
            wgsl: step.wgsl,
            uniforms: step.uniforms,
            textures: ['inputImage', ...Object.keys(guides), 'inputState'].map((name) => ({
              name,
              dimension: '2d' as const,
            })),
            outputs: ['rgba32float', 'rgba32float'],
            defines: {},
          });
          const formats = ['rgba32float', 'rgba32float'] as const;
          const targets = [b.createRenderTarget(W, H, formats), b.createRenderTarget(W, H, formats)];
          let input = tex(arrays.image);
          // Each level reads the previous level's filtered variance (the first a placeholder it does not read).
          let state = guides.guideMoments;
          for (let d = 0; d < (step.repeat ?? 1); d++) {
            const target = targets[d % 2];
            b.draw(pass, {
              uniforms: step.uniforms.pack(step.uniformValues(d)),
              textures: { ...guides, inputImage: input, inputState: state },
              target,
            });
            input = target.textures[0];
            state = target.textures[1];
          }
          const result = Array.from((await b.readTexture(input)) as Float32Array);
          b.dispose();
          return result;
        },
        backend,
        W,
        H,
        {
          image: Array.from(inputs.image),
          normalDepth: Array.from(inputs.normalDepth),
          albedo: Array.from(inputs.albedo),
          moments: Array.from(inputs.moments),
        },
      );
      outputs.push(out);
    }
    const [gl, gpu] = outputs;
    expect(gl.every(Number.isFinite)).toBe(true);
    expect(gl.filter((v, i) => !Object.is(v, gpu[i])).length).toBe(0);
    const ref = denoiseRef({ width: W, height: H, ...inputs });
    let worst = 0;
    for (let i = 0; i < ref.length; i++) worst = Math.max(worst, Math.abs(gl[i] - ref[i]) / (1e-3 + Math.abs(ref[i])));
    expect(worst).toBeLessThan(1e-3);
    // It filtered something: the output is not the input.
    let changed = 0;
    for (let i = 0; i < gl.length; i++) if (Math.abs(gl[i] - inputs.image[i]) > 1e-3) changed++;
    expect(changed).toBeGreaterThan(W * H);
  });
});

/** MCRT/EAM scenes for the rendered checks, with an HDR reader before and after the radiance-preserving post steps. */
async function renderPair(opts: {
  backend: 'webgl2' | 'webgpu';
  renderer: string;
  sceneName: 'blob' | 'block';
  size: number;
  iterations: number[];
  seed: number;
  sampling?: 'exact';
  denoise?: Record<string, number>;
  params?: Record<string, unknown>;
  /** Also read the last image through a denoise step with these parameters (same samples, same guides). */
  control?: Record<string, number>;
}) {
  return page().page.evaluate(async (o) => {
    const { core } = window.vpt;
    const volume = o.sceneName === 'blob' ? core.createProceduralVolume('blob', 32) : window.tv.block(32, 0.3);
    const scene = (seed: number) => ({
      ...window.t.scene({
        volume,
        transferFunction: {
          dimensions: '1d' as const,
          points:
            o.sceneName === 'blob'
              ? [
                  { value: 0.05, color: [0.9, 0.5, 0.3] as [number, number, number], opacity: 0 },
                  { value: 1, color: [0.95, 0.95, 0.95] as [number, number, number], opacity: 1 },
                ]
              : [
                  { value: 0, color: [0.8, 0.8, 0.8] as [number, number, number], opacity: 0 },
                  { value: 1, color: [0.8, 0.8, 0.8] as [number, number, number], opacity: 1 },
                ],
        },
        camera:
          o.sceneName === 'blob'
            ? { position: [0.2, 0.5, 1.9], target: [0, 0, 0], up: [0, 1, 0], fovy: 0.7 }
            : { position: [0, 0, 2.2], target: [0, 0, 0], up: [0, 1, 0], fovy: 0.6 },
        environment: { type: 'constant' as const, radiance: [0.3, 0.4, 0.6] as [number, number, number] },
        densityScale: o.sceneName === 'blob' ? 40 : 100,
        seed,
      }),
      lights: [
        {
          type: 'directional' as const,
          direction: (o.sceneName === 'blob' ? [1, 1, 0] : [0.3, 0.5, 1]) as [number, number, number],
          irradiance: [2, 2, 2] as [number, number, number],
        },
      ],
    });
    const ctx = await window.t.context({
      backend: o.backend,
      renderer: o.renderer,
      params: o.params,
      width: o.size,
      height: o.size,
      sampling: o.sampling,
      post: [{ type: 'denoise', ...o.denoise }, { type: 'srgb' }],
    });
    const out: { n: number; plain: number[]; denoised: number[]; control?: number[] }[] = [];
    for (const n of o.iterations) {
      ctx.setScene(scene(o.seed + n));
      await ctx.renderIterations(n);
      out.push({
        n,
        plain: Array.from(await ctx.readHDR()),
        denoised: Array.from(await ctx.readHDR({ afterPost: true })),
      });
    }
    if (o.control) {
      // Still using guides, so the chain change keeps the samples.
      ctx.setPost(window.vpt.post.postChainFromJSON([{ type: 'denoise', ...o.control }, { type: 'srgb' }]));
      out[out.length - 1].control = Array.from(await ctx.readHDR({ afterPost: true }));
    }
    ctx.dispose();
    return out;
  }, opts);
}

describe('vpt-render and the HDR image', () => {
  it('the HDR image of a scene whose chain starts with denoise is the denoised one, and says so', async () => {
    const desc = {
      renderer: 'mcrt' as const,
      width: 16,
      height: 16,
      iterations: 2,
      backend: 'webgl2' as const,
      volume: { procedural: 'blob' as const, size: 16 },
      lights: [
        {
          type: 'directional' as const,
          direction: [1, 1, 0] as [number, number, number],
          irradiance: [2, 2, 2] as [number, number, number],
        },
      ],
    };
    const chain = [{ type: 'tonemap', operator: 'aces' }, { type: 'srgb' }];
    const plain = await page().render({ ...desc, post: chain });
    const denoised = await page().render({ ...desc, post: [{ type: 'denoise' }, ...chain] });
    expect(plain.hdrPostSteps).toEqual([]);
    expect(denoised.hdrPostSteps).toEqual(['denoise']);
    expect(Array.from(denoised.hdr).every(Number.isFinite)).toBe(true);
    expect(rmse(Array.from(denoised.hdr), Array.from(plain.hdr))).toBeGreaterThan(0);
  });
});

describe('denoising rendered images', () => {
  it('a chain with the denoiser leaves the HDR estimate bit for bit as it is without (MCRT, EAM, ISO)', async () => {
    const r = await page().page.evaluate(async () => {
      const { core } = window.vpt;
      const scene = {
        ...window.t.scene({ volume: core.createProceduralVolume('blob', 16), densityScale: 8, seed: 3 }),
        lights: [
          {
            type: 'directional' as const,
            direction: [1, 1, 0] as [number, number, number],
            irradiance: [2, 2, 2] as [number, number, number],
          },
        ],
      };
      const diffs: Record<string, number> = {};
      for (const renderer of ['mcrt', 'eam', 'iso', 'mip']) {
        const images: Float32Array[] = [];
        for (const post of [[{ type: 'srgb' }], [{ type: 'denoise' }, { type: 'srgb' }]]) {
          const ctx = await window.t.context({ backend: 'webgl2', renderer, width: 16, height: 16, post });
          ctx.setScene(scene);
          await ctx.renderIterations(3);
          images.push(await ctx.readHDR());
          const denoised = await ctx.readHDR({ afterPost: true });
          if (window.t.hasNonFinite(denoised)) diffs[`${renderer} non-finite`] = 1;
          ctx.dispose();
        }
        diffs[renderer] = window.t.sameBits(images[0], images[1]);
      }
      return diffs;
    });
    expect(r).toEqual({ mcrt: 0, eam: 0, iso: 0, mip: 0 });
  });

  it('the denoised MCRT image (guides written during generate) is bit-identical on WebGL 2 and WebGPU', async () => {
    const images: Awaited<ReturnType<typeof renderPair>>[number][] = [];
    for (const backend of BACKENDS)
      images.push(
        (
          await renderPair({
            backend,
            renderer: 'mcrt',
            sceneName: 'blob',
            size: 16,
            iterations: [3],
            seed: 1,
            sampling: 'exact',
          })
        )[0],
      );
    expect(images[0].plain).toEqual(images[1].plain);
    const differing = images[0].denoised.filter((v, i) => !Object.is(v, images[1].denoised[i])).length;
    expect(differing).toBe(0);
    expect(rmse(images[0].denoised, images[0].plain)).toBeGreaterThan(0);
  });

  it('reduces the error of MCRT at 4 samples per pixel against a long-run reference', async () => {
    const [ref, low] = await renderPair({
      backend: 'webgl2',
      renderer: 'mcrt',
      sceneName: 'blob',
      size: 64,
      iterations: [256, 4],
      seed: 11,
    });
    const noisy = rmse(low.plain, ref.plain),
      denoised = rmse(low.denoised, ref.plain);
    console.log(`MCRT blob 64², 4 spp: RMSE plain ${noisy.toFixed(4)}, denoised ${denoised.toFixed(4)}`);
    expect(denoised).toBeLessThan(0.75 * noisy);
  });

  it('leaves a converged EAM image (exact sampling) within 1 % relative RMSE of the plain one', async () => {
    const [c] = await renderPair({
      backend: 'webgl2',
      renderer: 'eam',
      sceneName: 'blob',
      size: 64,
      iterations: [256],
      seed: 5,
      sampling: 'exact',
    });
    let mean = 0;
    for (let i = 0; i < c.plain.length; i += 4) mean += (c.plain[i] + c.plain[i + 1] + c.plain[i + 2]) / 3;
    mean /= c.plain.length / 4;
    const rel = rmse(c.denoised, c.plain) / mean;
    console.log(`EAM blob 64², 256 spp: denoised vs plain relative RMSE ${rel.toExponential(2)}`);
    expect(rel).toBeLessThan(0.01);
  });

  it("keeps the procedural cube's silhouette edge sharp (10-90 % width within 1 px of the converged plain image)", async () => {
    const size = 64;
    const [ref, low] = await renderPair({
      backend: 'webgl2',
      renderer: 'mcrt',
      sceneName: 'block',
      size,
      iterations: [64, 8],
      seed: 21,
      params: { scattering: 'single' },
      // Control: two levels of the same filter with its edge-stopping weights off (a plain B3 blur,
      // standard deviation √5 px) must widen the edge, so the measure can see a blur.
      control: { colorSigma: 1e6, depthEpsilon: 1e6, normalSigma: 0, albedoSigma: 1e6, iterations: 2 },
    });
    // The left edge: luminance profile over columns 0..31, averaged over the middle rows of the face.
    const profile = (img: number[]) => {
      const p: number[] = [];
      for (let x = 0; x < size / 2; x++) {
        let s = 0;
        for (let y = 24; y < 40; y++) {
          const i = 4 * (y * size + x);
          s += 0.2126 * img[i] + 0.7152 * img[i + 1] + 0.0722 * img[i + 2];
        }
        p.push(s / 16);
      }
      return p;
    };
    const width = (p: number[]) => {
      const lo = p[0],
        hi = p[p.length - 1];
      const cross = (f: number) => {
        const level = lo + f * (hi - lo);
        for (let x = 1; x < p.length; x++)
          if ((p[x - 1] - level) * (p[x] - level) <= 0 && p[x] !== p[x - 1])
            return x - 1 + (level - p[x - 1]) / (p[x] - p[x - 1]);
        return NaN;
      };
      return Math.abs(cross(0.9) - cross(0.1));
    };
    const wRef = width(profile(ref.plain)),
      wDen = width(profile(low.denoised)),
      wBlur = width(profile(low.control!));
    console.log(
      `cube edge 10-90 % width: converged plain ${wRef.toFixed(2)} px, 8 spp denoised ${wDen.toFixed(2)} px, weights off ${wBlur.toFixed(2)} px`,
    );
    expect(Number.isFinite(wRef) && Number.isFinite(wDen)).toBe(true);
    expect(wDen).toBeLessThan(wRef + 1);
    expect(wBlur).toBeGreaterThan(wRef + 1);
  });

  it('halves the 4-spp error of the bundled head (MCRT, 64²) against 512 spp, and leaves 512 spp within its noise', async () => {
    // The gallery's head scene file at 64², its volume from the served workspace root.
    const desc = JSON.parse(fs.readFileSync(new URL('../apps/gallery/scenes/head-mcrt.json', import.meta.url), 'utf8'));
    desc.volume = { sidecar: '/data/mri_head_volpack_brainsmall_128x128x84_uint8.json' };
    const runs: [number, number][] = [
      [1000, 512],
      [1, 4],
      [2, 4],
    ];
    const images = await page().page.evaluate(
      async (d, runs) => {
        const { core, post } = window.vpt;
        const ctx = await core.RenderContext.create({
          backend: 'webgl2',
          width: 64,
          height: 64,
          renderer: window.vpt.createRenderer(d.renderer, d.rendererParams),
          post: post.postChainFromJSON([{ type: 'denoise' }, { type: 'srgb' }]),
        });
        const out: { plain: number[]; denoised: number[]; noise: number }[] = [];
        for (const [seed, n] of runs) {
          ctx.setScene(await window.vpt.buildScene({ ...d, seed }, location.origin + '/'));
          await ctx.renderIterations(n);
          out.push({
            plain: Array.from(await ctx.readHDR()),
            denoised: Array.from(await ctx.readHDR({ afterPost: true })),
            noise: (await ctx.estimateError())!.rmse,
          });
        }
        ctx.dispose();
        return out;
      },
      desc,
      runs,
    );
    for (const im of images) expect(im.denoised.every(Number.isFinite)).toBe(true);
    const [ref, ...lows] = images;
    for (const low of lows) {
      const plain = rmse(low.plain, ref.plain),
        denoised = rmse(low.denoised, ref.plain);
      console.log(
        `head 64², 4 spp: RMSE plain ${plain.toFixed(4)}, denoised ${denoised.toFixed(4)} (×${(denoised / plain).toFixed(2)})`,
      );
      expect(denoised).toBeLessThanOrEqual(0.5 * plain);
    }
    // At 512 spp the filter moves the image by less than the plain estimate's own noise (its RMSE
    // estimated from MCRT's independent even and odd half accumulations, RenderContext.estimateError).
    const moved = rmse(ref.denoised, ref.plain);
    console.log(`head 64², 512 spp: denoised moves ${moved.toFixed(5)}, plain noise ${ref.noise.toFixed(5)}`);
    expect(moved).toBeLessThan(ref.noise);
  }, 600_000);
});
