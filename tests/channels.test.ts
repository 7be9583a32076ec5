import { describe, expect, it } from 'vitest';
import {
  createVolume,
  rasterizeTransferFunction,
  reference,
  TF_RESOLUTION,
  type ChannelSettings,
  type Scene,
  type TransferFunction,
  type Vec3,
} from '../packages/core/src/index.js';
import { tf1d } from './helpers/test-scene.js';
import { zSummary } from './helpers/mcrt-stats.js';
import { BACKENDS, usePage } from './helpers/session.js';

/**
 * Multichannel volumes (scene/channels.ts) in every renderer on both backends: a channel scene
 * of one channel gives the scalar path's bits (EAM, ISO, MCRT); EAM's mixture and MIP's
 * per-channel maxima against CPU twins with 1–4 channels; ISO's surfaces on their channels
 * against the scalar renders of each channel; a channel whose TF has opacity 0 leaves the
 * image of the others; MCRT's mixture against a scalar volume holding the same medium (z-test).
 */
const page = usePage({ mcrt: true });

const N = 16;
const W = 20,
  H = 16;
const CAMERA = { position: [0.9, 0.5, 1.6] as Vec3, target: [0, 0, 0] as Vec3, up: [0, 1, 0] as Vec3, fovy: 0.5 };

/** Four smooth uint8 fields (Gaussian blobs at different centres and widths), interleaved channel-fastest. */
function fields(): Uint8Array[] {
  const centres: [number, number, number, number][] = [
    [0.4, 0.5, 0.5, 0.22],
    [0.62, 0.42, 0.55, 0.18],
    [0.5, 0.65, 0.4, 0.2],
    [0.35, 0.35, 0.62, 0.16],
  ];
  return centres.map(([cx, cy, cz, r]) => {
    const d = new Uint8Array(N * N * N);
    for (let z = 0; z < N; z++)
      for (let y = 0; y < N; y++)
        for (let x = 0; x < N; x++) {
          const q = ((x + 0.5) / N - cx) ** 2 + ((y + 0.5) / N - cy) ** 2 + ((z + 0.5) / N - cz) ** 2;
          d[x + N * (y + N * z)] = Math.round(255 * Math.exp(-q / (r * r)));
        }
    return d;
  });
}
const FIELDS = fields();
function interleave(parts: Uint8Array[]): number[] {
  const out: number[] = new Array(parts.length * N * N * N);
  for (let i = 0; i < N * N * N; i++) for (let k = 0; k < parts.length; k++) out[k + parts.length * i] = parts[k][i];
  return out;
}

const TFS: TransferFunction[] = [
  tf1d([0.1, [1, 0.3, 0.2], 0], [0.5, [1, 0.6, 0.3], 0.7], [1, [1, 1, 0.8], 1]),
  tf1d([0.05, [0.2, 1, 0.3], 0], [0.6, [0.3, 1, 0.6], 0.9], [1, [0.8, 1, 1], 1]),
  tf1d([0.2, [0.2, 0.4, 1], 0], [0.7, [0.4, 0.5, 1], 0.5], [1, [1, 1, 1], 0.8]),
  tf1d([0.1, [1, 1, 0.2], 0], [0.5, [1, 0.9, 0.1], 0.6], [1, [1, 1, 1], 1]),
];

type Image = number[];

interface RenderSpec {
  backend: string;
  renderer: string;
  /** Interleaved channel data (channels > 0), or one scalar field. */
  voxels: number[];
  channels: number;
  /** Scene channel settings; absent: the scalar path with `transferFunction`. */
  settings?: ChannelSettings[];
  transferFunction?: TransferFunction;
  params?: object;
  iterations: number;
  sampling?: 'exact' | 'fast';
}

async function render(spec: RenderSpec): Promise<Image> {
  return page.run(
    async ({ core, t }, spec, n, camera, w, h) => {
      const volume = core.createVolume([n, n, n], 'uint8', new Uint8Array(spec.voxels), [1, 1, 1], spec.channels);
      const ctx = await t.context({
        backend: spec.backend as 'webgl2',
        renderer: spec.renderer,
        width: w,
        height: h,
        params: spec.params ?? {},
        sampling: spec.sampling ?? 'exact',
      });
      const scene = t.scene({
        volume,
        camera,
        densityScale: 10,
        environment: { type: 'constant', radiance: [0.1, 0.12, 0.15] },
        ...(spec.transferFunction ? { transferFunction: spec.transferFunction } : {}),
      });
      ctx.setScene({ ...scene, ...(spec.settings ? { channels: spec.settings } : {}) });
      return t.finalHDR(ctx, spec.iterations);
    },
    spec,
    N,
    CAMERA,
    W,
    H,
  );
}

function bitsDiffer(a: Image, b: Image): number {
  const u = new Uint32Array(new Float32Array(a).buffer),
    v = new Uint32Array(new Float32Array(b).buffer);
  let n = 0;
  for (let i = 0; i < u.length; i++) if (u[i] !== v[i]) n++;
  return u.length === v.length ? n : -1;
}
function maxAbsDiff(a: ArrayLike<number>, b: ArrayLike<number>, comps = [0, 1, 2, 3]): number {
  let m = 0;
  for (let i = 0; i < a.length; i += 4) for (const c of comps) m = Math.max(m, Math.abs(a[i + c] - b[i + c]));
  return m;
}

/** A CPU channel: its sampler (range 0..255 as uint8 maps) and its rasterized TF, colour replaced when given. */
function cpuChannels(count: number, settings: ChannelSettings[]) {
  return settings.slice(0, count).map((s, k) => {
    const sampler = new reference.CpuVolumeSampler({ volume: createVolume([N, N, N], 'uint8', FIELDS[k]) });
    const tex = rasterizeTransferFunction(s.transferFunction, TF_RESOLUTION);
    if (s.color) for (let i = 0; i < TF_RESOLUTION; i++) tex.set(s.color, 4 * i);
    const lookup = (v: number) => {
      const x = Math.min(1, Math.max(0, v)) * (TF_RESOLUTION - 1);
      const i0 = Math.floor(x),
        i1 = Math.min(i0 + 1, TF_RESOLUTION - 1);
      return [0, 1, 2, 3].map((c) => tex[4 * i0 + c] + (tex[4 * i1 + c] - tex[4 * i0 + c]) * (x - i0));
    };
    return { sampler, lookup };
  });
}

const cpuScene = { camera: CAMERA, seed: 1 } as Scene;

/** CPU EAM of the channels' mixture: sigma = sum of opacities, colour the opacity-weighted mean (the kernel's march and RNG). */
function cpuEamMixture(count: number, settings: ChannelSettings[], iterations: number, step: number): Float64Array {
  const ch = cpuChannels(count, settings);
  const box = ch[0].sampler.box;
  const bg = [0.1, 0.12, 0.15];
  const out = new Float64Array(4 * W * H);
  for (let y = 0; y < H; y++)
    for (let x = 0; x < W; x++)
      for (let it = 0; it < iterations; it++) {
        const rng = new reference.CpuRng(x, y, it, 1);
        const { origin, dir } = reference.jitteredCameraRay(cpuScene, W, H, x, y, rng);
        const [t0, t1] = reference.intersectBox(origin, dir, box.min, box.max);
        const color = [0, 0, 0];
        let T = 1;
        if (t0 < t1) {
          const offset = rng.next();
          const n = Math.max(1, Math.ceil((t1 - t0) / step));
          const seg = (t1 - t0) / n;
          for (let k = 0; k < n; k++) {
            const s = t0 + (k + offset) * seg;
            const p = [0, 1, 2].map((a) => origin[a] + dir[a] * s) as Vec3;
            const tfs = ch.map((c) => c.lookup(c.sampler.sample(p)));
            const sigma = tfs.reduce((a, t) => a + t[3], 0);
            const alpha = 1 - Math.exp(-10 * sigma * seg);
            for (let c = 0; c < 3; c++) {
              const mixed = sigma > 0 ? tfs.reduce((a, t) => a + (t[3] / sigma) * t[c], 0) : 0;
              color[c] += T * alpha * mixed;
            }
            T *= 1 - alpha;
          }
        }
        const i = 4 * (x + W * y);
        for (let c = 0; c < 3; c++) out[i + c] += (color[c] + T * bg[c]) / iterations;
        out[i + 3] += (1 - T) / iterations;
      }
  return out;
}

/** CPU MIP of the channels: per channel the maximum along the pixel-centre ray, then sum of opacity × colour at it. */
function cpuMipChannels(count: number, settings: ChannelSettings[], iterations: number, step: number): Float64Array {
  const ch = cpuChannels(count, settings);
  const box = ch[0].sampler.box;
  const out = new Float64Array(4 * W * H);
  for (let y = 0; y < H; y++)
    for (let x = 0; x < W; x++) {
      const { origin, dir } = reference.cameraRay(cpuScene, W, H, (x + 0.5) / W, (y + 0.5) / H);
      const [t0, t1] = reference.intersectBox(origin, dir, box.min, box.max);
      if (!(t0 < t1)) continue;
      const best = ch.map(() => 0);
      for (let it = 0; it < iterations; it++) {
        const rng = new reference.CpuRng(x, y, it, 1);
        const offset = rng.next();
        const n = Math.max(1, Math.ceil((t1 - t0) / step));
        const seg = (t1 - t0) / n;
        for (let k = 0; k < n; k++) {
          const s = t0 + (k + offset) * seg;
          const p = [0, 1, 2].map((a) => origin[a] + dir[a] * s) as Vec3;
          ch.forEach((c, j) => (best[j] = Math.max(best[j], c.sampler.sample(p))));
        }
      }
      const i = 4 * (x + W * y);
      ch.forEach((c, j) => {
        const t = c.lookup(best[j]);
        for (let q = 0; q < 3; q++) out[i + q] += t[3] * t[q];
      });
      out[i + 3] = 1;
    }
  return out;
}

const settingsOf = (count: number, extra: Partial<ChannelSettings>[] = []): ChannelSettings[] =>
  TFS.slice(0, count).map((transferFunction, k) => ({ transferFunction, ...(extra[k] ?? {}) }));

describe('one channel through the multichannel path gives the scalar path, bit for bit', () => {
  for (const backend of BACKENDS)
    for (const renderer of ['eam', 'iso', 'mcrt'])
      it(`${renderer} on ${backend}`, async () => {
        const params = renderer === 'iso' ? { surfaces: [{ value: 0.45, color: [0.9, 0.7, 0.5] }], jitter: false } : {};
        const base = {
          backend,
          renderer,
          voxels: Array.from(FIELDS[0]),
          channels: 1,
          transferFunction: TFS[0],
          params,
          iterations: 3,
        };
        const scalar = await render(base);
        const one = await render({ ...base, settings: settingsOf(1) });
        expect(scalar.every(Number.isFinite)).toBe(true);
        expect(bitsDiffer(scalar, one)).toBe(0);
        // The fast path too (r8unorm, hardware filter), EAM only.
        if (renderer === 'eam') {
          const fastScalar = await render({ ...base, sampling: 'fast' });
          const fastOne = await render({ ...base, sampling: 'fast', settings: settingsOf(1) });
          expect(bitsDiffer(fastScalar, fastOne)).toBe(0);
        }
      });
  for (const backend of BACKENDS)
    it(`slice on ${backend}: a 2-channel scene shows its first drawn channel as the scalar scene of it`, async () => {
      const scalar = await render({
        backend,
        renderer: 'slice',
        voxels: Array.from(FIELDS[1]),
        channels: 1,
        transferFunction: TFS[1],
        iterations: 1,
      });
      const two = await render({
        backend,
        renderer: 'slice',
        voxels: interleave(FIELDS.slice(0, 3)),
        channels: 3,
        settings: settingsOf(3, [{ enabled: false }]),
        iterations: 1,
      });
      expect(bitsDiffer(scalar, two)).toBe(0);
      let lit = 0;
      for (let i = 0; i < scalar.length; i += 4) if (scalar[i] > 0.05) lit++;
      expect(lit).toBeGreaterThan(10);
    });
  it('a 2-channel volume with channel 1 disabled renders channel 0 alone (EAM, WebGL 2)', async () => {
    const scalar = await render({
      backend: 'webgl2',
      renderer: 'eam',
      voxels: Array.from(FIELDS[0]),
      channels: 1,
      settings: settingsOf(1),
      iterations: 3,
    });
    const two = await render({
      backend: 'webgl2',
      renderer: 'eam',
      voxels: interleave(FIELDS.slice(0, 2)),
      channels: 2,
      settings: settingsOf(2, [{}, { enabled: false }]),
      iterations: 3,
    });
    expect(bitsDiffer(scalar, two)).toBe(0);
  });
});

describe('EAM and MIP with 1–4 channels against CPU twins, the same bits on both backends', () => {
  const STEP = 1 / 20;
  for (const renderer of ['eam', 'mip'])
    for (const count of [1, 2, 3, 4])
      it(`${renderer}, ${count} channel${count > 1 ? 's' : ''}`, async () => {
        // Channel 1 takes a display colour (replacing its TF's colours).
        const settings = settingsOf(count, [{}, { color: [0.1, 0.9, 0.9] }]);
        const spec = {
          renderer,
          voxels: interleave(FIELDS.slice(0, count)),
          channels: count,
          settings,
          // The CPU twins draw the march offsets from the PCG stream (EAM's default sampler is blue noise).
          params: renderer === 'eam' ? { cutoff: 0, stepSize: STEP, sampler: 'pcg' } : { stepSize: STEP },
          iterations: 3,
        };
        const gl = await render({ ...spec, backend: 'webgl2' });
        const gpu = await render({ ...spec, backend: 'webgpu' });
        const cpu =
          renderer === 'eam' ? cpuEamMixture(count, settings, 3, STEP) : cpuMipChannels(count, settings, 3, STEP);
        expect(gl.every(Number.isFinite)).toBe(true);
        const d = maxAbsDiff(gl, cpu);
        expect(d, `max |GPU − CPU| ${d}`).toBeLessThan(2e-4);
        expect(bitsDiffer(gl, gpu)).toBe(0);
        // Something was drawn: the test can fail.
        let lit = 0;
        for (let i = 0; i < cpu.length; i += 4) if (cpu[i] + cpu[i + 1] + cpu[i + 2] > 0.05) lit++;
        expect(lit).toBeGreaterThan(20);
      });
});

describe('a channel whose TF has opacity 0 leaves what the other channels render alone', () => {
  const zero = tf1d([0, [1, 0, 1], 0], [1, [1, 0, 1], 0]);
  for (const renderer of ['eam', 'mip', 'mcrt'])
    it(renderer, async () => {
      const base = { backend: 'webgl2', renderer, channels: 2, iterations: 3 };
      const withZero = await render({
        ...base,
        voxels: interleave(FIELDS.slice(0, 2)),
        settings: [{ transferFunction: TFS[0] }, { transferFunction: zero }],
      });
      const alone = await render({
        ...base,
        voxels: interleave(FIELDS.slice(0, 2)),
        settings: [{ transferFunction: TFS[0] }, { transferFunction: zero, enabled: false }],
      });
      const both = await render({ ...base, voxels: interleave(FIELDS.slice(0, 2)), settings: settingsOf(2) });
      expect(bitsDiffer(withZero, alone)).toBe(0);
      expect(maxAbsDiff(withZero, both)).toBeGreaterThan(0.02);
    });
});

describe('ISO: surface k lies on channel k', () => {
  it('the nearest crossing of two channel surfaces is the nearer of the two scalar renders (both backends)', async () => {
    const surfaces = [
      { value: 0.45, color: [0.9, 0.5, 0.4] },
      { value: 0.35, color: [0.4, 0.6, 0.9] },
    ];
    const params = (s: object[]) => ({ surfaces: s, jitter: false, output: 'depth' });
    const one = async (k: number) =>
      render({
        backend: 'webgl2',
        renderer: 'iso',
        voxels: Array.from(FIELDS[k]),
        channels: 1,
        transferFunction: TFS[k],
        params: params([surfaces[k]]),
        iterations: 1,
      });
    const a = await one(0),
      b = await one(1);
    const spec = {
      renderer: 'iso',
      voxels: interleave(FIELDS.slice(0, 2)),
      channels: 2,
      settings: settingsOf(2),
      params: params(surfaces),
      iterations: 1,
    };
    const gl = await render({ ...spec, backend: 'webgl2' });
    const gpu = await render({ ...spec, backend: 'webgpu' });
    let wrong = 0,
      hits = 0,
      fromB = 0;
    for (let i = 0; i < gl.length; i += 4) {
      const da = a[i + 3] > 0 ? a[i] : Infinity,
        db = b[i + 3] > 0 ? b[i] : Infinity;
      const want = Math.min(da, db);
      const got = gl[i + 3] > 0 ? gl[i] : Infinity;
      if (got !== want) wrong++;
      if (Number.isFinite(want)) hits++;
      if (db < da) fromB++;
    }
    expect(wrong).toBe(0);
    expect(hits).toBeGreaterThan(40);
    expect(fromB).toBeGreaterThan(5);
    expect(bitsDiffer(gl, gpu)).toBe(0);
  });
});

describe('MCRT: the channels are one mixture (z-test against a scalar volume holding it)', () => {
  const MW = 20,
    MH = 16,
    MN = 64;
  /** Float32 fields so the scalar twin can hold sums exactly enough; ramp TFs (opacity = value × gain). */
  async function mcrt(
    voxels: number[],
    channels: number,
    settings: ChannelSettings[] | null,
    tf: TransferFunction | null,
    seed: number,
  ) {
    return page.run(
      async ({ core, mt, t }, voxels, channels, settings, tf, seed, n, camera, w, h, iterations) => {
        const volume = core.createVolume([n, n, n], 'float32', new Float32Array(voxels), [1, 1, 1], channels);
        volume.valueRange = [0, 1];
        const scene = {
          ...t.scene({
            volume,
            camera,
            ...(tf ? { transferFunction: tf } : {}),
            environment: { type: 'constant', radiance: [0.4, 0.5, 0.7] },
            densityScale: 14,
            seed,
          }),
          lights: [
            { type: 'directional' as const, direction: [-0.5, 1, 0.4] as Vec3, irradiance: [2, 1.8, 1.5] as Vec3 },
          ],
          ...(settings ? { channels: settings } : {}),
        };
        const r = await mt.run({
          backend: 'webgl2',
          width: w,
          height: h,
          iterations,
          scene,
          params: { majorantCellSize: 4 },
        });
        return { mean: r.mean!, se: r.se!, nonFinite: r.nonFinite };
      },
      voxels,
      channels,
      settings,
      tf,
      seed,
      N,
      CAMERA,
      MW,
      MH,
      MN,
    );
  }
  const f = (k: number) => Array.from(FIELDS[k], (x) => x / 255);
  const ramp = (gain: number, color: [number, number, number]) => tf1d([0, color, 0], [1, color, gain]);
  function z(a: { mean: number[]; se: number[] }, b: { mean: number[]; se: number[] }) {
    const out: number[] = [];
    for (let i = 0; i < a.mean.length; i += 4)
      for (let c = 0; c < 3; c++) {
        const se = Math.hypot(a.se[i + c], b.se[i + c]);
        if (se === 0 && a.mean[i + c] === b.mean[i + c]) continue;
        out.push((a.mean[i + c] - b.mean[i + c]) / se);
      }
    return zSummary(out, 3);
  }
  it('different fields, one colour: extinction is the sum', async () => {
    const c: [number, number, number] = [0.85, 0.8, 0.7];
    const d0 = f(0),
      d1 = f(1);
    const mixed = await mcrt(
      d0.flatMap((x, i) => [x, d1[i]]),
      2,
      [{ transferFunction: ramp(1, c) }, { transferFunction: ramp(1, c) }],
      null,
      3,
    );
    // The scalar twin: w = (d0 + d1) / 2 with opacity 2w.
    const w = d0.map((x, i) => (x + d1[i]) / 2);
    const single = await mcrt(w, 1, null, ramp(2, c), 4);
    const onlyFirst = await mcrt(d0, 1, null, ramp(1, c), 5);
    expect(mixed.nonFinite || single.nonFinite).toBe(false);
    const s = z(mixed, single),
      s0 = z(mixed, onlyFirst);
    const msg = `mixture vs scalar ${JSON.stringify(s)}; vs channel 0 alone ${JSON.stringify(s0)}`;
    expect(Math.abs(s.meanScaled), msg).toBeLessThan(4);
    expect(s.maxAbs, msg).toBeLessThan(5.5);
    expect(s.n, msg).toBeGreaterThan(300);
    expect(Math.abs(s0.meanScaled), msg).toBeGreaterThan(8);
  });
  it('proportional fields, two colours: albedo is weighted by each channel’s share', async () => {
    const c0: [number, number, number] = [0.95, 0.3, 0.2],
      c1: [number, number, number] = [0.2, 0.3, 0.95];
    const d0 = f(0);
    // Channel 1 = half of channel 0: shares 2/3 and 1/3 everywhere, albedo (2 c0 + c1) / 3.
    const mixed = await mcrt(
      d0.flatMap((x) => [x, x / 2]),
      2,
      [{ transferFunction: ramp(1, c0) }, { transferFunction: ramp(1, c1) }],
      null,
      6,
    );
    const share = [0, 1, 2].map((k) => (2 * c0[k] + c1[k]) / 3) as [number, number, number];
    const even = [0, 1, 2].map((k) => (c0[k] + c1[k]) / 2) as [number, number, number];
    const single = await mcrt(d0, 1, null, ramp(1.5, share), 7);
    const unweighted = await mcrt(d0, 1, null, ramp(1.5, even), 8);
    const s = z(mixed, single),
      sEven = z(mixed, unweighted);
    const msg = `mixture vs share-weighted ${JSON.stringify(s)}; vs plain mean ${JSON.stringify(sEven)}`;
    expect(Math.abs(s.meanScaled), msg).toBeLessThan(4);
    expect(s.maxAbs, msg).toBeLessThan(5.5);
    expect(Math.abs(sEven.meanScaled), msg).toBeGreaterThan(8);
  });
});

describe('the compact fast path (rg8unorm / rgba8unorm, hardware filter)', () => {
  for (const count of [2, 4])
    it(`EAM with ${count} channels agrees with the exact path and across backends`, async () => {
      const spec = {
        renderer: 'eam',
        voxels: interleave(FIELDS.slice(0, count)),
        channels: count,
        settings: settingsOf(count),
        params: { cutoff: 0, stepSize: 1 / 20 },
        iterations: 3,
      };
      const exact = await render({ ...spec, backend: 'webgl2' });
      const fast = await render({ ...spec, backend: 'webgl2', sampling: 'fast' });
      const fastGpu = await render({ ...spec, backend: 'webgpu', sampling: 'fast' });
      const d = maxAbsDiff(exact, fast);
      // The texture unit's 8-bit filter weights against float64-exact ones.
      expect(d, `max |fast − exact| ${d}`).toBeLessThan(0.02);
      expect(maxAbsDiff(fast, fastGpu)).toBeLessThan(0.02);
    });
});
