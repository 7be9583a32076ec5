import { describe, expect, it } from 'vitest';
import { tf1d } from './helpers/test-scene.js';
import { DEFAULT_EAM_CUTOFF } from '@vpt/renderer-eam';
import { blueNoiseDim } from '../packages/core/src/shaders/blue-noise.js';
import {
  rasterizeTransferFunction,
  reference,
  TF_RESOLUTION,
  type Sampler,
  type Scene,
  type Vec3,
  createProceduralVolume,
} from '../packages/core/src/index.js';
import { BACKENDS, usePage } from './helpers/session.js';

/**
 * Emission-absorption through a homogeneous cube has a closed form along each ray:
 * L = c·(1 − e^{−σ·ℓ}) + L_bg·e^{−σ·ℓ}, ℓ the chord length. A pixel is the box-filtered
 * mean over its footprint, integrated here with a fine stratified grid.
 */
function analyticPixel(
  scene: Scene,
  w: number,
  h: number,
  x: number,
  y: number,
  color: Vec3,
  sigma: number,
  bg: Vec3,
  sub = 16,
) {
  const box = { min: [-0.5, -0.5, -0.5] as Vec3, max: [0.5, 0.5, 0.5] as Vec3 };
  const acc = [0, 0, 0];
  const acc2 = [0, 0, 0];
  let allInside = true;
  let hits = 0;
  for (let j = 0; j < sub; j++) {
    for (let i = 0; i < sub; i++) {
      const { origin, dir } = reference.cameraRay(scene, w, h, (x + (i + 0.5) / sub) / w, (y + (j + 0.5) / sub) / h);
      const [t0, t1] = reference.intersectBox(origin, dir, box.min, box.max);
      const len = t1 > t0 ? t1 - t0 : 0;
      if (len === 0) allInside = false;
      else hits++;
      const T = Math.exp(-sigma * len);
      for (let c = 0; c < 3; c++) {
        const v = color[c] * (1 - T) + bg[c] * T;
        acc[c] += v;
        acc2[c] += v * v;
      }
    }
  }
  // Pixels whose corners all hit the box have a smooth integrand; edge pixels are noisy.
  for (const [cx, cy] of [
    [0, 0],
    [1, 0],
    [0, 1],
    [1, 1],
  ]) {
    const { origin, dir } = reference.cameraRay(scene, w, h, (x + cx) / w, (y + cy) / h);
    const [t0, t1] = reference.intersectBox(origin, dir, box.min, box.max);
    if (!(t1 > t0)) allInside = false;
  }
  const n = sub * sub;
  const rgb = acc.map((a) => a / n);
  // Spread of the radiance over the pixel footprint: the per-sample standard deviation.
  const std = acc2.map((a2, c) => Math.sqrt(Math.max(0, a2 / n - rgb[c] * rgb[c])));
  return { rgb, std, allInside, allMiss: hits === 0 };
}

const page = usePage();
const W = 24,
  H = 24,
  ITER = 64;

describe.each(BACKENDS)('EAM on %s', (backend) => {
  it.each([0.5, 4])('matches the analytic emission-absorption of a homogeneous cube (sigma = %s)', async (sigma) => {
    const color: Vec3 = [1, 0.5, 0.25];
    const bg: Vec3 = [0.2, 0.3, 0.4];
    const camera = { position: [0.4, 0.5, 2.6] as Vec3, target: [0, 0, 0] as Vec3, up: [0, 1, 0] as Vec3, fovy: 0.9 };
    const gpu: number[] = await page.run(
      async ({ core, t }, backend, W, H, ITER, camera, color, bg, sigma) => {
        const ctx = await t.context({ backend, renderer: 'eam', width: W, height: H, params: { cutoff: 0 } });
        ctx.setScene(
          t.scene({
            volume: core.createProceduralVolume('cube', 8),
            camera,
            densityScale: sigma,
            transferFunction: { dimensions: '1d', points: [{ value: 0, color, opacity: 1 }] },
            environment: { type: 'constant', radiance: bg },
          }),
        );
        return t.finalHDR(ctx, ITER);
      },
      backend,
      W,
      H,
      ITER,
      camera,
      color,
      bg,
      sigma,
    );
    const scene = { camera } as Scene;
    void createProceduralVolume;
    let interior = 0,
      misses = 0,
      maxZ = 0;
    const pixels = Array.from({ length: W * H }, (_, i) =>
      analyticPixel(scene, W, H, i % W, Math.floor(i / W), color, sigma, bg),
    );
    // Background only where the pixel and its 8 neighbours all miss: no jittered sample can clip the cube there.
    const farFromCube = (x: number, y: number) =>
      [-1, 0, 1].every((dy) =>
        [-1, 0, 1].every((dx) => {
          const px = x + dx,
            py = y + dy;
          return px < 0 || py < 0 || px >= W || py >= H || pixels[px + W * py].allMiss;
        }),
      );
    for (let y = 0; y < H; y++) {
      for (let x = 0; x < W; x++) {
        const { rgb, std, allInside } = pixels[x + W * y];
        const i = 4 * (x + W * y);
        if (allInside) {
          interior++;
          // z-score of the GPU's ITER-sample mean; 1e-4 relative covers float32 rounding.
          for (let c = 0; c < 3; c++) {
            const sigmaMean = std[c] / Math.sqrt(ITER) + 1e-4 * rgb[c];
            maxZ = Math.max(maxZ, Math.abs(gpu[i + c] - rgb[c]) / sigmaMean);
          }
        } else if (farFromCube(x, y)) {
          misses++;
          for (let c = 0; c < 3; c++) expect(gpu[i + c]).toBeCloseTo(bg[c], 6);
          expect(gpu[i + 3]).toBe(0);
        }
      }
    }
    expect(interior).toBeGreaterThan(100);
    expect(misses).toBeGreaterThan(10);
    // ~1700 channel values: a max |z| above 5 would be a real bias, not noise.
    expect(maxZ).toBeLessThan(5);
  });
});

/**
 * CPU emission–absorption of the same heterogeneous volume and camera: the kernel's
 * stratified ray march with its random offset per ray (the RNG twin gives the same random
 * numbers), the TF looked up linearly between texels, in float64. On a homogeneous cube the
 * sample placement never matters; here it does, so a march that ignores the offset differs.
 */
function cpuEam(
  scene: Scene,
  w: number,
  h: number,
  iterations: number,
  stepSize: number,
  dims: Sampler = 'pcg',
): Float64Array {
  const sampler = new reference.CpuVolumeSampler(scene);
  const tex = rasterizeTransferFunction(scene.transferFunction, TF_RESOLUTION);
  const lookup = (v: number) => {
    const x = Math.min(1, Math.max(0, v)) * (TF_RESOLUTION - 1);
    const i0 = Math.floor(x),
      i1 = Math.min(i0 + 1, TF_RESOLUTION - 1);
    return [0, 1, 2, 3].map((c) => tex[4 * i0 + c] + (tex[4 * i1 + c] - tex[4 * i0 + c]) * (x - i0));
  };
  const bg = (scene.environment as { radiance: Vec3 }).radiance;
  const out = new Float64Array(4 * w * h);
  for (let y = 0; y < h; y++)
    for (let x = 0; x < w; x++) {
      for (let it = 0; it < iterations; it++) {
        // 'blue-noise': dimensions 0, 1 (jitter) and 2 (offset) of core's SAMPLE_DIMS, from its CPU twin.
        let dim = 0;
        const rng =
          dims === 'pcg'
            ? new reference.CpuRng(x, y, it, scene.seed)
            : ({ next: () => blueNoiseDim(x, y, it, scene.seed, dim++) } as reference.CpuRng);
        const { origin, dir } = reference.jitteredCameraRay(scene, w, h, x, y, rng);
        const [t0, t1] = reference.intersectBox(origin, dir, sampler.box.min, sampler.box.max);
        const color = [0, 0, 0];
        let T = 1;
        if (t0 < t1) {
          const offset = rng.next();
          const n = Math.max(1, Math.ceil((t1 - t0) / stepSize));
          const seg = (t1 - t0) / n;
          for (let k = 0; k < n; k++) {
            const s = t0 + (k + offset) * seg;
            const tf = lookup(sampler.sample([0, 1, 2].map((a) => origin[a] + dir[a] * s) as Vec3));
            const alpha = 1 - Math.exp(-scene.densityScale * tf[3] * seg);
            for (let c = 0; c < 3; c++) color[c] += T * alpha * tf[c];
            T *= 1 - alpha;
          }
        }
        const i = 4 * (x + w * y);
        for (let c = 0; c < 3; c++) out[i + c] += (color[c] + T * bg[c]) / iterations;
        out[i + 3] += (1 - T) / iterations;
      }
    }
  return out;
}

describe.each(BACKENDS)('EAM on %s against a CPU twin', (backend) => {
  it.each(['pcg', 'blue-noise'] as const)(
    'sampler %s: equals a CPU emission–absorption march of a heterogeneous volume, sample for sample',
    async (sampler) => {
      const camera = {
        position: [0.9, 0.5, 1.7] as Vec3,
        target: [0, 0, 0] as Vec3,
        up: [0, 1, 0] as Vec3,
        fovy: 0.45,
      };
      const tf = tf1d([0.1, [0.2, 0.4, 1], 0], [0.4, [1, 0.6, 0.2], 0.8], [0.6, [0.3, 1, 0.4], 0.1], [1, [1, 1, 1], 1]);
      const bg: Vec3 = [0.1, 0.15, 0.2];
      const W = 20,
        H = 16,
        ITER = 3,
        STEP = 1 / 24; // steps of ~1.3 voxels: where the samples fall matters
      const scene: Scene = {
        volume: createProceduralVolume('blob', 16),
        transferFunction: tf,
        camera,
        lights: [],
        environment: { type: 'constant', radiance: bg },
        densityScale: 12,
        seed: 9,
      };
      const gpu: number[] = await page.run(
        async ({ core, t }, backend, W, H, ITER, STEP, camera, tf, bg, sampler) => {
          // sampling: 'exact': the twin samples with float64 trilinear weights (a hardware filter's are coarser).
          const ctx = await t.context({
            backend,
            renderer: 'eam',
            width: W,
            height: H,
            params: { cutoff: 0, stepSize: STEP, sampler },
            sampling: 'exact',
          });
          ctx.setScene(
            t.scene({
              volume: core.createProceduralVolume('blob', 16),
              camera,
              transferFunction: tf,
              densityScale: 12,
              seed: 9,
              environment: { type: 'constant', radiance: bg },
            }),
          );
          return t.finalHDR(ctx, ITER);
        },
        backend,
        W,
        H,
        ITER,
        STEP,
        camera,
        tf,
        bg,
        sampler,
      );
      const cpu = cpuEam(scene, W, H, ITER, STEP, sampler);
      let maxErr = 0,
        covered = 0,
        spread = 0;
      for (let i = 0; i < W * H; i++) {
        for (let c = 0; c < 4; c++) maxErr = Math.max(maxErr, Math.abs(gpu[4 * i + c] - cpu[4 * i + c]));
        if (cpu[4 * i + 3] > 0.2) covered++;
        spread = Math.max(spread, Math.abs(cpu[4 * i] - cpu[4 * i + 2]));
      }
      expect(covered).toBeGreaterThan(W * H * 0.2); // the volume is in view and absorbs
      expect(spread).toBeGreaterThan(0.1); // colours vary (the TF's colour is looked up, not constant)
      // Float32 against float64 over ~30 steps (measured ~1e-6): far below the effect of moving the samples.
      expect(maxErr).toBeLessThan(5e-5);
    },
  );

  it('stops early at the default cutoff, leaving behind at most cutoff × the brightest colour', async () => {
    // A dense blob in front of a white background: rays through it fall below the cutoff
    // early, and the light they leave behind is what ending the march may drop.
    const { withCutoff, without } = await page.run(async ({ core, t }, backend) => {
      const render = async (params: Record<string, number>) => {
        const ctx = await t.context({ backend, renderer: 'eam', width: 16, height: 16, params, sampling: 'exact' });
        ctx.setScene(
          t.scene({
            volume: core.createProceduralVolume('blob', 16),
            densityScale: 400,
            seed: 4,
            environment: { type: 'constant', radiance: [1, 1, 1] },
          }),
        );
        const image = await t.finalHDR(ctx, 1);
        ctx.dispose();
        return image;
      };
      return { withCutoff: await render({}), without: await render({ cutoff: 0 }) };
    }, backend);
    let maxDiff = 0,
      opaque = 0;
    for (let i = 0; i < withCutoff.length; i += 4) {
      for (let c = 0; c < 3; c++) maxDiff = Math.max(maxDiff, Math.abs(withCutoff[i + c] - without[i + c]));
      if (without[i + 3] > 1 - DEFAULT_EAM_CUTOFF) opaque++;
    }
    expect(opaque).toBeGreaterThan(10); // the cutoff is reached on these rays
    expect(maxDiff).toBeLessThanOrEqual(DEFAULT_EAM_CUTOFF * 1.0001); // TF colours and background ≤ 1
  });
});
