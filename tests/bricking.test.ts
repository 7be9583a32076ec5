import { beforeAll, describe, expect, it } from 'vitest';
import { installBrickingHelpers, type BrickRenderOptions } from './helpers/bricking-in-page.js';
import { zSummary } from './helpers/mcrt-stats.js';
import { BACKENDS, usePage } from './helpers/session.js';

/**
 * Bricked volumes (core/src/bricking): a volume held as bricks in an atlas with a page table
 * renders like the same volume in one texture. The test volume is uint8 [72, 60, 52] (partial
 * bricks on every axis at brick size 16), exactly 0 outside a ball, so corner bricks are
 * constant and take no slot.
 */
const page = usePage();
beforeAll(async () => {
  await installBrickingHelpers(page().page);
});

const render = (o: BrickRenderOptions) => page().page.evaluate((o) => window.bt.render(o), o);

/** [72, 60, 52]: partial bricks on every axis at brick size 16; the ball leaves the corners empty. */
const LUMPY = { dims: [72, 60, 52] as [number, number, number], radius: 0.4 };
/** [96, 96, 80] with a small ball: most bricks are empty, so its level-0 bricks fit in less than the plain volume takes. */
const SPARSE = { dims: [96, 96, 80] as [number, number, number], radius: 0.22 };

function maxAbsDiff(a: number[], b: number[]): number {
  let m = 0;
  for (let i = 0; i < a.length; i++) m = Math.max(m, Math.abs(a[i] - b[i]));
  return m;
}

describe.each(BACKENDS)('bricked volumes (%s)', (backend) => {
  it.each(['eam', 'mip', 'iso'])(
    '%s: exact sampling of a fully resident bricked volume gives the unbricked image',
    async (renderer) => {
      const base = { backend, renderer, sampling: 'exact' as const, size: 32, iterations: 3, ...LUMPY };
      const plain = await render({ ...base, bricking: 'off' });
      const bricked = await render({ ...base, bricking: 'force' });
      expect(bricked.bricking).not.toBeNull();
      const b = bricked.bricking!;
      expect(b.complete).toBe(true);
      expect(b.finest).toBe(5 * 4 * 4); // every level-0 brick served by its own data
      expect(b.constant).toBeGreaterThan(0); // the empty corners take no slot
      expect(plain.bricking).toBeNull();
      expect(bricked.nonFinite || plain.nonFinite).toBe(false);
      expect(Math.max(...plain.hdr)).toBeGreaterThan(0.05); // something to compare
      // Same texels, same weights, same arithmetic: bit for bit.
      expect(maxAbsDiff(bricked.hdr, plain.hdr)).toBe(0);
    },
  );

  it('uploads at most brickUploadsPerFrame bricks a frame, restarts accumulation at every residency change, and ends at the settled image', async () => {
    const o = {
      backend,
      renderer: 'eam',
      sampling: 'exact' as const,
      size: 24,
      iterations: 2,
      ...LUMPY,
      bricking: 'force' as const,
      uploadsPerFrame: 4,
    };
    const streamed = await page().page.evaluate((o) => window.bt.stream(o), o);
    const settled = await render(o);
    const log = streamed.log;
    let prev = { iterations: 0, uploaded: 0, held: 0 };
    for (const f of log) {
      expect(f.uploaded - prev.uploaded).toBeLessThanOrEqual(4);
      // A frame that changed what is held started a new estimate; any other frame added one sample.
      expect(f.iterations).toBe(f.held > prev.held ? 1 : prev.iterations + 1);
      prev = f;
    }
    expect(prev.uploaded).toBe(settled.bricking!.uploaded);
    expect(log.filter((f, i) => f.uploaded > (i ? log[i - 1].uploaded : 0)).length).toBeGreaterThanOrEqual(
      Math.ceil(prev.uploaded / 4),
    );
    expect(maxAbsDiff(streamed.hdr, settled.hdr)).toBe(0);
  });

  it('a volume streamed from a multiscale source renders like the bricked volume; a failed brick read warns and leaves a coarser level in its place', async () => {
    // EAM's default step derives from the scene's volume, here the coarsest level [9, 8, 7]
    // (docs/architecture.md, "Bricked volumes"): the direct render is given that step,
    // DEFAULT_EAM_STEP_VOXELS (1 voxel) of the stand-in's largest side.
    const o = {
      backend,
      renderer: 'eam',
      sampling: 'exact' as const,
      size: 24,
      iterations: 2,
      ...LUMPY,
      bricking: 'off' as const,
    };
    const direct = await render({ ...o, bricking: 'force', params: { stepSize: 1 / 9 } });
    const streamed = await page().page.evaluate((o) => window.bt.streamed(o, null), o);
    expect(streamed.bricking!.complete).toBe(true);
    expect(streamed.bricking!.finest).toBe(5 * 4 * 4);
    expect(streamed.warnings).toEqual([]);
    // The box comes from level 0 (the stand-in is the coarsest level): equal up to the float rounding of the box.
    expect(maxAbsDiff(streamed.hdr, direct.hdr)).toBeLessThan(1e-5);
    const failing = await page().page.evaluate((o) => window.bt.streamed(o, [31, 15, 15]), o); // level-0 brick [2, 1, 1], inside the ball
    expect(failing.codes).toEqual(['brick-load-failed']);
    expect(failing.warnings[0]).toMatch(/brick \[2, 1, 1\] of level 0.*HTTP 404/);
    expect(failing.bricking).toMatchObject({ complete: true, failed: 1, finest: 5 * 4 * 4 - 1 });
    expect(failing.hdr.every(Number.isFinite)).toBe(true);
    expect(maxAbsDiff(failing.hdr, direct.hdr)).toBeGreaterThan(1e-3); // that region shows level 1
  });

  it('a lost context rebuilds the bricked volume (reloading its bricks) and renders the same image', async () => {
    const r = await page().page.evaluate(async (backend) => {
      const o = {
        backend,
        renderer: 'eam',
        sampling: 'exact' as const,
        size: 16,
        iterations: 2,
        dims: [72, 60, 52] as [number, number, number],
        radius: 0.4,
        bricking: 'force' as const,
      };
      const ctx = await window.bt.context(o);
      ctx.setScene(window.bt.scene(o));
      await ctx.whenBricksSettled();
      await ctx.renderIterations(2);
      const want = Array.from(await ctx.readHDR());
      await ctx.backend.simulateLoss(30);
      const afterLoss = ctx.stats.bricking!;
      const settled = await ctx.whenBricksSettled();
      await ctx.renderIterations(2);
      const got = Array.from(await ctx.readHDR());
      ctx.dispose();
      return { want, got, uploadedAfterLoss: afterLoss.uploaded, settled };
    }, backend);
    expect(r.uploadedAfterLoss).toBe(0); // a new, empty cache
    expect(r.settled!.complete).toBe(true);
    expect(r.settled!.uploaded).toBeGreaterThan(0);
    expect(maxAbsDiff(r.got, r.want)).toBe(0);
  });

  it('eam: the hardware-filtered bricked volume agrees with the unbricked one within the filter precision', async () => {
    const base = { backend, renderer: 'eam', sampling: 'fast' as const, size: 32, iterations: 3, ...LUMPY };
    const plain = await render({ ...base, bricking: 'off' });
    const bricked = await render({ ...base, bricking: 'force' });
    expect(bricked.bricking?.complete).toBe(true);
    // The texture unit's weights are computed from other coordinates (atlas vs whole volume).
    expect(maxAbsDiff(bricked.hdr, plain.hdr)).toBeLessThan(1e-4);
  });
});

describe('bricked volumes: bad budgets (webgl2)', () => {
  it('a budget without room for the coarsest level refuses the scene with limit-exceeded and keeps rendering the previous one', async () => {
    const r = await page().page.evaluate(async () => {
      const { core } = window.vpt;
      const t = window.t;
      const W = 8;
      const ctx = await t.context({
        backend: 'webgl2',
        renderer: 'eam',
        width: W,
        height: W,
        bricking: 'auto',
        brickSize: 16,
        maxGpuBytes: W * W * 16 * 4 + 256 * 256 * 16 + 3000, // 3000 bytes for a volume: the 8³ float32 blob, not one 18³ uint8 slot
      });
      const small = t.scene({ volume: core.createProceduralVolume('blob', 8), densityScale: 20 });
      ctx.setScene(small);
      const before = Array.from(await ctx.readHDR());
      let error: { code: string; message: string } | null = null;
      try {
        ctx.setScene({ ...small, volume: window.bt.volume([72, 60, 52], 0.4) });
      } catch (e) {
        error = { code: (e as { code: string }).code, message: (e as Error).message };
      }
      await ctx.renderIterations(1);
      const after = Array.from(await ctx.readHDR());
      const out = { error, before, after, dims: ctx.getScene()!.volume.dims, bricking: ctx.stats.bricking };
      ctx.dispose();
      return out;
    });
    expect(r.error?.code).toBe('limit-exceeded');
    expect(r.error?.message).toMatch(/maxGpuBytes.*coarsest level/);
    expect(r.dims).toEqual([8, 8, 8]);
    expect(r.bricking).toBeNull();
    expect(r.after).toEqual(r.before);
    expect(Math.max(...r.after)).toBeGreaterThan(0);
  });
});

/** Per-pixel z-scores of two Monte Carlo runs (pixels both estimate exactly, e.g. background only, are skipped). */
function compareRuns(
  a: { mean: number[] | null; se: number[] | null },
  b: { mean: number[] | null; se: number[] | null },
) {
  const z: number[] = [];
  for (let i = 0; i < a.mean!.length; i += 4) {
    if (a.se![i] === 0 && b.se![i] === 0 && a.mean![i] === b.mean![i]) continue;
    for (let c = 0; c < 3; c++) z.push((a.mean![i + c] - b.mean![i + c]) / Math.hypot(a.se![i + c], b.se![i + c]));
  }
  return zSummary(z, 3);
}

describe('bricked volumes above the memory budget (MCRT, webgl2)', () => {
  const mcrt = {
    backend: 'webgl2' as const,
    renderer: 'mcrt',
    sampling: 'fast' as const,
    size: 16,
    iterations: 64,
    frames: true,
    ...SPARSE,
  };

  it('a volume over the budget is bricked, not downsampled, and agrees by z-scores with the unbricked render', async () => {
    const plain = await render({ ...mcrt, bricking: 'off', seed: 1 });
    const bricked = await render({ ...mcrt, bricking: 'auto', volumeBytes: 600_000, seed: 2 });
    const b = bricked.bricking!;
    expect(b).not.toBeNull();
    expect(bricked.dims).toEqual(SPARSE.dims); // not downsampled
    expect(bricked.plainVolumeBytes).toBeGreaterThan(600_000); // the volume alone exceeds the budget…
    expect(bricked.gpuVolumeBytes).toBeLessThanOrEqual(600_000); // …its bricks do not
    expect(b.complete).toBe(true);
    expect(b.finest).toBe(6 * 6 * 5); // every level-0 brick served by its own data (or its constant)
    expect(bricked.nonFinite || plain.nonFinite).toBe(false);
    const s = compareRuns(bricked, plain);
    expect(Math.abs(s.meanScaled), JSON.stringify(s)).toBeLessThan(4);
    expect(s.maxAbs, JSON.stringify(s)).toBeLessThan(5.5);
    expect(Math.max(...plain.mean!)).toBeGreaterThan(0.2);
  });

  it('with the atlas too small for level 0, coarser bricks serve the rest and the majorant grid still bounds them (grid vs one global majorant)', async () => {
    const base = { ...mcrt, ...LUMPY, bricking: 'force' as const, volumeBytes: 40 * 18 ** 3 + 2000 };
    const grid = await render({ ...base, params: { majorantGrid: true, tracking: 'delta' }, seed: 3 });
    const global = await render({ ...base, params: { majorantGrid: false, tracking: 'delta' }, seed: 4 });
    const b = grid.bricking!;
    expect(b.slots).toBe(40); // 40 slots of 18³ bytes and the page and level tables
    expect(grid.gpuVolumeBytes).toBeLessThanOrEqual(40 * 18 ** 3 + 2000);
    expect(b.complete).toBe(true);
    expect(b.finest).toBeLessThan(5 * 4 * 4); // some level-0 bricks are served by a coarser level
    expect(b.finest).toBeGreaterThan(0);
    expect(global.bricking).toEqual(b); // the same residency in both runs
    const s = compareRuns(grid, global);
    expect(Math.abs(s.meanScaled), JSON.stringify(s)).toBeLessThan(4);
    expect(s.maxAbs, JSON.stringify(s)).toBeLessThan(5.5);
  });
});
