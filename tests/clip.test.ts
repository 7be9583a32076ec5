import { describe, expect, it } from 'vitest';
import { createProceduralVolume, reference, type Clip, type Scene, type Vec3 } from '../packages/core/src/index.js';
import { clippedAt, maskVolume, nearCut } from './helpers/clip-volumes.js';
import { zSummary } from './helpers/mcrt-stats.js';
import { usePage } from './helpers/session.js';

/**
 * Clipping (scene `clip`: planes and a crop box) in every renderer on both backends. EAM, MIP and
 * MCRT: the banded blob rendered with the clip against the zeroed blob rendered without it (the
 * same medium, helpers/clip-volumes.ts); ISO: a distance-field sphere cut by a plane against the
 * analytic ray–sphere crossings inside the CPU's kept interval; and each clipped image the same
 * bits on WebGL 2 and WebGPU.
 */
const page = usePage({ mcrt: true });

const N = 24;
const VOXEL = 1 / N;
const W = 32,
  H = 32;
const CAMERA = { position: [0.9, 0.55, 1.3] as Vec3, target: [0, 0, 0] as Vec3, up: [0, 1, 0] as Vec3, fovy: 0.75 };

const CLIPS: Record<string, Clip> = {
  plane: { planes: [{ normal: [1, 0.4, 0.2], offset: 0.04 }] },
  box: { box: { min: [-0.3, -0.25, -0.35], max: [0.22, 0.3, 0.2] } },
  both: {
    planes: [
      { normal: [0, 1, 0.3], offset: 0.08 },
      { normal: [-1, 0, -0.2], offset: 0.18 },
    ],
    box: { min: [-0.4, -0.3, -0.3], max: [0.3, 0.4, 0.35] },
  },
};

/** The banded blob (nothing within 1.5 voxels of a cut) and its zeroed twin, as plain arrays for the page. */
function volumesFor(clip: Clip): { banded: number[]; zeroed: number[] } {
  const blob = createProceduralVolume('blob', N);
  const banded = maskVolume(blob, (p) => nearCut(clip, p, 1.5 * VOXEL));
  const zeroed = maskVolume(banded, (p) => clippedAt(clip, p));
  return { banded: Array.from(banded.data as Float32Array), zeroed: Array.from(zeroed.data as Float32Array) };
}

type Image = number[];

/** Render a blob volume given by its voxels with a renderer; `clip` set or not. */
async function render(
  backend: string,
  renderer: string,
  voxels: number[],
  clip: Clip | null,
  iterations: number,
  params: object = {},
): Promise<Image> {
  return page.run(
    async ({ core, t }, backend, renderer, voxels, clip, iterations, params, n, camera, w, h) => {
      const volume = core.createVolume([n, n, n], 'float32', new Float32Array(voxels));
      volume.valueRange = [0, 1];
      const ctx = await t.context({ backend, renderer, width: w, height: h, params, sampling: 'exact' });
      const transferFunction = t.tf1d([0, [1, 0.8, 0.6], 0], [0.5, [0.6, 0.8, 1], 0.6], [1, [1, 1, 1], 1]);
      ctx.setScene({
        ...t.scene({ volume, camera, transferFunction, densityScale: 12 }),
        ...(clip ? { clip } : {}),
      });
      return t.finalHDR(ctx, iterations);
    },
    backend,
    renderer,
    voxels,
    clip,
    iterations,
    params,
    N,
    CAMERA,
    W,
    H,
  );
}

const scene = { camera: CAMERA } as Scene;
const centreRay = (x: number, y: number) => reference.cameraRay(scene, W, H, (x + 0.5) / W, (y + 0.5) / H);

/** The CPU's kept interval of a ray (float64): the volume box, the crop box and each half-space. */
function keptInterval(o: Vec3, d: Vec3, clip: Clip, box = { min: [-0.5, -0.5, -0.5], max: [0.5, 0.5, 0.5] }) {
  let t0 = 0,
    t1 = Infinity;
  for (const b of [box, clip.box].filter((x) => x !== undefined)) {
    for (let i = 0; i < 3; i++) {
      const a = (b.min[i] - o[i]) / d[i],
        c = (b.max[i] - o[i]) / d[i];
      t0 = Math.max(t0, Math.min(a, c));
      t1 = Math.min(t1, Math.max(a, c));
    }
  }
  for (const p of clip.planes ?? []) {
    const den = p.normal[0] * d[0] + p.normal[1] * d[1] + p.normal[2] * d[2];
    const num = p.offset - (p.normal[0] * o[0] + p.normal[1] * o[1] + p.normal[2] * o[2]);
    if (den > 0) t1 = Math.min(t1, num / den);
    else if (den < 0) t0 = Math.max(t0, num / den);
    else if (num < 0) t1 = -1;
  }
  return [t0, t1];
}

function maxAbsDiff(a: Image, b: Image, channels = [0, 1, 2]): number {
  let m = 0;
  for (let i = 0; i < a.length; i += 4) for (const c of channels) m = Math.max(m, Math.abs(a[i + c] - b[i + c]));
  return m;
}
function meanAbsDiff(a: Image, b: Image): number {
  let s = 0;
  for (let i = 0; i < a.length; i += 4) for (let c = 0; c < 3; c++) s += Math.abs(a[i + c] - b[i + c]);
  return s / ((a.length / 4) * 3);
}
function bitsDiffer(a: Image, b: Image): number {
  const x = new Float32Array(a),
    y = new Float32Array(b);
  const u = new Uint32Array(x.buffer),
    v = new Uint32Array(y.buffer);
  let n = 0;
  for (let i = 0; i < u.length; i++) if (u[i] !== v[i]) n++;
  return n;
}

describe('clipping: EAM and MIP against the zeroed volume, and across backends', () => {
  for (const renderer of ['eam', 'mip']) {
    for (const name of ['plane', 'box']) {
      it(`${renderer}, ${name}`, async () => {
        const clip = CLIPS[name];
        const v = volumesFor(clip);
        const iterations = renderer === 'eam' ? 24 : 32;
        const clipped = await render('webgl2', renderer, v.banded, clip, iterations);
        const zeroed = await render('webgl2', renderer, v.zeroed, null, iterations);
        const unclipped = await render('webgl2', renderer, v.banded, null, iterations);
        const gpu = await render('webgpu', renderer, v.banded, clip, iterations);
        expect(clipped.every(Number.isFinite)).toBe(true);
        // The clip removes something visible: the unclipped banded volume differs.
        expect(maxAbsDiff(clipped, unclipped)).toBeGreaterThan(0.1);
        const dMax = maxAbsDiff(clipped, zeroed),
          dMean = meanAbsDiff(clipped, zeroed);
        const msg = `max |Δ| ${dMax}, mean |Δ| ${dMean}`;
        // Same medium; only the march lattices differ (they start at the cut, or at the box).
        expect(dMax, msg).toBeLessThan(renderer === 'mip' ? 0.02 : 0.03);
        expect(dMean, msg).toBeLessThan(0.003);
        expect(bitsDiffer(clipped, gpu)).toBe(0);
        if (renderer === 'mip') {
          // MIP's coverage: the centre ray meets the kept region (CPU interval, away from a grazing ray).
          let wrong = 0,
            covered = 0;
          for (let y = 0; y < H; y++)
            for (let x = 0; x < W; x++) {
              const r = centreRay(x, y);
              const [t0, t1] = keptInterval(r.origin, r.dir, clip);
              if (Math.abs(t1 - t0) < 1e-3) continue;
              const want = t0 < t1 ? 1 : 0;
              covered += want;
              if (clipped[4 * (x + W * y) + 3] !== want) wrong++;
            }
          expect(wrong).toBe(0);
          expect(covered).toBeGreaterThan(50);
        }
      });
    }
  }
});

describe('clipping composes with bricking', () => {
  it('EAM with a box and a plane: a forced brick atlas gives the unbricked image', async () => {
    const clip = CLIPS.both;
    const v = volumesFor(clip);
    const plain = await render('webgl2', 'eam', v.banded, clip, 4);
    const bricked = await page.run(
      async ({ core, t }, voxels, clip, n, camera, w, h) => {
        const volume = core.createVolume([n, n, n], 'float32', new Float32Array(voxels));
        volume.valueRange = [0, 1];
        const ctx = await t.context({
          backend: 'webgl2',
          renderer: 'eam',
          width: w,
          height: h,
          sampling: 'exact',
          bricking: 'force',
          brickSize: 8,
        });
        const transferFunction = t.tf1d([0, [1, 0.8, 0.6], 0], [0.5, [0.6, 0.8, 1], 0.6], [1, [1, 1, 1], 1]);
        ctx.setScene({ ...t.scene({ volume, camera, transferFunction, densityScale: 12 }), clip });
        const settled = await ctx.whenBricksSettled();
        return { image: await t.finalHDR(ctx, 4), bricked: settled !== null };
      },
      v.banded,
      clip,
      N,
      CAMERA,
      W,
      H,
    );
    expect(bricked.bricked).toBe(true);
    expect(maxAbsDiff(plain, bricked.image, [0, 1, 2, 3])).toBeLessThan(1e-6);
  });
});

describe('clipping: ISO', () => {
  const R = 0.3;
  const ISO_CLIPS: Record<string, Clip> = {
    plane: { planes: [{ normal: [1, 0.3, 0], offset: 0.05 }] },
    box: { box: { min: [-0.4, -0.4, -0.4], max: [0.12, 0.1, 0.4] } },
  };
  for (const [name, clip] of Object.entries(ISO_CLIPS))
    it(`a sphere cut by a ${name} shows its surface only on the kept side, at the kept crossing`, async () => {
      const out: Record<string, Image> = {};
      for (const [key, backend, c] of [
        ['clipped', 'webgl2', clip],
        ['webgpu', 'webgpu', clip],
        ['whole', 'webgl2', null],
      ] as const) {
        out[key] = await page.run(
          async ({ t }, backend, clip, n, camera, w, h, r) => {
            const volume = window.tv.sphereDistance(n);
            const params = { surfaces: [{ value: r, color: [1, 1, 1] }], jitter: false, output: 'depth' };
            const ctx = await t.context({ backend, renderer: 'iso', width: w, height: h, params, sampling: 'exact' });
            ctx.setScene({ ...t.scene({ volume, camera }), ...(clip ? { clip } : {}) });
            return t.finalHDR(ctx, 2);
          },
          backend,
          c,
          32,
          CAMERA,
          W,
          H,
          R,
        );
      }
      const voxel = 1 / 32;
      let checked = 0,
        removedHits = 0;
      const errors: string[] = [];
      for (let y = 0; y < H; y++)
        for (let x = 0; x < W; x++) {
          const { origin: o, dir: d } = centreRay(x, y);
          const b = o[0] * d[0] + o[1] * d[1] + o[2] * d[2];
          const disc = b * b - (o[0] ** 2 + o[1] ** 2 + o[2] ** 2 - R * R);
          const [t0, t1] = keptInterval(o, d, clip);
          const crossings = disc > 0 ? [-b - Math.sqrt(disc), -b + Math.sqrt(disc)] : [];
          // Ambiguous: a grazing ray, or a crossing within 1.5 voxels of the kept interval's ends.
          const closest = Math.sqrt(Math.max(0, o[0] ** 2 + o[1] ** 2 + o[2] ** 2 - b * b));
          if (
            Math.abs(closest - R) < voxel ||
            crossings.some((tc) => Math.min(Math.abs(tc - t0), Math.abs(tc - t1)) < 1.5 * voxel)
          )
            continue;
          const kept = crossings.filter((tc) => t0 < t1 && tc > t0 && tc < t1);
          const depth = out.clipped[4 * (x + W * y)];
          const hit = out.clipped[4 * (x + W * y) + 3] === 1;
          checked++;
          if (hit !== kept.length > 0) errors.push(`(${x}, ${y}): hit ${hit}, expected ${kept.length > 0}`);
          else if (hit && Math.abs(depth - kept[0]) > 1.5 * voxel)
            errors.push(`(${x}, ${y}): depth ${depth}, expected ${kept[0]}`);
          // Surface the cut removed: the whole sphere's first crossing (on the removed side) is gone.
          const whole = out.whole[4 * (x + W * y)];
          if (out.whole[4 * (x + W * y) + 3] === 1 && (!hit || depth > whole + 3 * voxel)) removedHits++;
        }
      expect(errors.slice(0, 10).join('\n')).toBe('');
      expect(checked).toBeGreaterThan(0.6 * W * H);
      // The cut removed surface that the whole sphere shows.
      expect(removedHits).toBeGreaterThan(40);
      expect(bitsDiffer(out.clipped, out.webgpu)).toBe(0);
    });
});

describe('clipping: MCRT (the removed region is vacuum)', () => {
  const MW = 24,
    MH = 24,
    MN = 96;
  async function mcrt(
    backend: string,
    voxels: number[],
    clip: Clip | null,
    seed: number,
    iterations: number,
    frames = true,
  ) {
    return page.run(
      async ({ core, mt, t }, backend, voxels, clip, seed, iterations, frames, n, camera, w, h) => {
        const volume = core.createVolume([n, n, n], 'float32', new Float32Array(voxels));
        volume.valueRange = [0, 1];
        const scene = {
          ...t.scene({
            volume,
            camera,
            transferFunction: t.tf1d([0, [0.9, 0.8, 0.7], 0], [0.5, [0.7, 0.9, 0.95], 0.6], [1, [0.95, 0.95, 0.95], 1]),
            environment: { type: 'constant', radiance: [0.4, 0.5, 0.7] },
            densityScale: 20,
            seed,
          }),
          lights: [
            { type: 'directional' as const, direction: [-0.5, 1, 0.4] as Vec3, irradiance: [2, 1.8, 1.5] as Vec3 },
          ],
          ...(clip ? { clip } : {}),
        };
        const r = await mt.run({
          backend,
          width: w,
          height: h,
          iterations,
          frames,
          scene,
          params: { majorantCellSize: 4 },
        });
        return { mean: r.mean, se: r.se, hdr: r.hdr, nonFinite: r.nonFinite };
      },
      backend,
      voxels,
      clip,
      seed,
      iterations,
      frames,
      N,
      CAMERA,
      MW,
      MH,
    );
  }
  it('clipped agrees with the zeroed volume in expectation (per-pixel z-test), on both backends bit for bit', async () => {
    const clip = CLIPS.both;
    const v = volumesFor(clip);
    const a = await mcrt('webgl2', v.banded, clip, 3, MN);
    const b = await mcrt('webgl2', v.zeroed, null, 4, MN);
    const whole = await mcrt('webgl2', v.banded, null, 5, MN);
    expect(a.nonFinite || b.nonFinite).toBe(false);
    const z: number[] = [],
      zWhole: number[] = [];
    for (let i = 0; i < a.mean!.length; i += 4) {
      for (let c = 0; c < 3; c++) {
        const se = Math.hypot(a.se![i + c], b.se![i + c]);
        if (se === 0 && a.mean![i + c] === b.mean![i + c]) continue; // sky alone, exact in both
        z.push((a.mean![i + c] - b.mean![i + c]) / se);
        const seW = Math.hypot(a.se![i + c], whole.se![i + c]);
        if (seW > 0) zWhole.push((a.mean![i + c] - whole.mean![i + c]) / seW);
      }
    }
    const s = zSummary(z, 3),
      sWhole = zSummary(zWhole, 3);
    const msg = `clipped vs zeroed ${JSON.stringify(s)}; clipped vs unclipped ${JSON.stringify(sWhole)}`;
    // No aggregate bias (4σ) and no outlier beyond 5.5σ over the few hundred channel values of the medium.
    expect(Math.abs(s.meanScaled), msg).toBeLessThan(4);
    expect(s.maxAbs, msg).toBeLessThan(5.5);
    expect(s.n, msg).toBeGreaterThan(300);
    // The test can fail: against the unclipped volume the same statistic is far out.
    expect(Math.abs(sWhole.meanScaled), msg).toBeGreaterThan(8);
    const gl = await mcrt('webgl2', v.banded, clip, 7, 4, false);
    const gpu = await mcrt('webgpu', v.banded, clip, 7, 4, false);
    expect(bitsDiffer(gl.hdr, gpu.hdr)).toBe(0);
  });
});
