import { describe, expect, it } from 'vitest';
import {
  createProceduralVolume,
  createVolume,
  defaultCamera,
  reference,
  type Scene,
  type Vec3,
} from '../packages/core/src/index.js';
import { defaultStepSize } from '../packages/renderer-mip/src/index.js';
import { readFileSync } from 'node:fs';
import { BACKENDS, usePage } from './helpers/session.js';

/**
 * CPU MIP of the same volume and camera: the straightforward march of the pixel-centre ray
 * with a random offset the kernel documents, with the same random numbers (the RNG twin), in float64.
 */
function cpuMip(scene: Scene, w: number, h: number, iterations: number, stepSize: number): Float64Array {
  const sampler = new reference.CpuVolumeSampler(scene);
  const out = new Float64Array(w * h);
  for (let y = 0; y < h; y++) {
    for (let x = 0; x < w; x++) {
      let best = 0;
      for (let it = 0; it < iterations; it++) {
        const rng = new reference.CpuRng(x, y, it, scene.seed);
        const { origin, dir } = reference.cameraRay(scene, w, h, (x + 0.5) / w, (y + 0.5) / h);
        const [t0, t1] = reference.intersectBox(origin, dir, sampler.box.min, sampler.box.max);
        if (!(t0 < t1)) continue;
        const offset = rng.next();
        const n = Math.max(1, Math.ceil((t1 - t0) / stepSize));
        const seg = (t1 - t0) / n;
        for (let k = 0; k < n; k++) {
          const s = t0 + (k + offset) * seg;
          best = Math.max(best, sampler.sample([0, 1, 2].map((a) => origin[a] + dir[a] * s) as Vec3));
        }
      }
      out[x + w * y] = best;
    }
  }
  return out;
}

const page = usePage();
const W = 24,
  H = 20,
  ITER = 4;

/** A MIP scene: a white transfer function (MIP reads values only), no lights, a black sky. */
function mipScene(volume: Scene['volume'], camera: Scene['camera'], seed: number): Scene {
  return {
    volume,
    transferFunction: { dimensions: '1d', points: [{ value: 0, color: [1, 1, 1], opacity: 1 }] },
    camera,
    lights: [],
    environment: { type: 'constant', radiance: [0, 0, 0] },
    densityScale: 1,
    seed,
  };
}

describe.each(BACKENDS)('MIP on %s', (backend) => {
  it('equals a CPU MIP of a smooth procedural volume', async () => {
    const camera = { position: [0.9, 0.6, 1.6] as Vec3, target: [0, 0, 0] as Vec3, up: [0, 1, 0] as Vec3, fovy: 0.7 };
    const volume = createProceduralVolume('blob', 16);
    const scene = mipScene(volume, camera, 7);
    const gpu: number[] = await page.run(
      async ({ core, t }, backend, W, H, ITER, camera) => {
        const ctx = await t.context({ backend, renderer: 'mip', width: W, height: H });
        ctx.setScene(t.scene({ volume: core.createProceduralVolume('blob', 16), camera, seed: 7 }));
        return t.finalHDR(ctx, ITER);
      },
      backend,
      W,
      H,
      ITER,
      camera,
    );
    const cpu = cpuMip(scene, W, H, ITER, defaultStepSize(scene));
    let maxErr = 0,
      covered = 0;
    for (let i = 0; i < W * H; i++) {
      maxErr = Math.max(maxErr, Math.abs(gpu[4 * i] - cpu[i]));
      expect(gpu[4 * i + 1]).toBe(gpu[4 * i]); // grey
      if (gpu[4 * i + 3] > 0) covered++;
    }
    expect(covered).toBeGreaterThan(W * H * 0.3); // the volume is in view
    expect(maxErr).toBeLessThan(1 / 255); // within 8-bit quantization
  });

  it('equals a CPU MIP of the bundled MRI head', async () => {
    const raw = readFileSync(new URL('../data/mri_head_volpack_brainsmall_128x128x84_uint8.raw', import.meta.url));
    const volume = createVolume([128, 128, 84], 'uint8', new Uint8Array(raw.buffer, raw.byteOffset, raw.byteLength));
    const camera = {
      position: [-1.6, -0.3, 0.5] as Vec3,
      target: [0, 0, 0] as Vec3,
      up: [0, -1, 0] as Vec3,
      fovy: 0.8,
    };
    const scene = mipScene(volume, camera, 3);
    const w = 16,
      h = 16;
    const gpu: number[] = await page.run(
      async ({ t }, backend, w, h, camera) => {
        const volume = await t.loadRaw(
          '/data/mri_head_volpack_brainsmall_128x128x84_uint8.raw',
          [128, 128, 84],
          'uint8',
        );
        const ctx = await t.context({ backend, renderer: 'mip', width: w, height: h });
        ctx.setScene(t.scene({ volume, camera, seed: 3 }));
        return t.finalHDR(ctx, 2);
      },
      backend,
      w,
      h,
      camera,
    );
    const cpu = cpuMip(scene, w, h, 2, defaultStepSize(scene));
    let maxErr = 0,
      bright = 0;
    for (let i = 0; i < w * h; i++) {
      maxErr = Math.max(maxErr, Math.abs(gpu[4 * i] - cpu[i]));
      if (cpu[i] > 0.3) bright++;
    }
    expect(bright).toBeGreaterThan(20);
    expect(maxErr).toBeLessThan(1 / 255);
  });
});

void defaultCamera;
