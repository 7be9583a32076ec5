import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { afterAll, describe, expect, it } from 'vitest';
import { startFaultServer, writeZarrFolder } from '../packages/loaders/test/zarr-fixtures.js';
import { useViewerPage } from './helpers/viewer-page.js';
import { uint8Ball } from './helpers/uint8-ball.js';

// <vpt-viewer> on a 2-channel NIfTI (dim[5] = 2): every channel is drawn, each through its own
// transfer function fitted to its histogram, in its own colour (channels.ts); the `channels`
// property reads and sets them; the Channels panel lists them and its toggles change the image
// and fire vpt-change. Checked against what the image must be: MIP's channels add (its HDR
// image is the sum of the channels' images alone, each purely in its colour), a channel whose
// transfer function has opacity 0 draws nothing, and EAM of channel 0 alone is the image of a
// single-channel file of that channel with the same function and colour.
const viewer = useViewerPage();
const dir = fs.mkdtempSync(path.join(os.tmpdir(), 'vpt-viewer-channels-'));
afterAll(() => fs.rmSync(dir, { recursive: true, force: true }));

const D = 12;
/** A ball of radius r centred at (cx, 6, 6), peak value `peak`. */
function ball(cx: number, r: number, peak: number): Uint8Array {
  return uint8Ball(D, [cx, 6, 6], r, peak);
}

/** A NIfTI-1 file (uint8, 1 mm) holding these volumes as channels along dim[5] (one: a 3D file). */
function nifti(channels: Uint8Array[]): Uint8Array {
  const out = new Uint8Array(352 + channels.length * D ** 3);
  const v = new DataView(out.buffer);
  v.setInt32(0, 348, true);
  const dims = channels.length > 1 ? [5, D, D, D, 1, channels.length, 1, 1] : [3, D, D, D, 1, 1, 1, 1];
  dims.forEach((d, i) => v.setInt16(40 + 2 * i, d, true));
  v.setInt16(70, 2, true);
  v.setInt16(72, 8, true);
  [1, 1, 1, 1, 1, 1, 1, 1].forEach((p, i) => v.setFloat32(76 + 4 * i, p, true));
  v.setFloat32(108, 352, true);
  out[123] = 2 | 8;
  out.set([0x6e, 0x2b, 0x31, 0], 344);
  channels.forEach((c, k) => out.set(c, 352 + k * D ** 3));
  return out;
}

const c0 = ball(4, 4.5, 250),
  c1 = ball(8, 4, 180);
fs.writeFileSync(path.join(dir, 'two.nii'), nifti([c0, c1]));
fs.writeFileSync(path.join(dir, 'c0.nii'), nifti([c0]));

describe('<vpt-viewer> channels', () => {
  it.each(['webgl2', 'webgpu'])(
    'MIP on %s draws both channels, each in its default colour, added; opacity 0 or disabled draws the others alone',
    async (backend) => {
      const base = viewer().server.mount(dir);
      const r = await viewer().run(
        async (vt, base: string, backend: string) => {
          const el = vt.create(
            { src: `${base}two.nii`, renderer: 'mip', backend, panels: 'none', 'max-samples': '1' },
            'width:32px;height:32px',
          );
          await vt.next(el, 'load');
          await vt.converged(el);
          const hdr = async () => Array.from((await el.context.readHDR()) as Float32Array);
          const show = async (channels: unknown) => {
            el.channels = channels;
            await vt.converged(el);
            return hdr();
          };
          const defaults = el.channels;
          const both = await hdr();
          const scene = el.context.getScene();
          const sceneInfo = { channels: scene.volume.channels, entries: scene.channels.length };
          const only0 = await show([{ enabled: true }, { enabled: false }]);
          const only1 = await show([{ enabled: false }, { enabled: true }]);
          const tf = defaults[1].transferFunction;
          const clear1 = await show([
            {},
            { transferFunction: { ...tf, points: tf.points.map((p: any) => ({ ...p, opacity: 0 })) } },
          ]);
          const read = el.channels;
          // An entry core refuses: vpt-error, and the settings stay.
          el.channels = [{ color: [2, 0, 0] }];
          const afterBad = el.channels;
          const errors = el.__events.filter((e: any) => e.type === 'error').map((e: any) => [e.source, e.message]);
          const changes = el.__events.filter((e: any) => e.type === 'change').length;
          const kind = el.context.backend.kind;
          el.remove();
          return { defaults, both, only0, only1, clear1, read, afterBad, errors, changes, sceneInfo, kind };
        },
        base,
        backend,
      );
      expect(r.kind).toBe(backend);
      expect(r.sceneInfo).toEqual({ channels: 2, entries: 2 });
      expect(r.defaults.map((c: any) => c.enabled)).toEqual([true, true]);
      expect(r.defaults[0].color).not.toEqual(r.defaults[1].color);
      // Each channel's function is fitted to its own histogram: the peaks differ, so do the functions.
      expect(r.defaults[0].transferFunction).not.toEqual(r.defaults[1].transferFunction);
      const lit = (img: number[]) => img.filter((_, i) => i % 4 < 3).some((x) => x > 0.05);
      expect(lit(r.only0) && lit(r.only1)).toBe(true);
      // Alone, each channel is purely its colour (green: r = b = 0; magenta: g = 0, r = b).
      const [g, m] = [r.defaults[0].color, r.defaults[1].color];
      expect([g, m]).toEqual([
        [0, 1, 0],
        [1, 0, 1],
      ]);
      for (let i = 0; i < r.only0.length; i += 4) {
        expect(r.only0[i]).toBe(0);
        expect(r.only0[i + 2]).toBe(0);
        expect(r.only1[i + 1]).toBe(0);
        expect(r.only1[i]).toBe(r.only1[i + 2]);
      }
      // Additive: both = channel 0 alone + channel 1 alone, pixel by pixel.
      let maxDiff = 0;
      for (let i = 0; i < r.both.length; i++)
        if (i % 4 < 3) maxDiff = Math.max(maxDiff, Math.abs(r.both[i] - (r.only0[i] + r.only1[i])));
      expect(maxDiff).toBeLessThan(1e-5);
      expect(r.both).not.toEqual(r.only0);
      // A channel whose function has opacity 0 renders what the other renders alone.
      expect(r.clear1).toEqual(r.only0);
      expect(r.read[1].transferFunction.points.every((p: any) => p.opacity === 0)).toBe(true);
      expect(r.afterBad).toEqual(r.read);
      expect(r.errors).toEqual([['attribute', expect.stringMatching(/color/)]]);
      // Set from outside: no vpt-change (that is for the user's edits).
      expect(r.changes).toBe(0);
    },
  );

  it('EAM of channel 0 alone is the image of a single-channel file of that channel with its function and colour', async () => {
    const base = viewer().server.mount(dir);
    const r = await viewer().run(async (vt, base: string) => {
      const attrs = { renderer: 'eam', backend: 'webgl2', panels: 'none', 'max-samples': '2', denoise: 'off' };
      const el = vt.create({ ...attrs, src: `${base}two.nii` }, 'width:32px;height:32px');
      await vt.next(el, 'load');
      await vt.converged(el);
      const both = await vt.ldr(el);
      el.channels = [{}, { enabled: false }];
      await vt.converged(el);
      const alone = await vt.ldr(el);
      const tf = el.channels[0].transferFunction;
      el.remove();
      const one = vt.create(
        { ...attrs, src: `${base}c0.nii`, 'transfer-function': JSON.stringify(tf) },
        'width:32px;height:32px',
      );
      await vt.next(one, 'load');
      await vt.converged(one);
      const scalar = await vt.ldr(one);
      const single = { channels: one.channels, scene: one.context.getScene().channels ?? null };
      one.remove();
      return { both, alone, scalar, single };
    }, base);
    expect(r.single).toEqual({ channels: null, scene: null });
    const bright = (img: number[]) => img.some((x, i) => i % 4 < 3 && x > 20);
    expect(bright(r.alone)).toBe(true);
    expect(r.alone).toEqual(r.scalar);
    expect(r.both).not.toEqual(r.alone);
  });

  it('ISO and MCRT draw the channels too (a surface per drawn channel in its colour; the channels as one mixture)', async () => {
    const base = viewer().server.mount(dir);
    const r = await viewer().run(async (vt, base: string) => {
      const out: Record<string, unknown> = {};
      for (const renderer of ['iso', 'mcrt']) {
        const el = vt.create(
          { src: `${base}two.nii`, renderer, backend: 'webgl2', panels: 'none', 'max-samples': '2', denoise: 'off' },
          'width:24px;height:24px',
        );
        await vt.next(el, 'load');
        await vt.converged(el);
        const both = await vt.ldr(el);
        const surfacesBoth = el.context.renderer.getParams().surfaces;
        const defaults = el.channels;
        el.channels = [{ enabled: false }, {}];
        await vt.converged(el);
        const only1 = await vt.ldr(el);
        // Pixels green (channel 0's default colour) and magenta (channel 1's) in the image.
        const hues = (img: number[]) => {
          let green = 0,
            magenta = 0;
          for (let i = 0; i < img.length; i += 4) {
            const [r, g, b] = [img[i], img[i + 1], img[i + 2]];
            if (g > r + 40 && g > b + 40) green++;
            if (r > g + 40 && b > g + 40) magenta++;
          }
          return { green, magenta };
        };
        if (renderer === 'iso')
          out.isoSurfaces = {
            both: surfacesBoth,
            only1: el.context.renderer.getParams().surfaces,
            colors: defaults.map((c: any) => c.color),
            firstPoints: defaults.map((c: any) => c.transferFunction.points.slice(0, 2).map((p: any) => p.value)),
            hues: { both: hues(both), only1: hues(only1) },
          };
        out[renderer] = {
          drawn: el.context.getScene().channels.map((c: any) => c.enabled !== false),
          errors: el.__events.filter((e: any) => e.type === 'error').map((e: any) => e.message),
          lit: both.some((x: number, i: number) => i % 4 < 3 && x > 80),
          changed: both.some((x: number, i: number) => x !== only1[i]),
        };
        el.remove();
      }
      return out;
    }, base);
    for (const renderer of ['iso', 'mcrt'])
      expect(r[renderer], renderer).toEqual({ drawn: [false, true], errors: [], lit: true, changed: true });
    // ISO's default surfaces follow the drawn channels: one each, in the channel's colour, at the
    // isovalue its own fitted function suggests (halfway between its first two points).
    const iso = r.isoSurfaces as {
      both: { value: number; color: number[] }[];
      only1: { value: number; color: number[] }[];
      colors: number[][];
      firstPoints: number[][];
      hues: { both: { green: number; magenta: number }; only1: { green: number; magenta: number } };
    };
    const isoValue = (k: number) => (iso.firstPoints[k][0] + iso.firstPoints[k][1]) / 2;
    expect(iso.both.map((s) => s.color)).toEqual(iso.colors);
    iso.both.forEach((s, k) => expect(s.value).toBeCloseTo(isoValue(k), 3));
    expect(iso.only1.map((s) => s.color)).toEqual([iso.colors[1]]);
    expect(iso.only1[0].value).toBeCloseTo(isoValue(1), 3);
    // Both balls show, each in its colour; with channel 0 off only the magenta one.
    expect(iso.hues.both.green).toBeGreaterThan(5);
    expect(iso.hues.both.magenta).toBeGreaterThan(5);
    expect(iso.hues.only1.green).toBe(0);
    expect(iso.hues.only1.magenta).toBeGreaterThan(5);
  });

  it('an OME-Zarr store with a c axis shows every channel (unless its fragment picks one), with its omero names and colours', async () => {
    await writeZarrFolder(path.join(dir, 'two.ome.zarr'), {
      dims: [D, D, D],
      type: 'uint8',
      spacing: [1, 1, 1],
      images: [[c0, c1]],
    });
    await writeZarrFolder(
      path.join(dir, 'named.ome.zarr'),
      { dims: [D, D, D], type: 'uint8', spacing: [1, 1, 1], images: [[c0, c1]] },
      {
        channelInfo: [
          { label: 'nuclei', color: '0000FF' },
          { label: 'membrane <b>', color: 'FF8000' },
        ],
      },
    );
    const base = viewer().server.mount(dir);
    const r = await viewer().run(async (vt, base: string) => {
      const attrs = { renderer: 'mip', backend: 'webgl2', panels: 'none', 'max-samples': '1' };
      const open = async (src: string) => {
        const el = vt.create({ ...attrs, src }, 'width:24px;height:24px');
        await vt.next(el, 'load');
        await vt.converged(el);
        const img = Array.from((await el.context.readHDR()) as Float32Array);
        const scene = el.context.getScene();
        const out = {
          channels: el.channels,
          drawn: scene.channels?.length ?? 0,
          volumeChannels: scene.volume.channels ?? 1,
          errors: el.__events.filter((e: any) => e.type === 'error').map((e: any) => e.message),
          green: img.some((x, i) => i % 4 === 1 && x > 0.05 && img[i - 1] === 0),
          magenta: img.some((x, i) => i % 4 === 0 && x > 0.05 && img[i + 1] === 0),
        };
        el.remove();
        return out;
      };
      const named = vt.create(
        { ...attrs, src: `${base}named.ome.zarr`, panels: 'channels', 'resolution-scale': '0.07' },
        'width:660px;height:160px',
      );
      await vt.next(named, 'load');
      await vt.converged(named);
      await named.updateComplete;
      const names = [...named.shadowRoot.querySelectorAll('[data-channel] label')].map((l: any) =>
        l.textContent.trim(),
      );
      const namedColors = named.channels.map((c: any) => c.color);
      named.remove();
      return {
        zarr: await open(`${base}two.ome.zarr`),
        nifti: await open(`${base}two.nii`),
        picked: await open(`${base}two.ome.zarr#channel=1`),
        names,
        namedColors,
      };
    }, base);
    expect(r.names).toEqual(['nuclei', 'membrane <b>']);
    // sRGB FF8000 in linear RGB: 1, (128/255) through the sRGB curve, 0.
    const g = ((128 / 255 + 0.055) / 1.055) ** 2.4;
    expect(r.namedColors[0]).toEqual([0, 0, 1]);
    expect(r.namedColors[1][0]).toBe(1);
    expect(r.namedColors[1][1]).toBeCloseTo(g, 3);
    expect(r.namedColors[1][2]).toBe(0);
    expect(r.zarr.errors).toEqual([]);
    expect([r.zarr.drawn, r.zarr.volumeChannels]).toEqual([2, 2]);
    // The same voxels as the NIfTI's channels: the same fitted defaults.
    expect(r.zarr.channels).toEqual(r.nifti.channels);
    expect([r.zarr.green, r.zarr.magenta]).toEqual([true, true]);
    expect([r.picked.channels, r.picked.drawn, r.picked.volumeChannels]).toEqual([null, 0, 1]);
  });

  it("an OME-Zarr store's levels are planned for all its channels' bytes, each level read once", async () => {
    // 64³ uint8: level 0 is 256 KiB a channel, level 1 32 KiB. The volume budget is maxGpuBytes
    // less 1 MiB (transfer function) and the render targets: about 340 kB fits one channel of
    // level 0 but not two, so the store loads whole up to level 1 only (level 0 then streams as
    // bricks: tests/viewer-zarr-bricked-channels.test.ts).
    const N = 64;
    const blob = (cx: number) => {
      const v = new Uint8Array(N ** 3);
      for (let z = 0; z < N; z++)
        for (let y = 0; y < N; y++)
          for (let x = 0; x < N; x++)
            v[x + N * (y + N * z)] = Math.max(0, Math.round(250 * (1 - Math.hypot(x - cx, y - 32, z - 32) / 20)));
      return v;
    };
    await writeZarrFolder(
      path.join(dir, 'levels.ome.zarr'),
      { dims: [N, N, N], type: 'uint8', spacing: [1, 1, 1], images: [[blob(24), blob(40)]] },
      { levels: 3, chunk: [32, 32, 32] },
    );
    // Served with a request log: after the first level, the store's channel count is known, so
    // level 1 is one read of both channels (2 chunks), not a channel-0 read first (3).
    const server = await startFaultServer(dir);
    const r = await viewer().run(async (vt, base: string) => {
      const el = vt.create(
        { src: `${base}levels.ome.zarr`, renderer: 'mip', backend: 'webgl2', panels: 'none', 'max-samples': '1' },
        'width:24px;height:24px',
      );
      el.maxGpuBytes = (1 << 20) + 384 * 1024;
      const loads: any[] = [];
      el.addEventListener('vpt-load', (e: CustomEvent) => {
        loads.push(e.detail.level);
        // Level 1 is read whole: a mark in the request log before level 0's streaming reads the store again.
        if (e.detail.level.index === 1) fetch(`${base}levels.ome.zarr/zarr.json?mark`);
      });
      await el.whenSettled();
      await vt.converged(el);
      const scene = el.context.getScene();
      const out = {
        budget: el.context.volumeBudgetBytes,
        loads: loads.map((l: any) => [l.index, l.final, l.bricked ?? false]),
        dims: scene.volume.dims,
        channels: scene.volume.channels,
        errors: el.__events.filter((e: any) => e.type === 'error').map((e: any) => e.message),
      };
      el.remove();
      return out;
    }, server.url);
    const mark = server.queries.indexOf('?mark');
    expect(mark).toBeGreaterThan(0);
    const level1 = server.log
      .slice(0, mark)
      .filter((p) => /levels\.ome\.zarr\/1\//.test(p) && !/\.z(array|attrs|group)$|zarr\.json$/.test(p));
    await server.close();
    expect(level1.length, level1.join(' ')).toBe(2);
    // The premise: one channel of level 0 fits, two do not.
    expect(r.budget).toBeGreaterThan(N ** 3);
    expect(r.budget).toBeLessThan(2 * N ** 3);
    expect(r.errors).toEqual([]);
    expect(r.loads).toEqual([
      [2, false, false],
      [1, false, false],
      [0, true, true],
    ]);
    // The scene's volume: level 1 with both channels (whole, or standing in for the bricks).
    expect([r.dims, r.channels]).toEqual([[32, 32, 32], 2]);
  });

  it('a time series of channels keeps the channel settings from step to step', async () => {
    // NIfTI dim[4] = 2 steps, dim[5] = 2 channels, stored component after component, each a run of the steps.
    const steps = [
      [c0, c1],
      [ball(6, 4.5, 120), ball(7, 3, 250)],
    ];
    const out = new Uint8Array(352 + 4 * D ** 3);
    const v = new DataView(out.buffer);
    v.setInt32(0, 348, true);
    [5, D, D, D, 2, 2, 1, 1].forEach((d, i) => v.setInt16(40 + 2 * i, d, true));
    v.setInt16(70, 2, true);
    v.setInt16(72, 8, true);
    [1, 1, 1, 1, 1, 1, 1, 1].forEach((p, i) => v.setFloat32(76 + 4 * i, p, true));
    v.setFloat32(108, 352, true);
    out[123] = 2 | 8;
    out.set([0x6e, 0x2b, 0x31, 0], 344);
    for (let k = 0; k < 2; k++) for (let t = 0; t < 2; t++) out.set(steps[t][k], 352 + (2 * k + t) * D ** 3);
    fs.writeFileSync(path.join(dir, 'series.nii'), out);
    const base = viewer().server.mount(dir);
    const r = await viewer().run(async (vt, base: string) => {
      const el = vt.create(
        { src: `${base}series.nii`, renderer: 'mip', backend: 'webgl2', panels: 'none', 'max-samples': '1' },
        'width:24px;height:24px',
      );
      await vt.next(el, 'load');
      await vt.converged(el);
      el.channels = [{}, { enabled: false }];
      await vt.converged(el);
      const before = { channels: el.channels, img: await vt.ldr(el), steps: el.timeSteps };
      el.setAttribute('time', '1');
      await vt.next(el, 'change');
      await vt.converged(el);
      const after = { channels: el.channels, img: await vt.ldr(el), drawn: el.context.getScene().channels.length };
      el.remove();
      return { before, after };
    }, base);
    expect(r.before.steps).toBe(2);
    expect(r.after.drawn).toBe(2);
    expect(r.after.channels).toEqual(r.before.channels);
    expect(r.after.img).not.toEqual(r.before.img);
  });

  it('five channels: four drawn by default, the panel will not enable a fifth, nor will the property', async () => {
    fs.writeFileSync(path.join(dir, 'five.nii'), nifti([2, 4, 6, 8, 10].map((cx) => ball(cx, 3, 200))));
    const base = viewer().server.mount(dir);
    const r = await viewer().run(async (vt, base: string) => {
      const el = vt.create(
        {
          src: `${base}five.nii`,
          renderer: 'mip',
          backend: 'webgl2',
          panels: 'channels',
          'max-samples': '1',
          'resolution-scale': '0.07',
        },
        'width:660px;height:160px',
      );
      await vt.next(el, 'load');
      await vt.converged(el);
      await el.updateComplete;
      const toggles = [...el.shadowRoot.querySelectorAll('[data-enable]')].map((t: any) => [t.checked, t.disabled]);
      const before = el.channels.map((c: any) => c.enabled);
      el.channels = [{}, {}, {}, {}, { enabled: true }];
      const after = el.channels.map((c: any) => c.enabled);
      const errors = el.__events.filter((e: any) => e.type === 'error').map((e: any) => e.message);
      const colours = new Set(el.channels.map((c: any) => c.color.join())).size;
      el.remove();
      return { toggles, before, after, errors, colours };
    }, base);
    expect(r.before).toEqual([true, true, true, true, false]);
    expect(r.toggles).toEqual([
      [true, false],
      [true, false],
      [true, false],
      [true, false],
      [false, true],
    ]);
    expect(r.after).toEqual(r.before);
    expect(r.errors).toEqual([expect.stringMatching(/5 channels enabled, at most 4/)]);
    expect(r.colours).toBe(5);
  });

  it('the Channels panel lists the channels; its enable toggle changes the image and fires vpt-change', async () => {
    const base = viewer().server.mount(dir);
    const r = await viewer().run(async (vt, base: string) => {
      const el = vt.create(
        {
          src: `${base}two.nii`,
          renderer: 'mip',
          backend: 'webgl2',
          panels: 'tf channels',
          'max-samples': '1',
          'resolution-scale': '0.07',
        },
        'width:660px;height:160px',
      );
      await vt.next(el, 'load');
      await vt.converged(el);
      const q = (sel: string) => el.shadowRoot.querySelector(sel);
      const rows = [...el.shadowRoot.querySelectorAll('[data-channel]')].map((n: any) => ({
        channel: n.dataset.channel,
        enabled: n.querySelector('[data-enable]').checked,
        colour: n.querySelector('input[type=color]').value,
        editor: !!n.querySelector('vpt-tf-editor')?.histogram,
      }));
      const tfEditorsOutsideChannels = el.shadowRoot.querySelectorAll(
        'details:not(:has([data-channel])) vpt-tf-editor',
      ).length;
      // The panels' rules came with their chunk (panel-styles.ts, adopted into the shadow root).
      const panelDisplay = getComputedStyle(q('.panel')).display;
      const before = Array.from((await el.context.readHDR()) as Float32Array);
      const changes: any[] = [];
      el.addEventListener('vpt-change', (e: CustomEvent) => changes.push(e.detail));
      const toggle = q('[data-channel="1"] [data-enable]') as HTMLInputElement;
      toggle.checked = false;
      toggle.dispatchEvent(new Event('change', { bubbles: true, composed: true }));
      await el.updateComplete;
      await vt.converged(el);
      const after = Array.from((await el.context.readHDR()) as Float32Array);
      const checkedNow = (q('[data-channel="1"] [data-enable]') as HTMLInputElement).checked;
      // The only drawn channel's toggle is not refused by the panel, but core's rule is: at least one drawn.
      const enabled = el.channels.map((c: any) => c.enabled);
      el.remove();
      // A single-channel volume: no Channels panel.
      const one = vt.create(
        {
          src: `${base}c0.nii`,
          renderer: 'mip',
          backend: 'webgl2',
          panels: 'tf channels',
          'max-samples': '1',
          'resolution-scale': '0.07',
        },
        'width:660px;height:160px',
      );
      await vt.next(one, 'load');
      await vt.converged(one);
      const scalarRows = one.shadowRoot.querySelectorAll('[data-channel]').length;
      const scalarEditor = !!one.shadowRoot.querySelector('vpt-tf-editor');
      one.remove();
      return {
        rows,
        panelDisplay,
        tfEditorsOutsideChannels,
        changes,
        enabled,
        checkedNow,
        changed: before.some((x, i) => x !== after[i]),
        scalarRows,
        scalarEditor,
      };
    }, base);
    expect(r.rows.map((x: any) => x.channel)).toEqual(['0', '1']);
    expect(r.panelDisplay).toBe('grid');
    expect(r.rows.every((x: any) => x.enabled && x.editor)).toBe(true);
    expect(r.rows[0].colour).not.toBe(r.rows[1].colour);
    // The Transfer function panel's editor is not drawn for channels: only theirs are shown.
    expect(r.tfEditorsOutsideChannels).toBe(0);
    expect(r.changed).toBe(true);
    expect(r.enabled).toEqual([true, false]);
    expect(r.checkedNow).toBe(false);
    expect(r.changes.map((c: any) => c.property)).toEqual(['channels']);
    expect(r.changes[0].value.map((c: any) => c.enabled)).toEqual([true, false]);
    expect(r.scalarRows).toBe(0);
    expect(r.scalarEditor).toBe(true);
  });
});
