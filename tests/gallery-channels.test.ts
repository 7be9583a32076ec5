import fs from 'node:fs';
import { fileURLToPath } from 'node:url';
import { describe, expect, it } from 'vitest';
import { useGalleryServer } from './helpers/gallery-server.js';
import { recordPageErrors } from './helpers/page-errors.js';

// The gallery's multichannel and labelled entries (issue 24): "CT chest with lung
// segmentation" (the pyradiomics lung2 CT with its label map, both from `pnpm data:fetch`) and
// "2-channel microscopy" (a real 2-channel brain stack from the imaris-ims-file-reader sdist,
// as the OME-Zarr store `pnpm data:fetch` writes, with a `c` axis), and the
// fluorescence time series (nellie's yeast mitochondria, a 4D NRRD) that plays with the viewer's
// time toolbar. Each is skipped, its title saying why, where its data has not been fetched.
//
// What is checked here: the entry is listed, opens in <vpt-viewer> with the dataset's volume
// (dims, type, channels as the manifest says), the CT entry sets the viewer's `labels` property
// to the label volume's URL, and that label volume loads through the viewer's loaders on the CT's
// grid (uint8, the ids 0 and 1), and the scene the viewer draws holds it with a table naming
// label 1; the 2-channel store shows both channels with the label, colour and window of
// each channel's sidecar (through the store's omero metadata).
const FETCHED = fileURLToPath(new URL('../data/fetched/', import.meta.url));
const CT = 'ct_chest_pyradiomics_lung2_512x512x61_int16';
const LABELS = 'ct_chest_pyradiomics_lung2_label_512x512x61_uint8';
const ctFetched = [CT, LABELS].every(
  (n) => fs.existsSync(`${FETCHED}${n}.raw`) && fs.existsSync(`${FETCHED}${n}.json`),
);

// The 2-channel store: imaris-ims-file-reader's brain_crop3.ims (Imaris resolution level 1, both
// channels), written by `pnpm data:fetch` from the two verified raw channels and their sidecars.
const STORE = 'micro_brain_ims_2ch.ome.zarr';
const CHANNEL_SIDECARS = [0, 1].map((c) => `${FETCHED}micro_brain_ims_ch${c}_336x317x51_uint16.json`);
const store = [`${FETCHED}${STORE}/.zattrs`, ...CHANNEL_SIDECARS].every((f) => fs.existsSync(f)) ? STORE : null;
/** The fetched channels' sidecars (what the store was written from: dims, windows, labels, colours). */
const channelSidecars = () => CHANNEL_SIDECARS.map((f) => JSON.parse(fs.readFileSync(f, 'utf8')));
/** sRGB hex RRGGBB to linear RGB (the viewer's channel colours are linear; omero's are sRGB). */
const linear = (hex: string) =>
  [0, 2, 4].map((i) => {
    const v = parseInt(hex.slice(i, i + 2), 16) / 255;
    return v <= 0.04045 ? v / 12.92 : ((v + 0.055) / 1.055) ** 2.4;
  });
const SERIES = 'micro_yeast_mitochondria_279x192x17x30_uint16';
const seriesFetched = fs.existsSync(`${FETCHED}${SERIES}.nrrd`);

const gallery = useGalleryServer(ctFetched || store !== null || seriesFetched);

/** Open the gallery on `dataset` with MIP at a tenth of the size, 2 samples; resolves when the view is ready. */
async function open(dataset: string) {
  const { server, browser } = gallery();
  const page = await browser.newPage();
  const errors = recordPageErrors(page);
  await page.setViewport({ width: 480, height: 360 });
  await page.goto(
    new URL(`apps/gallery/dist/index.html?dataset=${dataset}&renderer=mip&scale=0.1&max=2`, server.url).href,
  );
  await page.waitForFunction(() => (window as any).__galleryReady === true, { timeout: 180_000, polling: 200 });
  return { page, errors };
}

describe.skipIf(!ctFetched)(
  `gallery: CT chest with its segmentation${ctFetched ? '' : ' (skipped: run pnpm data:fetch for the chest CT and its label map)'}`,
  () => {
    it('is listed, opens the CT with `labels` set to the label volume, which loads on the CT grid', async () => {
      const { page, errors } = await open(`${CT}-labels`);
      const r = await page.evaluate(async (ct: string) => {
        const w = window as any;
        const el = w.gallery.viewer;
        const entry = w.gallery.catalog.find((d: any) => d.id === `${ct}-labels`);
        const v = el.loadedVolume;
        // The label volume the viewer draws over the CT (its lazy labels layer has read the URL).
        await el.whenSettled();
        const scene = el.context?.getScene();
        const drawnLabels = scene?.labels
          ? { dims: scene.labels.volume.dims, ids: scene.labels.table.map((e: any) => e.id) }
          : null;
        const table = (el.labelTable ?? []).map((e: any) => e.id);
        // The label volume through the viewer's own loaders: a second element with it as src.
        const probe = document.createElement('vpt-viewer') as any;
        probe.setAttribute('panels', 'none');
        probe.setAttribute('max-samples', '1');
        probe.style.cssText = 'width:16px;height:16px';
        const loaded = new Promise((res, rej) => {
          probe.addEventListener('vpt-load', res, { once: true });
          probe.addEventListener('vpt-error', (e: CustomEvent) => rej(new Error(e.detail.message)), { once: true });
        });
        probe.setAttribute('src', entry.labels);
        document.body.append(probe);
        await loaded;
        const lv = probe.loadedVolume;
        let ones = 0;
        let other = 0;
        for (const x of lv.data as Uint8Array) {
          if (x === 1) ones++;
          else if (x !== 0) other++;
        }
        probe.remove();
        return {
          listed: !!document.querySelector(`button[data-id="${ct}-labels"]`),
          title: entry.title,
          current: w.gallery.current.dataset.id,
          src: el.src,
          ctUrl: w.gallery.catalog.find((d: any) => d.id === ct).url,
          labelsUrl: entry.labels,
          labelsProperty: el.labels,
          dims: v.dims,
          type: v.type,
          labelDims: lv.dims,
          labelType: lv.type,
          labelSpacing: lv.spacing,
          spacing: v.spacing,
          ones,
          other,
          drawnLabels,
          table,
        };
      }, CT);
      // Another dataset clears the labels (the preset sets labels: null).
      await page.evaluate((ct: string) => (window as any).gallery.select(ct, 'mip'), CT);
      const afterOther = await page.evaluate(() => (window as any).gallery.viewer.labels);
      await page.close();
      expect(r.listed).toBe(true);
      expect(r.title).toMatch(/^CT chest with its segmentation/);
      expect(r.current).toBe(`${CT}-labels`);
      expect(r.src).toBe(r.ctUrl);
      expect(r.labelsUrl).toBe(`data/fetched/${LABELS}.json`);
      expect(r.labelsProperty).toBe(r.labelsUrl);
      expect(r.dims).toEqual([512, 512, 61]);
      expect(r.type).toBe('int16');
      expect(r.labelDims).toEqual(r.dims);
      expect(r.labelSpacing).toEqual(r.spacing);
      expect(r.labelType).toBe('uint8');
      expect(r.other).toBe(0);
      expect(r.ones).toBeGreaterThan(0);
      expect(afterOther).toBeNull();
      // The scene the context draws holds the label volume on the CT grid, its table label 1.
      expect(r.drawnLabels?.dims).toEqual(r.dims);
      expect(r.drawnLabels?.ids).toContain(1);
      expect(r.table).toContain(1);
      expect(errors).toEqual([]);
    });
  },
);

describe.skipIf(!store)(
  `gallery: 2-channel microscopy (brain tissue)${store ? '' : ' (skipped: run pnpm data:fetch for the imaris-ims-file-reader brain stack, micro_brain_ims)'}`,
  () => {
    it('is listed and opens the store with both channels, named, coloured and windowed as its sidecars say', async () => {
      const sidecars = channelSidecars();
      const zattrs = JSON.parse(fs.readFileSync(`${FETCHED}${STORE}/.zattrs`, 'utf8'));
      const axes = zattrs.multiscales[0].axes.map((a: { name: string }) => a.name);
      const shape = JSON.parse(
        fs.readFileSync(`${FETCHED}${STORE}/${zattrs.multiscales[0].datasets[0].path}/.zarray`, 'utf8'),
      ).shape;
      const id = STORE.replace(/\.ome\.zarr$/, '') + '-ome-zarr';
      const { page, errors } = await open(id);
      const r = await page.evaluate(async (id: string) => {
        const w = window as any;
        const el = w.gallery.viewer;
        await el.whenSettled();
        const entry = w.gallery.catalog.find((d: any) => d.id === id);
        const v = el.loadedVolume;
        return {
          listed: !!document.querySelector(`button[data-id="${id}"]`),
          title: entry.title,
          channels: entry.channels,
          dims: v.dims,
          spacing: v.spacing,
          labels: v.meta?.channelLabels ?? null,
          current: w.gallery.current.dataset.id,
          viewerChannels: (el.channels ?? []).map((c: any) => ({ color: c.color, enabled: c.enabled, range: c.range })),
        };
      }, id);
      await page.close();
      // The store: a c axis of 2, on the sidecars' grid (zarr shape is t, c, z, y, x).
      expect(axes).toEqual(['t', 'c', 'z', 'y', 'x']);
      expect(shape).toEqual([1, 2, ...[...sidecars[0].dims].reverse()]);
      expect(r.listed).toBe(true);
      expect(r.current).toBe(id);
      expect(r.channels).toBe(2);
      expect(r.title).toMatch(/^2-channel microscopy.*2 channels/);
      expect(r.dims).toHaveLength(3);
      // Every channel drawn, in the colour its sidecar gives (omero, sRGB) as linear RGB, with
      // its sidecar's value_range as the window and its channel_label as the name.
      expect(r.viewerChannels).toHaveLength(2);
      expect(r.labels).toEqual(sidecars.map((s) => s.channel_label));
      for (const [k, c] of r.viewerChannels.entries()) {
        expect(c.enabled).toBe(true);
        const want = linear(sidecars[k].channel_color);
        for (let i = 0; i < 3; i++) expect(c.color[i]).toBeCloseTo(want[i], 4);
        expect(c.range).toEqual(sidecars[k].value_range);
      }
      expect(new Set(r.viewerChannels.map((c: any) => c.color.join(','))).size).toBe(2);
      expect(errors.filter((e) => !/404/.test(e))).toEqual([]);
    });
  },
);

describe.skipIf(!seriesFetched)(
  `gallery: a fluorescence time series plays${seriesFetched ? '' : ' (skipped: run pnpm data:fetch for the nellie yeast series)'}`,
  () => {
    it('opens the 4D NRRD as 30 steps; the toolbar button plays it, the slider picks a step', async () => {
      const id = `${SERIES}-nrrd`;
      const { page, errors } = await open(id);
      const r = await page.evaluate(async (id: string) => {
        const w = window as any;
        const el = w.gallery.viewer;
        const frames = () => new Promise((res) => requestAnimationFrame(() => requestAnimationFrame(res)));
        let button: HTMLButtonElement | null = null;
        for (let i = 0; i < 300 && !button; i++) {
          await frames();
          button = el.shadowRoot.querySelector('[part~="time-play"]');
        }
        const slider = el.shadowRoot.querySelector('[part~="time-slider"]') as HTMLInputElement;
        const played: number[] = [];
        el.addEventListener(
          'vpt-change',
          (e: CustomEvent) => e.detail.property === 'time' && played.push(e.detail.value),
        );
        el.fps = 30;
        button!.click();
        const t0 = performance.now();
        while (played.length < 3 && performance.now() - t0 < 60_000) await frames();
        const playing = el.playing;
        button!.click();
        await frames();
        const paused = !el.playing;
        slider.value = '7';
        slider.dispatchEvent(new Event('input'));
        for (let i = 0; i < 600 && el.time !== 7; i++) await frames();
        return {
          listed: !!document.querySelector(`button[data-id="${id}"]`),
          steps: el.timeSteps,
          dims: el.loadedVolume.dims,
          sliderMax: slider.max,
          played: played.slice(0, 3),
          playing,
          paused,
          time: el.time,
        };
      }, id);
      await page.close();
      expect(r.listed).toBe(true);
      expect(r.steps).toBe(30);
      expect(r.dims).toEqual([279, 192, 17]);
      expect(r.sliderMax).toBe('29');
      expect(r.playing).toBe(true);
      expect(r.played).toEqual([1, 2, 3]);
      expect(r.paused).toBe(true);
      expect(r.time).toBe(7);
      expect(errors).toEqual([]);
    });
  },
);
