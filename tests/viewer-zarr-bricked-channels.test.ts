import fs from 'node:fs';
import path from 'node:path';
import { afterAll, beforeAll, describe, expect, it } from 'vitest';
import {
  startFaultServer,
  tempDir,
  writeZarrFolder,
  type FaultServer,
} from '../packages/loaders/test/zarr-fixtures.js';
import { openViewerPage, type ViewerPage } from './helpers/viewer-page.js';
import { twoFieldBall } from './helpers/uint8-ball.js';

// <vpt-viewer src="….ome.zarr"> on a 2-channel store whose level 0 does not fit the GPU memory
// budget with both channels counted: after the levels that fit, level 0 streams from both
// channels' chunks through the brick cache (one interleaved source, StreamedChannels), and once
// its bricks are resident the image equals the unbricked level 0 (`#level=0`, both channels
// whole) with the same channel settings. Turning a channel off (or the other one) while
// streamed draws the other channel alone: the unbricked level 0 with that channel off, and,
// each channel being drawn purely in its colour, no trace of the channel turned off. The slice
// panes, which draw the element's channel-0 view, stream channel 0 (as tests/viewer-zarr-panes.test.ts).
const N = 128;

// Level 0 takes 4 MiB (two uint8 channels, an rg8 texture), level 1 512 KiB. The volume budget
// is maxGpuBytes less 1 MiB for the transfer function and the small render targets: about
// 2.5 MiB, so level 1 fits and level 0 does not (it would as one channel of 2 MiB); the ball's
// 8 + 8 + 1 non-constant bricks (34³ texels × 2 bytes) fit in the atlas.
const MAX_GPU_BYTES = (1 << 20) + 2.5 * (1 << 20);

const tf = (opacity: number) => ({
  dimensions: '1d',
  points: [
    { value: 0.1, color: [1, 1, 1], opacity: 0 },
    { value: 1, color: [1, 1, 1], opacity },
  ],
});
// Green and magenta: a pixel's red or blue is channel 1's alone, its green channel 0's alone.
const BOTH = [
  { color: [0, 1, 0], enabled: true, transferFunction: tf(0.8), range: [0, 255] },
  { color: [1, 0, 1], enabled: true, transferFunction: tf(0.9), range: [0, 255] },
];
const ONLY0 = [BOTH[0], { ...BOTH[1], enabled: false }];
const ONLY1 = [{ ...BOTH[0], enabled: false }, BOTH[1]];

let A: Uint8Array;
let vp: ViewerPage;
let server: FaultServer;
let root: string;
beforeAll(async () => {
  root = tempDir('vpt-viewer-zarr-bricked-channels-');
  const [a, b] = twoFieldBall(N);
  A = a;
  await writeZarrFolder(
    path.join(root, 'two.ome.zarr'),
    { dims: [N, N, N], type: 'uint8', spacing: [1, 1, 1], images: [[a, b]] },
    { version: '0.5', codec: 'gzip', levels: 3, chunk: [32, 32, 32] },
  );
  server = await startFaultServer(root);
  vp = await openViewerPage();
});
afterAll(async () => {
  await vp?.close();
  await server?.close();
  fs.rmSync(root, { recursive: true, force: true });
});

interface ChannelRun {
  loads: { dims: number[]; level?: { index: number; dims: number[]; final: boolean; bricked?: boolean } }[];
  errors: string[];
  /** Per channel settings in `states`: the image once converged (and every brick resident), and the bricking stats. */
  images: {
    ldr: number[];
    hdr: number[];
    sceneChannels: number;
    sceneDims: number[];
    elementChannels: number;
    bricking: {
      complete: boolean;
      failed: number;
      finest: number;
      gpuBytes: number;
      slots: number;
      resident: number;
      constant: number;
    } | null;
    stats: string | null;
  }[];
}

// Before tone mapping, a channel drawn alone is purely its colour (green: r = b = 0; magenta: g = 0).
/** A MIP viewer on `src` (budget `maxGpuBytes`, or the default) drawn with each of `states` in turn. */
async function run(src: string, maxGpuBytes: number | null, states: unknown[]): Promise<ChannelRun> {
  return vp.page.evaluate(
    async (s: string, budget: number | null, list: string) => {
      const vt = window.vt;
      const settings = JSON.parse(list) as unknown[];
      const el = vt.create(
        {
          src: s,
          renderer: 'mip',
          backend: 'webgl2',
          panels: 'none',
          'max-samples': '2',
          // The renderers' default steps follow the stand-in's dims: fixed, so both renders march alike.
          'renderer-params': '{"stepSize":0.004}',
        },
        'width:32px;height:32px',
      );
      if (budget !== null) el.maxGpuBytes = budget;
      const loads: ChannelRun['loads'] = [];
      el.addEventListener('vpt-load', (e: CustomEvent) => {
        // The defaults are fitted to each level's histogram: the page's settings, from the first level on.
        if (!loads.length) el.channels = settings[0];
        loads.push({ dims: e.detail.dims, level: e.detail.level });
      });
      await el.whenSettled();
      if (budget !== null) for (let i = 0; i < 500 && !loads.some((l) => l.level?.bricked); i++) await vt.frames(1);
      const images: ChannelRun['images'] = [];
      for (const [i, state] of settings.entries()) {
        if (i > 0) el.channels = state;
        await vt.frames(2);
        if (budget !== null) await el.context.whenBricksSettled();
        await vt.frames(10); // the uploads' reset reaches the session's stats
        await vt.converged(el);
        await el.updateComplete;
        const scene = el.context.getScene();
        const b = el.context.stats.bricking;
        images.push({
          ldr: await vt.ldr(el),
          hdr: Array.from((await el.context.readHDR()) as Float32Array),
          sceneChannels: scene.volume.channels ?? 1,
          sceneDims: [...scene.volume.dims],
          elementChannels: el.channels?.length ?? 0,
          bricking: b && {
            complete: b.complete,
            failed: b.failed,
            finest: b.finest,
            gpuBytes: b.gpuBytes,
            slots: b.slots,
            resident: b.resident,
            constant: b.constant,
          },
          stats: vt.shadowText(el, '[part=stats]'),
        });
      }
      const errors = el.__events.filter((e: any) => e.type === 'error').map((e: any) => e.message);
      el.remove();
      return { loads, errors, images };
    },
    src,
    maxGpuBytes,
    JSON.stringify(states),
  );
}

/** The largest difference of two LDR images. */
function compare(a: number[], b: number[]): number {
  expect(a.length).toBe(b.length);
  let worst = 0;
  for (let i = 0; i < a.length; i++) worst = Math.max(worst, Math.abs(a[i] - b[i]));
  return worst;
}
/** Pixels whose colour component `c` is above 0. */
const lit = (img: number[], c: number) => {
  let n = 0;
  for (let i = c; i < img.length; i += 4) if (img[i] > 0) n++;
  return n;
};

describe('<vpt-viewer> streams a multichannel OME-Zarr level 0 beyond the budget as bricks', () => {
  it('both channels bricked from the chunks equal the unbricked level 0; a channel turned off draws the other alone', async () => {
    const url = `${server.url}two.ome.zarr`;
    const requests0 = server.log.length;
    const bricked = await run(url, MAX_GPU_BYTES, [BOTH, ONLY0, ONLY1]);
    const level0 = server.log.slice(requests0).filter((p) => /\/two\.ome\.zarr\/0\/c\//.test(p));
    expect(bricked.errors).toEqual([]);
    expect(bricked.loads.map((l) => [l.level?.index, l.level?.final, l.level?.bricked ?? false])).toEqual([
      [2, false, false],
      [1, false, false],
      [0, true, true],
    ]);
    expect(bricked.loads.at(-1)!.level!.dims).toEqual([N, N, N]);
    for (const img of bricked.images) {
      // The scene holds the stand-in (level 1, both channels); the element keeps its channels.
      expect([img.sceneChannels, img.sceneDims, img.elementChannels]).toEqual([2, [64, 64, 64], 2]);
      expect(img.bricking).toMatchObject({ complete: true, failed: 0 });
      expect(img.bricking!.finest).toBeGreaterThanOrEqual(8);
      expect(img.bricking!.gpuBytes).toBeLessThan(MAX_GPU_BYTES);
      expect(img.stats).toMatch(/level bricked 0 \(\d+\/64 bricks\) of 3/);
    }
    // Both channels' level-0 chunks were read (chunk keys …/c/z/y/x: one channel each).
    const channelOf = (p: string) => p.split('/').at(-4);
    expect(new Set(level0.map(channelOf))).toEqual(new Set(['0', '1']));

    const direct = await run(`${url}#level=0`, null, [BOTH, ONLY0, ONLY1]);
    expect(direct.errors).toEqual([]);
    expect(direct.loads.map((l) => l.dims)).toEqual([[N, N, N]]);
    for (const img of direct.images) {
      expect(img.bricking).toBeNull();
      expect([img.sceneChannels, img.sceneDims]).toEqual([2, [N, N, N]]);
    }
    const [both, only0, only1] = bricked.images.map((i) => i.ldr);
    const [dBoth, dOnly0, dOnly1] = direct.images.map((i) => i.ldr);
    const [hOnly0, hOnly1] = bricked.images.slice(1).map((i) => i.hdr);
    // Something to compare: both colours drawn; streamed, each channel alone draws its colour only.
    expect([lit(direct.images[0].hdr, 0), lit(direct.images[0].hdr, 1)].every((n) => n > 20)).toBe(true);
    expect([lit(hOnly0, 0), lit(hOnly0, 2), lit(hOnly0, 1) > 20]).toEqual([0, 0, true]);
    expect([lit(hOnly1, 1), lit(hOnly1, 0) > 20, lit(hOnly1, 2) > 20]).toEqual([0, true, true]);
    // The bricked filter reads the same voxels (the apron holds the neighbours): the same pixels,
    // up to the hardware filter's weights (one LDR step), for each set of channels drawn.
    expect(compare(both, dBoth)).toBeLessThanOrEqual(1);
    expect(compare(only0, dOnly0)).toBeLessThanOrEqual(1);
    expect(compare(only1, dOnly1)).toBeLessThanOrEqual(1);
    const figures = bricked.images.map(
      (i) =>
        `${i.bricking!.gpuBytes} B, ${i.bricking!.slots} slots, ${i.bricking!.resident} resident, ${i.bricking!.constant} constant`,
    );
    console.log(
      `bricked 2-channel OME-Zarr (128³ uint8, budget ${MAX_GPU_BYTES} B), atlas + tables: both ${figures[0]}; ` +
        `channel 0 ${figures[1]}; channel 1 ${figures[2]}; ${level0.length} level-0 chunk requests`,
    );
  });
  it("the slice panes stream channel 0: the axial pane equals level 0's channel 0 once its bricks are resident", async () => {
    const WINDOW: [number, number] = [128, 256];
    const r = await vp.page.evaluate(
      async (src: string, budget: number, win: [number, number]) => {
        const vt = window.vt as any;
        document.body.style.margin = '0';
        const el = vt.create(
          { src, backend: 'webgl2', panels: 'none', 'max-samples': '1', layout: 'slices' },
          'width:900px;height:400px',
        );
        el.maxGpuBytes = budget;
        const loads: any[] = [];
        el.addEventListener('vpt-load', (e: CustomEvent) => loads.push(e.detail.level));
        await el.whenSettled();
        for (let i = 0; i < 500 && !loads.some((l) => l?.bricked); i++) await vt.frames(1);
        el.sliceWindow = win;
        await el.updateComplete;
        let complete = false;
        for (let i = 0; i < 600 && !complete; i++) {
          await vt.frames(2);
          const b = el.paneContext('axial')?.stats.bricking;
          complete = !!b && b.complete;
        }
        await new Promise((res) => setTimeout(res, 300));
        await vt.frames(4);
        const ctx = el.paneContext('axial');
        const view = el.loadedVolume;
        const out = {
          loads,
          complete,
          size: ctx.size,
          params: ctx.renderer.getParams(),
          hdr: Array.from((await ctx.readHDR()) as Float32Array),
          view: {
            dims: Array.from(view.dims as number[]),
            channels: view.channels ?? 1,
            data: Array.from(view.data as Uint8Array),
          },
          paneChannels: ctx.getScene().volume.channels ?? 1,
          errors: el.__events.filter((e: { type: string }) => e.type === 'error'),
        };
        el.remove();
        return out;
      },
      `${server.url}two.ome.zarr`,
      MAX_GPU_BYTES,
      WINDOW,
    );
    expect(r.errors).toEqual([]);
    expect(r.loads.at(-1)).toMatchObject({ index: 0, bricked: true });
    expect(r.complete).toBe(true);
    // The element's volume: channel 0 of the stand-in (level 1), one channel; so is the pane's scene.
    const [sx, sy] = r.view.dims;
    expect([sx, r.view.channels, r.paneChannels]).toEqual([64, 1, 1]);
    // Axial cuts z at the stand-in's layer k: world z through its centre, the border of level 0's
    // layers 2k and 2k + 1 (float rounding picks either); each pixel one of the nearest voxels.
    const k = r.params.index as number;
    const w = (d: number) => Math.min(1, Math.max(0, (d - (WINDOW[0] - WINDOW[1] / 2)) / WINDOW[1]));
    const cands = (p: number, n: number, size: number) => {
      const s = ((p + 0.5) / size) * n;
      return [...new Set([Math.floor(s - 1e-4), Math.floor(s + 1e-4)])].filter((c) => c >= 0 && c < n);
    };
    const { width: W, height: H } = r.size;
    let worst0 = 0,
      worstView = 0;
    for (let j = 0; j < H; j++)
      for (let i = 0; i < W; i++) {
        const got = r.hdr[4 * (i + W * j)];
        let best = Infinity;
        for (const z of [2 * k, 2 * k + 1])
          for (const x of cands(i, N, W))
            for (const y of cands(j, N, H)) best = Math.min(best, Math.abs(got - w(A[x + N * (y + N * z)])));
        worst0 = Math.max(worst0, best);
        let bestV = Infinity;
        for (const x of cands(i, sx, W))
          for (const y of cands(j, sy, H))
            bestV = Math.min(bestV, Math.abs(got - w(r.view.data[x + sx * (y + sy * k)])));
        worstView = Math.max(worstView, bestV);
      }
    expect(worst0).toBeLessThan(1e-6);
    // The stand-in's own slice is not what is shown.
    expect(worstView).toBeGreaterThan(0.01);
  });
});
