import fs from 'node:fs';
import { fileURLToPath } from 'node:url';
import { describe, expect, it } from 'vitest';
import { useGalleryServer } from './helpers/gallery-server.js';
import { recordPageErrors } from './helpers/page-errors.js';

// The gallery's OME-Zarr example (the cells3d copy `pnpm data:fetch` writes): listed, loaded
// coarsest level first and refined to level 0, with the level on the stats line. Skipped
// (and the title says so) where the data has not been fetched.
const STORE = fileURLToPath(new URL('../data/fetched/micro_cells3d_nuclei.ome.zarr/.zattrs', import.meta.url));
const fetched = fs.existsSync(STORE);

const gallery = useGalleryServer(fetched);

describe.skipIf(!fetched)(`gallery: the OME-Zarr dataset${fetched ? '' : ' (skipped: run pnpm data:fetch)'}`, () => {
  it('is listed and refined level by level up to level 0', async () => {
    const { server, browser } = gallery();
    const page = await browser.newPage();
    const errors = recordPageErrors(page);
    await page.evaluateOnNewDocument(() => {
      const w = window as unknown as { __levels: unknown[] };
      w.__levels = [];
      document.addEventListener('vpt-load', (e) => w.__levels.push((e as CustomEvent).detail.level), true);
    });
    await page.setViewport({ width: 1000, height: 700 });
    await page.goto(
      new URL(
        'apps/gallery/dist/index.html?dataset=micro_cells3d_nuclei-ome-zarr&renderer=mip&scale=0.1&max=2',
        server.url,
      ).href,
    );
    await page.waitForFunction(
      () => {
        const w = window as any;
        const stats = w.gallery?.viewer?.shadowRoot?.querySelector('[part=stats]')?.textContent ?? '';
        return w.__galleryReady === true && w.__levels.some((l: any) => l?.final) && /level 0 of/.test(stats);
      },
      { timeout: 120_000, polling: 200 },
    );
    const r = await page.evaluate(() => {
      const w = window as any;
      const el = w.gallery.viewer;
      return {
        levels: w.__levels.map((l: any) => l.index),
        stats: el.shadowRoot.querySelector('[part=stats]')?.textContent ?? '',
        listed: !!document.querySelector('button[data-id="micro_cells3d_nuclei-ome-zarr"]'),
      };
    });
    await page.close();
    expect(r.listed).toBe(true);
    expect(r.levels[0]).toBe(2);
    expect(r.levels.at(-1)).toBe(0);
    expect(r.stats).toMatch(/level 0 of 3/);
    // A v0.4 store is found by asking for v0.5's zarr.json first: that one 404 is expected.
    expect(errors.filter((e) => !/404/.test(e))).toEqual([]);
  });
});
