import { describe, expect, it } from 'vitest';
import type { BrickingStats, ChannelSettings, TransferFunction, Vec3 } from '../packages/core/src/index.js';
import { tf1d } from './helpers/test-scene.js';
import { zSummary } from './helpers/mcrt-stats.js';
import { BACKENDS, usePage } from './helpers/session.js';

/**
 * Bricked multichannel volumes (core/src/bricking with BrickChannels): the atlas holds the
 * drawn channels as components (rg / rgba of the source type), so a bricked channel scene
 * renders like the same scene in one channel texture: bit for bit on the exact path for EAM,
 * MIP and MCRT (global majorant) with 2 and 4 channels on both backends; within the scalar
 * bricked tests' 1e-4 on the hardware filter; one drawn channel = the scalar bricked path bit
 * for bit; the memory budget counts every drawn channel; a streamed multichannel source
 * renders like the in-memory bricks; MCRT's summed bricked grid with level 0 partly resident
 * agrees with one global majorant by z-scores.
 */
const page = usePage();

/** [40, 34, 28] at brick size 16: partial bricks on every axis (3 × 3 × 2 level-0 bricks). */
const DIMS: [number, number, number] = [40, 34, 28];
const W = 20,
  H = 16;
const CAMERA = { position: [0.9, 0.5, 1.6] as Vec3, target: [0, 0, 0] as Vec3, up: [0, 1, 0] as Vec3, fovy: 0.62 };

/** Four smooth uint8 fields (Gaussian blobs at different centres and widths): 0 far from their centres, so some bricks are constant. */
function fields(): Uint8Array[] {
  const centres: [number, number, number, number][] = [
    [0.4, 0.5, 0.5, 0.15],
    [0.62, 0.42, 0.55, 0.12],
    [0.5, 0.62, 0.4, 0.13],
    [0.35, 0.35, 0.62, 0.11],
  ];
  const [nx, ny, nz] = DIMS;
  return centres.map(([cx, cy, cz, r]) => {
    const d = new Uint8Array(nx * ny * nz);
    for (let z = 0; z < nz; z++)
      for (let y = 0; y < ny; y++)
        for (let x = 0; x < nx; x++) {
          const q = ((x + 0.5) / nx - cx) ** 2 + ((y + 0.5) / ny - cy) ** 2 + ((z + 0.5) / nz - cz) ** 2;
          d[x + nx * (y + ny * z)] = Math.round(255 * Math.exp(-q / (r * r)));
        }
    return d;
  });
}
const FIELDS = fields();
function interleave(parts: Uint8Array[]): number[] {
  const n = DIMS[0] * DIMS[1] * DIMS[2];
  const out: number[] = new Array(parts.length * n);
  for (let i = 0; i < n; i++) for (let k = 0; k < parts.length; k++) out[k + parts.length * i] = parts[k][i];
  return out;
}

const TFS: TransferFunction[] = [
  tf1d([0.1, [1, 0.3, 0.2], 0], [0.5, [1, 0.6, 0.3], 0.7], [1, [1, 1, 0.8], 1]),
  tf1d([0.05, [0.2, 1, 0.3], 0], [0.6, [0.3, 1, 0.6], 0.9], [1, [0.8, 1, 1], 1]),
  tf1d([0.2, [0.2, 0.4, 1], 0], [0.7, [0.4, 0.5, 1], 0.5], [1, [1, 1, 1], 0.8]),
  tf1d([0.1, [1, 1, 0.2], 0], [0.5, [1, 0.9, 0.1], 0.6], [1, [1, 1, 1], 1]),
];
function settingsOf(count: number, enabled = [true, true, true, true]): ChannelSettings[] {
  return TFS.slice(0, count).map((tf, k) => ({ transferFunction: tf, enabled: enabled[k] }));
}

interface Spec {
  backend: string;
  renderer: string;
  /** Interleaved channel data and the channel count. */
  voxels: number[];
  channels: number;
  /** Scene channel settings; null: the scalar scene of channel 0 with `transferFunction`. */
  settings: ChannelSettings[] | null;
  transferFunction: TransferFunction;
  bricking: 'off' | 'force' | 'auto';
  sampling: 'exact' | 'fast';
  params?: Record<string, unknown>;
  iterations: number;
  /** Bytes for the volume (maxGpuBytes = this + what the context counts for the targets and the TF). */
  volumeBytes?: number;
  /** Stream the volume through setVolumeSource (its coarsest level as the stand-in). */
  streamed?: boolean;
  /** Per-pixel mean and standard error of single-iteration frames (MCRT z-tests). */
  frames?: boolean;
  seed?: number;
}

interface Result {
  hdr: number[];
  mean: number[] | null;
  se: number[] | null;
  bricking: BrickingStats | null;
  gpuVolumeBytes: number;
  dims: number[];
  codes: string[];
  nonFinite: boolean;
}

async function render(spec: Spec): Promise<Result> {
  return page.run(
    async ({ core, t }, spec, dims, camera, w, h) => {
      const all = core.createVolume(dims, 'uint8', new Uint8Array(spec.voxels), [1, 1, 1.25], spec.channels);
      const volume = spec.settings ? all : core.channelVolume(all, 0);
      const r = window.vpt.createRenderer(spec.renderer, spec.params || {});
      const targets = w * h * 16 * (r.frameFormats.length + 2 * r.accumulationFormats.length + 1) + 256 * 256 * 16;
      const ctx = await t.context({
        backend: spec.backend as 'webgl2',
        renderer: spec.renderer,
        width: w,
        height: h,
        params: spec.params ?? {},
        sampling: spec.sampling,
        bricking: spec.bricking,
        brickSize: 16,
        ...(spec.volumeBytes ? { maxGpuBytes: targets + spec.volumeBytes } : {}),
      });
      const codes: string[] = [];
      ctx.onWarning((wn: { code: string }) => codes.push(wn.code));
      try {
        let sceneVolume = volume;
        if (spec.streamed) {
          const mem = core.inMemoryMultiscaleSource(volume, { coarsestSide: 16 });
          const source = {
            type: mem.type,
            levels: mem.levels,
            channels: mem.channels,
            readLevel: (level: number) => mem.readLevel(level),
            async readRegion(level: number, min: [number, number, number], max: [number, number, number]) {
              await new Promise((resolve) => setTimeout(resolve, 1));
              return mem.readRegion(level, min, max);
            },
          };
          sceneVolume = await source.readLevel(mem.levels.length - 1);
          ctx.setVolumeSource(sceneVolume, source);
        }
        const scene = {
          ...t.scene({
            volume: sceneVolume,
            camera,
            sampling: spec.sampling,
            transferFunction: spec.transferFunction,
            densityScale: 12,
            seed: spec.seed ?? 1,
            environment: { type: 'constant', radiance: [0.1, 0.12, 0.15] },
          }),
          lights: [
            { type: 'directional' as const, direction: [-0.4, 1, 0.3] as Vec3, irradiance: [2, 1.8, 1.5] as Vec3 },
          ],
          ...(spec.settings ? { channels: spec.settings } : {}),
        };
        ctx.setScene(scene);
        await ctx.whenBricksSettled();
        const n = w * h * 4;
        let mean: number[] | null = null,
          se: number[] | null = null,
          nonFinite = false;
        if (spec.frames) {
          ctx.reset();
          const sum = new Float64Array(n),
            sum2 = new Float64Array(n);
          for (let k = 0; k < spec.iterations; k++) {
            ctx.iterate(1);
            const f = await ctx.readFrame();
            for (let j = 0; j < n; j++) {
              if (!Number.isFinite(f[j])) nonFinite = true;
              sum[j] += f[j];
              sum2[j] += f[j] * f[j];
            }
          }
          if (ctx.stats.iterations !== spec.iterations)
            throw new Error('accumulation restarted during the measurement');
          mean = Array.from(sum, (s) => s / spec.iterations);
          se = Array.from(sum2, (s2, j) =>
            Math.sqrt(Math.max(0, s2 / spec.iterations - mean![j] ** 2) / (spec.iterations - 1)),
          );
        } else await ctx.renderIterations(spec.iterations);
        const hdr = await ctx.readHDR();
        return {
          hdr: Array.from(hdr),
          mean,
          se,
          bricking: ctx.stats.bricking,
          gpuVolumeBytes: ctx.stats.gpuBytes.volume,
          dims: [...ctx.getScene()!.volume.dims],
          codes,
          nonFinite: nonFinite || t.hasNonFinite(hdr),
        };
      } finally {
        ctx.dispose();
      }
    },
    spec,
    DIMS,
    CAMERA,
    W,
    H,
  );
}

function bitsDiffer(a: number[], b: number[]): number {
  const u = new Uint32Array(new Float32Array(a).buffer),
    v = new Uint32Array(new Float32Array(b).buffer);
  let n = 0;
  for (let i = 0; i < u.length; i++) if (u[i] !== v[i]) n++;
  return u.length === v.length ? n : -1;
}
function maxAbsDiff(a: number[], b: number[]): number {
  let m = 0;
  for (let i = 0; i < a.length; i++) m = Math.max(m, Math.abs(a[i] - b[i]));
  return m;
}

const PARAMS: Record<string, Record<string, unknown>> = {
  eam: { cutoff: 0, stepSize: 1 / 24 },
  mip: { stepSize: 1 / 24 },
  // One global majorant (the CPU bound of the volume, the same in both runs): the same
  // collisions wherever the sampled values are the same.
  mcrt: { majorantGrid: false, tracking: 'delta' },
  // Surface k on drawn channel k (shaded, so the normals' reads through the bricks count too).
  iso: {
    surfaces: [
      { value: 0.45, color: [0.9, 0.5, 0.4] },
      { value: 0.35, color: [0.4, 0.6, 0.9] },
    ],
    stepSize: 1 / 24,
  },
};
const LEVEL0_BRICKS = 3 * 3 * 2;

function spec(backend: string, renderer: string, count: number, extra: Partial<Spec> = {}): Spec {
  return {
    backend,
    renderer,
    voxels: interleave(FIELDS.slice(0, count)),
    channels: count,
    settings: settingsOf(count),
    transferFunction: TFS[0],
    bricking: 'off',
    sampling: 'exact',
    params: PARAMS[renderer],
    iterations: renderer === 'mcrt' ? 4 : 2,
    ...extra,
  };
}

describe.each(BACKENDS)('bricked channel scenes (%s)', (backend) => {
  for (const renderer of ['eam', 'mip', 'mcrt'])
    for (const count of [2, 4])
      it(`${renderer}, ${count} channels: exact sampling of the fully resident bricks gives the unbricked image bit for bit`, async () => {
        const plain = await render(spec(backend, renderer, count));
        const bricked = await render(spec(backend, renderer, count, { bricking: 'force' }));
        expect(plain.bricking).toBeNull();
        const b = bricked.bricking!;
        expect(b.complete).toBe(true);
        expect(b.finest).toBe(LEVEL0_BRICKS); // every level-0 brick served by its own data
        expect(b.constant).toBeGreaterThan(0); // bricks where every channel is 0 take no slot
        expect(bricked.nonFinite || plain.nonFinite).toBe(false);
        expect(Math.max(...plain.hdr)).toBeGreaterThan(0.05);
        expect(bitsDiffer(bricked.hdr, plain.hdr)).toBe(0);
      });

  it('iso, 2 channels: exact sampling of the fully resident bricks gives the unbricked image bit for bit', async () => {
    const plain = await render(spec(backend, 'iso', 2));
    const bricked = await render(spec(backend, 'iso', 2, { bricking: 'force' }));
    expect(bricked.bricking?.finest).toBe(LEVEL0_BRICKS);
    expect(Math.max(...plain.hdr)).toBeGreaterThan(0.05);
    expect(bitsDiffer(bricked.hdr, plain.hdr)).toBe(0);
  });

  it('eam, 2 and 4 channels: the hardware-filtered bricks agree with the unbricked fast path within the filter precision', async () => {
    for (const count of [2, 4]) {
      const fast = { sampling: 'fast' as const };
      const plain = await render(spec(backend, 'eam', count, fast));
      const bricked = await render(spec(backend, 'eam', count, { ...fast, bricking: 'force' }));
      expect(bricked.bricking?.complete).toBe(true);
      expect(maxAbsDiff(bricked.hdr, plain.hdr)).toBeLessThan(1e-4);
    }
  });

  it('one drawn channel through the bricked channel path = the scalar bricked path, bit for bit (eam, mcrt)', async () => {
    for (const renderer of ['eam', 'mcrt']) {
      const one = await render(
        spec(backend, renderer, 2, { bricking: 'force', settings: settingsOf(2, [true, false]) }),
      );
      const scalar = await render(spec(backend, renderer, 2, { bricking: 'force', settings: null }));
      expect(one.bricking).toEqual(scalar.bricking);
      expect(Math.max(...scalar.hdr)).toBeGreaterThan(0.05);
      expect(bitsDiffer(one.hdr, scalar.hdr)).toBe(0);
    }
  });
});

describe('bricked channel scenes: streaming, budget and limits (webgl2)', () => {
  it('a streamed 4-channel source with 3 drawn (setVolumeSource, MultiscaleSource.channels) renders like the in-memory bricks', async () => {
    const base = spec('webgl2', 'eam', 4, { settings: settingsOf(4, [true, false, true, true]), bricking: 'force' });
    // EAM's default step follows the stand-in; both runs get the same explicit step.
    const direct = await render(base);
    const streamed = await render({ ...base, bricking: 'off', streamed: true });
    expect(streamed.bricking!.complete).toBe(true);
    expect(streamed.bricking!.finest).toBe(LEVEL0_BRICKS);
    expect(streamed.codes).toEqual([]);
    expect(Math.max(...direct.hdr)).toBeGreaterThan(0.05);
    // The box comes from level 0 (the stand-in is the coarsest level): equal up to the float rounding of the box.
    expect(maxAbsDiff(streamed.hdr, direct.hdr)).toBeLessThan(1e-5);
  });

  it("the budget counts every drawn channel: a volume that fits as one channel but not as four is bricked with four ('auto'), downsampled with 'off'", async () => {
    const voxels = DIMS[0] * DIMS[1] * DIMS[2];
    const volumeBytes = 2 * voxels; // one uint8 channel fits (r8unorm), four (rgba8unorm) do not
    const fast = { sampling: 'fast' as const, volumeBytes };
    const one = await render(
      spec('webgl2', 'eam', 4, { ...fast, bricking: 'auto', settings: settingsOf(4, [true, false, false, false]) }),
    );
    expect(one.bricking).toBeNull();
    expect(one.dims).toEqual(DIMS);
    expect(one.gpuVolumeBytes).toBe(voxels);
    const four = await render(spec('webgl2', 'eam', 4, { ...fast, bricking: 'auto' }));
    expect(four.bricking).not.toBeNull();
    expect(four.dims).toEqual(DIMS); // not downsampled
    expect(four.gpuVolumeBytes).toBeLessThanOrEqual(volumeBytes);
    expect(four.bricking!.gpuBytes).toBe(four.gpuVolumeBytes);
    // rgba8unorm slots: 4 bytes a texel, 18³ texels; the page table (one texel per level-0 brick) and the level table (3 × 3 levels).
    expect(four.gpuVolumeBytes - 16 * (LEVEL0_BRICKS + 3 * 3)).toBe(4 * 18 ** 3 * four.bricking!.slots);
    const off = await render(spec('webgl2', 'eam', 4, { ...fast, bricking: 'off' }));
    expect(off.bricking).toBeNull();
    expect(off.codes).toContain('volume-downsampled');
    expect(off.dims).not.toEqual(DIMS);
  });

  it('more than four drawn channels stay a typed error under bricking', async () => {
    const r = await page.run(
      async ({ core, t }, voxels, dims, tf) => {
        const volume = core.createVolume(dims, 'uint8', new Uint8Array(voxels), [1, 1, 1], 5);
        const ctx = await t.context({ backend: 'webgl2', renderer: 'eam', width: 8, height: 8, bricking: 'force' });
        try {
          ctx.setScene({
            ...t.scene({ volume }),
            channels: Array.from({ length: 5 }, () => ({ transferFunction: tf })),
          });
          return { code: 'none', message: '' };
        } catch (e) {
          return { code: (e as { code?: string }).code ?? 'untyped', message: (e as Error).message };
        } finally {
          ctx.dispose();
        }
      },
      interleave([...FIELDS, FIELDS[0]]),
      DIMS,
      TFS[0],
    );
    expect(r.code).not.toBe('none');
    expect(r.code).not.toBe('untyped');
    expect(r.message).toMatch(/MAX_ENABLED_CHANNELS|at most 4/);
  });

  it('mcrt, 2 channels, level 0 partly resident: the summed bricked grid and one global majorant agree by z-scores', async () => {
    const base = {
      ...spec('webgl2', 'mcrt', 2, { bricking: 'force', sampling: 'fast', frames: true, iterations: 64 }),
      volumeBytes: 8 * 2 * 18 ** 3 + 1000, // 8 rg8unorm slots (2 bytes a texel) and the tables
    };
    const grid = await render({ ...base, params: { majorantGrid: true, tracking: 'delta' }, seed: 3 });
    const global = await render({ ...base, params: { majorantGrid: false, tracking: 'delta' }, seed: 4 });
    const b = grid.bricking!;
    expect(b.slots).toBe(8);
    expect(b.complete).toBe(true);
    expect(b.finest).toBeLessThan(LEVEL0_BRICKS); // some level-0 bricks are served by a coarser level
    expect(global.bricking).toEqual(b);
    expect(grid.nonFinite || global.nonFinite).toBe(false);
    const z: number[] = [];
    for (let i = 0; i < grid.mean!.length; i += 4)
      for (let c = 0; c < 3; c++) {
        const d = grid.mean![i + c] - global.mean![i + c];
        const se = Math.hypot(grid.se![i + c], global.se![i + c]);
        if (se === 0 && d === 0) continue; // both exact (background only)
        z.push(se > 0 ? d / se : Infinity);
      }
    const s = zSummary(z, 3);
    expect(Math.abs(s.meanScaled), JSON.stringify(s)).toBeLessThan(4);
    expect(s.maxAbs, JSON.stringify(s)).toBeLessThan(5.5);
  });
});
