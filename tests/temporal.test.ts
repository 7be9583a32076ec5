import fs from 'node:fs';
import { describe, expect, it } from 'vitest';
import { rgbRmse as rmse } from './helpers/mcrt-stats.js';
import { BACKENDS, usePage } from './helpers/session.js';

/**
 * Temporal reuse across camera changes (docs/architecture.md, "Temporal reuse"): the first frame
 * after a small rotation is closer to the new view's converged image than a plain reset; at rest
 * the history fades, so the image is the plain estimate (within its noise, then bit for bit);
 * disoccluded pixels take no history; WebGL 2 and WebGPU agree bit for bit.
 */
const page = usePage();

type SceneDesc = Record<string, unknown> & { renderer: string; rendererParams?: Record<string, unknown> };
const headDesc = (renderer: 'mcrt' | 'eam'): SceneDesc => {
  const d = JSON.parse(
    fs.readFileSync(new URL(`../apps/gallery/scenes/head-${renderer}.json`, import.meta.url), 'utf8'),
  );
  d.volume = { sidecar: '/data/mri_head_volpack_brainsmall_128x128x84_uint8.json' };
  return d;
};

/**
 * In the page: the head scene `d` at camera A (its own) and B (A orbited by `angle` about the
 * target's vertical axis), a context with temporal reuse and one without.
 */
type Run = {
  /** B converged (plain, its own seed). */
  ref: number[];
  /** B after one iteration from a reset (plain). */
  plain1: number[];
  /** B one iteration after a move from A (64 iterations), with reuse. */
  reused1: number[];
  /** B's temporal state after that (hit share, samples). */
  state1: number[];
};

describe('temporal reuse', () => {
  for (const renderer of ['mcrt', 'eam'] as const) {
    it(`brings the first frame after a small rotation closer to the converged view than a reset (${renderer}, head 64²)`, async () => {
      const r: Run = await page().page.evaluate(
        async (d, refIterations) => {
          const { core } = window.vpt;
          const make = (temporal: boolean) =>
            core.RenderContext.create({
              backend: 'webgl2',
              width: 64,
              height: 64,
              renderer: window.vpt.createRenderer(d.renderer, d.rendererParams),
              temporal,
            });
          const sceneA = await window.vpt.buildScene({ ...d, seed: 3 }, location.origin + '/');
          const sceneB = { ...sceneA, camera: window.t.orbit(sceneA.camera, 0.05) };
          const plainCtx = await make(false);
          plainCtx.setScene({ ...sceneB, seed: 11 });
          await plainCtx.renderIterations(refIterations);
          const ref = Array.from(await plainCtx.readHDR());
          plainCtx.setScene(sceneB);
          await plainCtx.renderIterations(1);
          const plain1 = Array.from(await plainCtx.readHDR());
          plainCtx.dispose();
          const ctx = await make(true);
          ctx.setScene(sceneA);
          await ctx.renderIterations(64);
          ctx.setScene(sceneB);
          ctx.iterate(1);
          const reused1 = Array.from(await ctx.readHDR());
          const state1 = Array.from((await ctx.readTemporalState())!);
          ctx.dispose();
          return { ref, plain1, reused1, state1 };
        },
        headDesc(renderer),
        renderer === 'mcrt' ? 256 : 128,
      );
      expect(r.reused1.every(Number.isFinite)).toBe(true);
      const plain = rmse(r.plain1, r.ref),
        reused = rmse(r.reused1, r.ref);
      const took = r.state1.filter((v, i) => i % 4 === 1 && v > 1).length;
      console.log(
        `${renderer} head 64², first frame after a 0.05 rad orbit: RMSE reset ${plain.toFixed(4)}, reuse ${reused.toFixed(4)} (×${(reused / plain).toFixed(2)}), ${took} of 4096 pixels took history`,
      );
      expect(took).toBeGreaterThan(1000);
      // EAM's single sample is already close (little noise), so reuse gains less there.
      expect(reused).toBeLessThan((renderer === 'mcrt' ? 0.7 : 0.9) * plain);
    }, 600_000);
  }

  it('resamples the history by Catmull-Rom: after a half-pixel turn about the eye it is closer to the new view than bilinear (EAM head 64²)', async () => {
    // A camera turned about its own position maps the old image onto the new one whatever the depth
    // (a homography, here ≈ a shift by half a pixel), so the history alone, made exact by 128 samples,
    // should equal the new view's converged image but for the resampling, where bilinear blurs most.
    const r = await page().page.evaluate(async (d) => {
      const { core } = window.vpt;
      const S = 64;
      type Options = {
        historyFilter?: 'bilinear' | 'catmull-rom';
        maxHistory?: number;
        fadeSamples?: number;
        viewDecay?: number;
      };
      const make = (temporal: boolean | Options) =>
        core.RenderContext.create({
          backend: 'webgl2',
          width: S,
          height: S,
          renderer: window.vpt.createRenderer(d.renderer, d.rendererParams),
          temporal,
        });
      const sceneA = await window.vpt.buildScene({ ...d, seed: 3 }, location.origin + '/');
      const c = sceneA.camera;
      // Half a pixel's angle at the image centre, about the camera's up axis.
      const a = Math.atan((2 * Math.tan(c.fovy / 2)) / S / 2);
      const f = [c.target[0] - c.position[0], c.target[1] - c.position[1], c.target[2] - c.position[2]];
      const u = c.up.map((x: number) => x / Math.hypot(...c.up));
      const ud = f[0] * u[0] + f[1] * u[1] + f[2] * u[2];
      const cr = [u[1] * f[2] - u[2] * f[1], u[2] * f[0] - u[0] * f[2], u[0] * f[1] - u[1] * f[0]];
      // Rodrigues' rotation of the view vector f about u by a.
      const rot = f.map((x, i) => x * Math.cos(a) + cr[i] * Math.sin(a) + u[i] * ud * (1 - Math.cos(a)));
      const target = c.position.map((p: number, i: number) => p + rot[i]) as [number, number, number];
      const sceneB = { ...sceneA, camera: { ...c, target } };
      const plain = await make(false);
      plain.setScene({ ...sceneB, seed: 11 });
      await plain.renderIterations(128);
      const ref = Array.from(await plain.readHDR());
      // The new sample the moved context draws (TemporalReuse.sampleBase: sample 128, after the
      // first view's 128), to take out of the blend.
      plain.setSampleStart(128);
      plain.setScene(sceneB);
      await plain.renderIterations(1);
      const cur = Array.from(await plain.readHDR());
      plain.dispose();
      const out: Record<string, { image: number[]; state: number[] }> = {};
      for (const historyFilter of ['bilinear', 'catmull-rom'] as const) {
        // A history that neither fades nor decays: it weighs its 128 samples against the one new one.
        const ctx = await make({ historyFilter, maxHistory: 1024, fadeSamples: 1e6, viewDecay: 1e6 });
        ctx.setScene(sceneA);
        await ctx.renderIterations(128);
        ctx.setScene(sceneB);
        ctx.iterate(1);
        out[historyFilter] = {
          image: Array.from(await ctx.readHDR()),
          state: Array.from((await ctx.readTemporalState())!),
        };
        ctx.dispose();
      }
      return { ref, cur, out };
    }, headDesc('eam'));
    // The history alone, where a pixel took a full one: out = (cur + w·h)/(1 + w), so h = (out·(1 + w) − cur)/w.
    const hist = (k: string) => {
      const { image, state } = r.out[k];
      return (p: number, ch: number) => {
        const w = state[4 * p + 1] - 1;
        return (image[4 * p + ch] * (1 + w) - r.cur[4 * p + ch]) / w;
      };
    };
    const bil = hist('bilinear'),
      cr = hist('catmull-rom');
    let eb = 0,
      ec = 0,
      n = 0;
    for (let p = 0; p < r.ref.length / 4; p++) {
      // Both took the whole footprint's history (w near the 128 samples).
      if (!(r.out.bilinear.state[4 * p + 1] > 100 && r.out['catmull-rom'].state[4 * p + 1] > 100)) continue;
      for (let ch = 0; ch < 3; ch++) {
        expect(Number.isFinite(cr(p, ch))).toBe(true);
        eb += (bil(p, ch) - r.ref[4 * p + ch]) ** 2;
        ec += (cr(p, ch) - r.ref[4 * p + ch]) ** 2;
        n++;
      }
    }
    expect(r.out['catmull-rom'].image.every(Number.isFinite)).toBe(true);
    const rb = Math.sqrt(eb / n),
      rc = Math.sqrt(ec / n);
    console.log(
      `half-pixel turn, history alone against the converged view over ${n / 3} pixels: bilinear RMSE ${rb.toFixed(4)}, Catmull-Rom ${rc.toFixed(4)} (×${(rc / rb).toFixed(2)})`,
    );
    expect(n / 3).toBeGreaterThan(1000);
    expect(rc).toBeLessThan(0.9 * rb);
  }, 600_000);

  it('fades at rest: N iterations after a move equal N without it within the noise, and bit for bit past fadeSamples', async () => {
    const N = 16,
      FADE = 64;
    const r = await page().page.evaluate(
      async (d, N, FADE) => {
        const { core } = window.vpt;
        const make = (temporal: boolean) =>
          core.RenderContext.create({
            backend: 'webgl2',
            width: 32,
            height: 32,
            renderer: window.vpt.createRenderer(d.renderer, d.rendererParams),
            temporal: temporal ? { fadeSamples: FADE } : false,
          });
        const sceneA = await window.vpt.buildScene({ ...d, seed: 5 }, location.origin + '/');
        const c = sceneA.camera;
        const sceneB = {
          ...sceneA,
          camera: {
            ...c,
            position: [c.position[0] + 0.05, c.position[1] + 0.03, c.position[2]] as [number, number, number],
          },
        };
        // Without the move: N single frames (for the standard error per pixel) and their mean, with
        // the random numbers the moved context draws (TemporalReuse.sampleBase: the moved view's
        // samples continue the sequence after the 64 of the first view).
        const plainCtx = await make(false);
        plainCtx.setSampleStart(64);
        plainCtx.setScene(sceneB);
        await plainCtx.precompile();
        const sum = new Float64Array(32 * 32 * 4),
          sq = new Float64Array(32 * 32 * 4);
        for (let k = 0; k < N; k++) {
          plainCtx.iterate(1);
          const f = await plainCtx.readFrame(0);
          for (let i = 0; i < f.length; i++) {
            sum[i] += f[i];
            sq[i] += f[i] * f[i];
          }
        }
        const plainN = Array.from(await plainCtx.readHDR());
        plainCtx.iterate(FADE - N);
        const plainFade = await plainCtx.readHDR();
        // An independent estimate of N samples (another seed): the noise the comparison is made against.
        plainCtx.setScene({ ...sceneB, seed: 77 });
        await plainCtx.renderIterations(N);
        const otherN = Array.from(await plainCtx.readHDR());
        plainCtx.dispose();
        const se = Array.from(sum, (s, i) => {
          const m = s / N;
          return Math.sqrt(Math.max(0, sq[i] / N - m * m) / (N - 1));
        });
        const ctx = await make(true);
        ctx.setScene(sceneA);
        await ctx.renderIterations(64);
        ctx.setScene(sceneB);
        ctx.iterate(N);
        const movedN = Array.from(await ctx.readHDR());
        const stateN = Array.from((await ctx.readTemporalState())!);
        ctx.iterate(FADE - N);
        const movedFade = await ctx.readHDR();
        const differ = window.t.sameBits(movedFade, plainFade);
        ctx.dispose();
        return { plainN, movedN, otherN, se, stateN, differ };
      },
      headDesc('mcrt'),
      N,
      FADE,
    );
    // The history was still in the image at N (some pixels stand for more than N samples)…
    expect(r.stateN.filter((v, i) => i % 4 === 1 && v > N).length).toBeGreaterThan(100);
    // …and the difference is within the plain estimate's standard error: z = Δ / se per channel.
    // …and the difference is within the plain estimate's noise: over the image, z = the RMS difference
    // over the RMS standard error (se per channel from the N frames; two independent estimates give
    // about √2), and no more channels with |Δ| > 3 se than an independent run has.
    let d2 = 0,
      d2Other = 0,
      se2 = 0,
      out = 0,
      outOther = 0,
      count = 0;
    for (let i = 0; i < r.se.length; i++) {
      if (i % 4 === 3) continue;
      const diff = r.movedN[i] - r.plainN[i],
        diffOther = r.otherN[i] - r.plainN[i];
      d2 += diff * diff;
      d2Other += diffOther * diffOther;
      se2 += r.se[i] ** 2;
      count++;
      // Outliers where the frames vary (a channel whose N samples all agree has se = 0: the
      // silhouette, where a miss may take a partly covered history pixel; those count in z above).
      if (r.se[i] > 0 && Math.abs(diff) > 3 * r.se[i]) out++;
      if (r.se[i] > 0 && Math.abs(diffOther) > 3 * r.se[i]) outOther++;
    }
    const z = Math.sqrt(d2 / se2),
      zOther = Math.sqrt(d2Other / se2);
    console.log(
      `after a move and ${N} iterations at rest: z = ${z.toFixed(3)} (an independent run: ${zOther.toFixed(3)}), |z| > 3 in ${out} of ${count} channels (independent: ${outOther})`,
    );
    expect(z).toBeLessThan(0.5);
    expect(out).toBeLessThanOrEqual(outOther);
    expect(r.differ).toBe(0);
  }, 600_000);

  it('gives disoccluded pixels (depth mismatch) no history', async () => {
    // A far wall across the box and a small block in front of it; the camera slides sideways, so the
    // block's parallax uncovers wall pixels whose reprojection lands on the block's (nearer) depth.
    const r = await page().page.evaluate(async () => {
      const { core } = window.vpt;
      const n = 32;
      const data = new Float32Array(n * n * n);
      for (let z = 0; z < n; z++)
        for (let y = 0; y < n; y++)
          for (let x = 0; x < n; x++) {
            const wall = z < 6;
            const block = z >= 22 && z < 30 && x >= 12 && x < 20 && y >= 12 && y < 20;
            data[x + n * (y + n * z)] = wall || block ? 1 : 0;
          }
      const volume = core.createVolume([n, n, n], 'float32', data);
      const ctx = await window.t.context({ backend: 'webgl2', width: 48, height: 48, sampling: 'exact' });
      await ctx.setTemporal(true);
      const base = window.t.scene({
        volume,
        transferFunction: window.t.tf1d([0, [1, 1, 1], 0], [0.5, [0.9, 0.6, 0.3], 1], [1, [0.9, 0.6, 0.3], 1]),
        densityScale: 400,
      });
      const camA = {
        position: [0, 0, 1.6] as [number, number, number],
        target: [0, 0, 0] as [number, number, number],
        up: [0, 1, 0] as [number, number, number],
        fovy: 0.8,
      };
      const camB = {
        ...camA,
        position: [0.22, 0, 1.6] as [number, number, number],
        target: [0.22, 0, 0] as [number, number, number],
      };
      ctx.setScene({ ...base, camera: camA });
      await ctx.renderIterations(16);
      const old = (await ctx.readTemporalGuide())!;
      ctx.setScene({ ...base, camera: camB });
      ctx.iterate(1);
      const reused = await ctx.readHDR();
      const guide = Array.from((await ctx.readTemporalGuide())!);
      const state = Array.from((await ctx.readTemporalState())!);
      // The plain render draws the numbers the moved one did (TemporalReuse.sampleBase: sample 16 on, after camA's 16).
      await ctx.setTemporal(false);
      ctx.setSampleStart(16);
      ctx.setScene({ ...base, camera: camB });
      await ctx.renderIterations(1);
      const plain = await ctx.readHDR();
      const same = Array.from({ length: 48 * 48 }, (_, p) =>
        [0, 1, 2, 3].every((c) => Object.is(reused[4 * p + c], plain[4 * p + c])),
      );
      ctx.dispose();
      return { old: Array.from(old), guide, state, same, camA, camB };
    });
    // The CPU side of the reprojection (float64): each new pixel's point at its depth, projected into A.
    const W = 48;
    const basis = (c: typeof r.camA) => {
      const f = norm(sub(c.target, c.position));
      const rt = norm(cross(f, c.up));
      return { f, r: rt, u: cross(rt, f) };
    };
    const a = basis(r.camA),
      b = basis(r.camB);
    const tan = Math.tan(0.4);
    let rejectedCount = 0,
      agreeing = 0,
      agreeingTook = 0;
    for (let py = 0; py < W; py++)
      for (let px = 0; px < W; px++) {
        const p = py * W + px;
        const depth = r.guide[4 * p + 3];
        if (!(r.state[4 * p] > 0) || !(depth > 0)) continue;
        const sx = (2 * (px + 0.5)) / W - 1,
          sy = 1 - (2 * (py + 0.5)) / W;
        const dir = norm(add(b.f, add(scale(b.r, sx * tan), scale(b.u, sy * tan))));
        const d = sub(add(r.camB.position, scale(dir, depth)), r.camA.position);
        const zc = dot(d, a.f);
        const expected = Math.hypot(...d);
        const qx = (0.5 + (0.5 * dot(d, a.r)) / (zc * tan)) * W - 0.5,
          qy = (0.5 - (0.5 * dot(d, a.u)) / (zc * tan)) * W - 0.5;
        const taps: number[] = [];
        for (const [ox, oy] of [
          [0, 0],
          [1, 0],
          [0, 1],
          [1, 1],
        ]) {
          const tx = Math.floor(qx) + ox,
            ty = Math.floor(qy) + oy;
          if (tx >= 0 && ty >= 0 && tx < W && ty < W) taps.push(r.old[4 * (ty * W + tx) + 3]);
        }
        // Every tap off by over 3× the tolerance (0.1 relative), or a miss: a disocclusion.
        if (taps.length > 0 && taps.every((t) => !(t > 0) || Math.abs(t - expected) > 0.3 * expected)) {
          rejectedCount++;
          expect(r.state[4 * p + 1]).toBe(1);
          expect(r.same[p]).toBe(true);
        }
        if (taps.length === 4 && taps.every((t) => t > 0 && Math.abs(t - expected) < 0.02 * expected)) {
          agreeing++;
          if (r.state[4 * p + 1] > 1) agreeingTook++;
        }
      }
    console.log(
      `disocclusion: ${rejectedCount} uncovered pixels took no history; ${agreeingTook} of ${agreeing} consistent ones did`,
    );
    expect(rejectedCount).toBeGreaterThan(20);
    expect(agreeingTook).toBeGreaterThan(0.9 * agreeing);
    expect(agreeing).toBeGreaterThan(200);
  }, 600_000);

  it('is bit-identical on WebGL 2 and WebGPU (MCRT head, 32²)', async () => {
    const images: number[][] = [];
    for (const backend of BACKENDS) {
      images.push(
        await page().page.evaluate(
          async (d, backend) => {
            const { core } = window.vpt;
            const ctx = await core.RenderContext.create({
              backend,
              width: 32,
              height: 32,
              renderer: window.vpt.createRenderer(d.renderer, d.rendererParams),
              temporal: true,
              sampling: 'exact',
            });
            const sceneA = await window.vpt.buildScene({ ...d, seed: 2 }, location.origin + '/');
            const c = sceneA.camera;
            ctx.setScene(sceneA);
            await ctx.renderIterations(8);
            ctx.setScene({
              ...sceneA,
              camera: { ...c, position: [c.position[0] + 0.08, c.position[1], c.position[2]] },
            });
            ctx.iterate(1);
            const out = [...(await ctx.readHDR()), ...(await ctx.readTemporalState())!];
            ctx.iterate(3);
            out.push(...(await ctx.readHDR()));
            ctx.dispose();
            return out;
          },
          headDesc('mcrt'),
          backend,
        ),
      );
    }
    const [gl, gpu] = images;
    expect(gl.every(Number.isFinite)).toBe(true);
    expect(gl.filter((v, i) => !Object.is(v, gpu[i])).length).toBe(0);
  }, 600_000);
  it('keeps two sets of resolve targets through many moves and a size change (no texture made or freed per update)', async () => {
    const r = await page().page.evaluate(async (d) => {
      const { core } = window.vpt;
      const ctx = await core.RenderContext.create({
        backend: 'webgl2',
        width: 24,
        height: 24,
        renderer: window.vpt.createRenderer(d.renderer, d.rendererParams),
        temporal: true,
      });
      const scene = await window.vpt.buildScene({ ...d, seed: 3 }, location.origin + '/');
      const orbit = (a: number) => ({ ...scene, camera: window.t.orbit(scene.camera, a) });
      const targetBytes: number[] = [];
      let tookHistory = 0;
      for (let k = 0; k < 8; k++) {
        if (k === 5) ctx.setSize(20, 20);
        ctx.setScene(orbit(0.01 * k));
        ctx.iterate(2);
        await ctx.readHDR();
        const state = (await ctx.readTemporalState())!;
        let samples = 0;
        for (let i = 1; i < state.length; i += 4) samples += state[i];
        if (k > 0 && samples / (state.length / 4) > 2.5) tookHistory++;
        targetBytes.push(ctx.stats.gpuBytes.targets);
      }
      ctx.dispose();
      return { targetBytes, tookHistory };
    }, headDesc('eam'));
    // Every move but the first took history, and the targets' bytes stayed those of the first move
    // at each size (two sets of resolve targets, not one more per move).
    expect(r.tookHistory).toBe(7);
    const before = r.targetBytes.slice(1, 5),
      after = r.targetBytes.slice(6);
    expect(new Set(before).size).toBe(1);
    expect(new Set(after).size).toBe(1);
    expect(after[0]).toBeLessThan(before[0]);
  });
});

type V3 = [number, number, number];
const sub = (a: readonly number[], b: readonly number[]): V3 => [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
const add = (a: readonly number[], b: readonly number[]): V3 => [a[0] + b[0], a[1] + b[1], a[2] + b[2]];
const scale = (a: readonly number[], s: number): V3 => [a[0] * s, a[1] * s, a[2] * s];
const dot = (a: readonly number[], b: readonly number[]) => a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
const cross = (a: readonly number[], b: readonly number[]): V3 => [
  a[1] * b[2] - a[2] * b[1],
  a[2] * b[0] - a[0] * b[2],
  a[0] * b[1] - a[1] * b[0],
];
const norm = (a: readonly number[]): V3 => scale(a, 1 / Math.hypot(a[0], a[1], a[2]));
