import { describe, expect, it } from 'vitest';
import {
  createProceduralVolume,
  createVolume,
  gradientMagnitudes,
  maxGradientMagnitude,
  normalizedData,
  rasterizeTransferFunction,
  reference,
  volumeBox,
  type Scene,
  type TransferFunction2D,
  type Vec3,
  type Volume,
} from '../packages/core/src/index.js';
import { BACKENDS, usePage } from './helpers/session.js';
import { testVolumes } from './helpers/test-volumes.js';

/**
 * A 2D transfer function on a rendered image: a homogeneous block (value 1 inside
 * |x|, |y|, |z| < 0.25, 0 outside) under a TF that gives extinction only to high normalized
 * gradient magnitude. The block's interior (gradient 0) must be transparent and its boundary
 * shell visible. The EAM image is checked pixel by pixel against a CPU integration of the same
 * model (gradients, trilinear sampling and bilinear 2D lookup in float64), and against the
 * 1D-TF image of the same block, which is opaque.
 */
const N = 24;
const HALF = 0.25;
const TF2D: TransferFunction2D = {
  dimensions: '2d',
  widgets: [{ type: 'box', min: [0, 0.3], max: [1, 1], ramp: [0, 0.1], color: [1, 0.8, 0.6], opacity: 1 }],
};
const DENSITY = 4;
const W = 20,
  H = 20;
const CAMERA = { position: [0.7, 0.55, 1.5] as Vec3, target: [0, 0, 0] as Vec3, up: [0, 1, 0] as Vec3, fovy: 0.6 };

function block(): Volume {
  return testVolumes({ createVolume, createProceduralVolume }).block(N, HALF);
}

/** CPU model of transferAt() for a 2D TF: trilinear value and gradient, bilinear lookup. */
function cpuModel(volume: Volume, tf: TransferFunction2D) {
  const value = normalizedData(volume);
  const grad = gradientMagnitudes(volume);
  const gmax = maxGradientMagnitude(grad);
  const raster = rasterizeTransferFunction(tf);
  const box = volumeBox(volume);
  const [nx, ny, nz] = volume.dims;
  const tri = (a: Float32Array, p: Vec3) => {
    const c = p.map((x, k) => ((x - box.min[k]) / box.size[k]) * volume.dims[k] - 0.5);
    const i0 = c.map(Math.floor),
      f = c.map((x, k) => x - i0[k]);
    const cl = (i: number, n: number) => Math.min(n - 1, Math.max(0, i));
    let s = 0;
    for (const dz of [0, 1])
      for (const dy of [0, 1])
        for (const dx of [0, 1]) {
          s +=
            (dx ? f[0] : 1 - f[0]) *
            (dy ? f[1] : 1 - f[1]) *
            (dz ? f[2] : 1 - f[2]) *
            a[cl(i0[0] + dx, nx) + nx * (cl(i0[1] + dy, ny) + ny * cl(i0[2] + dz, nz))];
        }
    return s;
  };
  const opacity = (p: Vec3) => {
    const x = Math.min(1, Math.max(0, tri(value, p))) * 255,
      y = Math.min(1, Math.max(0, tri(grad, p) / gmax)) * 255;
    const x0 = Math.floor(x),
      y0 = Math.floor(y),
      x1 = Math.min(x0 + 1, 255),
      y1 = Math.min(y0 + 1, 255);
    const a = (i: number, j: number) => raster[4 * (i + 256 * j) + 3];
    const fx = x - x0,
      fy = y - y0;
    return (a(x0, y0) * (1 - fx) + a(x1, y0) * fx) * (1 - fy) + (a(x0, y1) * (1 - fx) + a(x1, y1) * fx) * fy;
  };
  /** 1 − exp(−densityScale ∫ opacity ds) along a ray, by a fine midpoint rule. */
  return (origin: Vec3, dir: Vec3) => {
    const [t0, t1] = reference.intersectBox(origin, dir, box.min, box.max);
    if (!(t1 > t0)) return 0;
    const steps = Math.ceil((t1 - t0) / (0.125 / N));
    const ds = (t1 - t0) / steps;
    let tau = 0;
    for (let k = 0; k < steps; k++) {
      const t = t0 + (k + 0.5) * ds;
      tau += opacity([origin[0] + dir[0] * t, origin[1] + dir[1] * t, origin[2] + dir[2] * t]) * ds;
    }
    return 1 - Math.exp(-DENSITY * tau);
  };
}

const page = usePage();

async function renderAlpha(backend: string, tf: object, iterations: number): Promise<number[]> {
  return page.run(
    async ({ t }, backend, tf, iterations, n, half, camera, density, W, H) => {
      const ctx = await t.context({ backend, renderer: 'eam', width: W, height: H, params: { cutoff: 0 } });
      ctx.setScene(t.scene({ volume: window.tv.block(n, half), camera, densityScale: density, transferFunction: tf }));
      await ctx.renderIterations(iterations);
      const hdr: Float32Array = await ctx.readHDR();
      ctx.dispose();
      return Array.from(hdr.filter((_, i) => i % 4 === 3));
    },
    backend,
    tf,
    iterations,
    N,
    HALF,
    CAMERA,
    DENSITY,
    W,
    H,
  );
}

describe.each(BACKENDS)('EAM with a 2D transfer function on %s', (backend) => {
  it("makes a homogeneous block's interior transparent and its boundary visible, as the CPU model predicts", async () => {
    const gpu = await renderAlpha(backend, TF2D, 32);
    const opaque1d = await renderAlpha(
      backend,
      {
        dimensions: '1d',
        points: [
          { value: 0.4, color: [1, 1, 1], opacity: 0 },
          { value: 0.6, color: [1, 1, 1], opacity: 10 },
        ],
      },
      4,
    );
    const alphaAlong = cpuModel(block(), TF2D);
    const scene = { camera: CAMERA } as Scene;
    const inner: Vec3 = [-HALF + 2 / N, -HALF + 2 / N, -HALF + 2 / N];
    let checked = 0,
      maxErr = 0,
      throughCore = 0,
      maxAlpha = 0,
      min1d = 1,
      minCoreAlpha = 1,
      maxCoreAlpha = 0;
    for (let y = 0; y < H; y++) {
      for (let x = 0; x < W; x++) {
        // The box-filtered pixel: CPU alpha over a 4 x 4 grid of rays; skip pixels where it varies a lot (silhouettes).
        const sub: number[] = [];
        for (let j = 0; j < 4; j++)
          for (let i = 0; i < 4; i++) {
            const r = reference.cameraRay(scene, W, H, (x + (i + 0.5) / 4) / W, (y + (j + 0.5) / 4) / H);
            sub.push(alphaAlong(r.origin, r.dir));
          }
        const want = sub.reduce((a, b) => a + b) / sub.length;
        maxAlpha = Math.max(maxAlpha, gpu[x + W * y]);
        if (Math.max(...sub) - Math.min(...sub) < 0.15) {
          maxErr = Math.max(maxErr, Math.abs(gpu[x + W * y] - want));
          checked++;
        }
        // Pixels whose centre ray runs through the block's core (a chord of > 4 voxels where the gradient is 0).
        const c = reference.cameraRay(scene, W, H, (x + 0.5) / W, (y + 0.5) / H);
        const [t0, t1] = reference.intersectBox(c.origin, c.dir, inner, inner.map((v) => -v) as Vec3);
        if (t1 - t0 > 4 / N) {
          throughCore++;
          min1d = Math.min(min1d, opaque1d[x + W * y]);
          minCoreAlpha = Math.min(minCoreAlpha, gpu[x + W * y]);
          maxCoreAlpha = Math.max(maxCoreAlpha, gpu[x + W * y]);
        }
      }
    }
    expect(checked).toBeGreaterThan(250);
    expect(maxErr).toBeLessThan(0.03);
    expect(throughCore).toBeGreaterThan(20);
    // Through the core, only the two boundary shells absorb: visible, but far from opaque...
    expect(minCoreAlpha).toBeGreaterThan(0.3);
    expect(maxCoreAlpha).toBeLessThan(0.75);
    // ...while a 1D TF makes the same block opaque there,
    expect(min1d).toBeGreaterThan(0.999);
    // and rays grazing along the boundary shell are denser than any ray through the interior.
    expect(maxAlpha).toBeGreaterThan(maxCoreAlpha + 0.1);
  });
});

describe('EAM with a 2D transfer function: WebGL 2 / WebGPU parity', () => {
  it('gives bit-identical HDR images', async () => {
    const r = await page.run(async ({ core, t }) => {
      const volume = core.createProceduralVolume('blob', 20);
      const out: Float32Array[] = [];
      for (const backend of ['webgl2', 'webgpu']) {
        const ctx = await t.context({ backend, renderer: 'eam', width: 20, height: 16 });
        ctx.setScene(
          t.scene({
            volume,
            seed: 3,
            densityScale: 20,
            camera: { position: [0.7, -0.4, 1.5], target: [0, 0.05, 0], up: [0, 1, 0], fovy: 0.8 },
            transferFunction: {
              dimensions: '2d',
              widgets: [
                { type: 'gaussian', center: [0.5, 0.8], width: [0.2, 0.2], color: [1, 0.6, 0.2], opacity: 2 },
                { type: 'box', min: [0.7, 0], max: [1, 0.4], ramp: [0.1, 0.1], color: [0.2, 0.5, 1], opacity: 1 },
              ],
            },
            environment: { type: 'constant', radiance: [0.3, 0.2, 0.1] },
          }),
        );
        await ctx.renderIterations(4);
        out.push(await ctx.readHDR());
        ctx.dispose();
      }
      let varied = 0;
      for (let i = 4; i < out[0].length; i += 4) if (out[0][i] !== out[0][0]) varied++;
      return { diff: t.sameBits(out[0], out[1]), varied, n: out[0].length / 4 };
    });
    expect(r.varied).toBeGreaterThan(r.n / 4);
    expect(r.diff).toBe(0);
  });
});

describe('2D transfer functions in a RenderContext', () => {
  it('switches between 1D and 2D on one context exactly as fresh contexts render them, and refuses a bad 2D TF', async () => {
    const r = await page.run(async ({ core, t }) => {
      const volume = core.createProceduralVolume('sphere', 16);
      const tf1 = {
        dimensions: '1d',
        points: [
          { value: 0, color: [1, 1, 1], opacity: 0 },
          { value: 1, color: [1, 0.5, 0], opacity: 2 },
        ],
      };
      const tf2 = {
        dimensions: '2d',
        widgets: [{ type: 'gaussian', center: [0.5, 1], width: [0.3, 0.3], color: [0, 0.5, 1], opacity: 8 }],
      };
      const render = async (ctx: any, tf: object) => {
        ctx.updateScene({ transferFunction: tf });
        await ctx.renderIterations(2);
        return ctx.readHDR();
      };
      const fresh = async (tf: object) => {
        const ctx = await t.context({ backend: 'webgl2', renderer: 'eam', width: 12, height: 12 });
        ctx.setScene(t.scene({ volume, densityScale: 5 }));
        const img = await render(ctx, tf);
        ctx.dispose();
        return img;
      };
      const ctx = await t.context({ backend: 'webgl2', renderer: 'eam', width: 12, height: 12 });
      ctx.setScene(t.scene({ volume, densityScale: 5 }));
      const a1 = await render(ctx, tf1),
        a2 = await render(ctx, tf2),
        a3 = await render(ctx, tf1);
      let error = '';
      try {
        ctx.updateScene({ transferFunction: { dimensions: '2d', widgets: [{ ...tf2.widgets[0], opacity: -1 }] } });
      } catch (e) {
        error = `${(e as any).code}: ${(e as Error).message}`;
      }
      const kept = ctx.getScene().transferFunction === tf1;
      ctx.dispose();
      const f1 = await fresh(tf1),
        f2 = await fresh(tf2);
      let pageError = '';
      try {
        await (window as any).vpt.buildScene({
          volume: { procedural: 'sphere', size: 4 },
          transferFunction: { dimensions: '2d', widgets: [{ type: 'blob', color: [1, 1, 1], opacity: 1 }] },
        });
      } catch (e) {
        pageError = (e as Error).message;
      }
      const built = await (window as any).vpt.buildScene({
        volume: { procedural: 'sphere', size: 4 },
        transferFunction: tf2,
      });
      return {
        d1: t.sameBits(a1, f1),
        d2: t.sameBits(a2, f2),
        d3: t.sameBits(a3, f1),
        differ: t.sameBits(f1, f2),
        error,
        kept,
        pageError,
        built: built.transferFunction,
      };
    });
    expect(r.differ).toBeGreaterThan(50); // the two transfer functions give different images
    expect([r.d1, r.d2, r.d3]).toEqual([0, 0, 0]);
    expect(r.error).toMatch(/^invalid-scene: TransferFunction: widget 0: opacity must be non-negative, got -1/);
    expect(r.kept).toBe(true);
    expect(r.pageError).toMatch(/widget 0: unknown widget type "blob"/);
    expect(r.built).toEqual({
      dimensions: '2d',
      widgets: [{ type: 'gaussian', center: [0.5, 1], width: [0.3, 0.3], color: [0, 0.5, 1], opacity: 8 }],
    });
  });
});
