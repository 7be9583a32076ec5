import fs from 'node:fs';
import path from 'node:path';
import { afterAll, beforeAll, describe, expect, it } from 'vitest';
import { validateSceneDescription, type SceneDescription } from '../packages/headless/src/index.js';
import { tempDir, writeZarrFolder } from '../packages/loaders/test/zarr-fixtures.js';
import { bytesIn, niftiFile } from '../packages/loaders/test/helpers.js';
import { usePage } from './helpers/session.js';

// vpt-render's scene-file interface for label volumes: `"labels": { "volume": <volume description>,
// "table": [{ "id", "name", "color", "opacity", "visible" }] }`, checked in Node before a browser
// starts; a NIfTI segmentation (int16 on disk) loads as the same ids as a raw uint8 file.
const page = usePage();
const TMP = tempDir('vpt-labels-render-');
afterAll(() => fs.rmSync(TMP, { recursive: true, force: true }));

const N = 16;
const image = new Uint8Array(N * N * N);
const ids = new Uint8Array(N * N * N);
for (let z = 0; z < N; z++)
  for (let y = 0; y < N; y++)
    for (let x = 0; x < N; x++) {
      const i = x + N * (y + N * z);
      const q = ((x + 0.5) / N - 0.45) ** 2 + ((y + 0.5) / N - 0.5) ** 2 + ((z + 0.5) / N - 0.55) ** 2;
      image[i] = Math.round(255 * Math.exp(-q / 0.05));
      ids[i] = q < 0.04 ? 1 : x > 11 && y < 6 ? 2 : 0;
    }

type Labels = NonNullable<SceneDescription['labels']>;
const TABLE: NonNullable<Labels['table']> = [
  { id: 1, name: 'liver', color: [0.8, 0.2, 0.1], opacity: 2, visible: true },
  { id: 2, name: 'tumour', color: [0.2, 0.3, 0.9], opacity: 3, visible: true },
];
const scene = (renderer: string, extra: Partial<SceneDescription>) =>
  ({
    width: 20,
    height: 16,
    renderer,
    iterations: 2,
    backend: 'webgl2',
    sampling: 'exact',
    densityScale: 10,
    camera: { position: [0.9, 0.5, 1.6], target: [0, 0, 0], up: [0, 1, 0], fovy: 0.5 },
    volume: { raw: 'image.raw', dims: [N, N, N], type: 'uint8' },
    transferFunction: {
      points: [
        { value: 0.1, color: [1, 1, 1], opacity: 0 },
        { value: 1, color: [1, 1, 1], opacity: 0.6 },
      ],
    },
    ...extra,
  }) as SceneDescription;

function bitsDiffer(a: ArrayLike<number>, b: ArrayLike<number>): number {
  const u = new Uint32Array(Float32Array.from(a).buffer),
    v = new Uint32Array(Float32Array.from(b).buffer);
  let n = 0;
  for (let i = 0; i < u.length; i++) if (u[i] !== v[i]) n++;
  return u.length === v.length ? n : -1;
}

describe('vpt-render: label scene files', () => {
  beforeAll(() => {
    fs.writeFileSync(path.join(TMP, 'image.raw'), image);
    fs.writeFileSync(path.join(TMP, 'labels.raw'), ids);
    fs.writeFileSync(
      path.join(TMP, 'labels.nii'),
      niftiFile({ dims: [N, N, N], datatype: 4, bitpix: 16, data: bytesIn(Int16Array.from(ids), true) }),
    );
  });
  const opts = { baseDir: TMP, warmup: false };
  const raw: Labels['volume'] = { raw: 'labels.raw', dims: [N, N, N], type: 'uint8' };

  for (const renderer of ['eam', 'mip', 'mcrt', 'slice'])
    it(`${renderer}: raw and NIfTI label files give the same bits; a hidden label = no label; labels change the image`, async () => {
      const fromRaw = await page().render(scene(renderer, { labels: { volume: raw, table: TABLE } }), opts);
      const fromNifti = await page().render(
        scene(renderer, { labels: { volume: { file: 'labels.nii' }, table: TABLE } }),
        opts,
      );
      const hidden = await page().render(
        scene(renderer, { labels: { volume: raw, table: TABLE.map((e) => ({ ...e, visible: false })) } }),
        opts,
      );
      const bare = await page().render(scene(renderer, {}), opts);
      expect(Array.from(fromRaw.hdr).every(Number.isFinite)).toBe(true);
      expect(bitsDiffer(fromRaw.hdr, fromNifti.hdr)).toBe(0);
      expect(bitsDiffer(hidden.hdr, bare.hdr)).toBe(0);
      expect(bitsDiffer(fromRaw.hdr, bare.hdr)).toBeGreaterThan(10);
      // The label textures: one byte per voxel (r8unorm) and a 256 × 1 rgba32float table (the slice
      // renderer has no grid, whose textures differ with labels: a CPU-built grid in place of the GPU passes).
      if (renderer === 'slice') expect(fromRaw.gpuBytes.auxiliary - bare.gpuBytes.auxiliary).toBe(N * N * N + 256 * 16);
    });

  it('labels alone (no image volume): only the organs, in their table colours; a default table without one', async () => {
    const alone = await page().render(scene('mip', { volume: undefined, labels: { volume: raw, table: TABLE } }), opts);
    const colours = new Set<string>();
    for (let i = 0; i < alone.hdr.length; i += 4) colours.add(Array.from(alone.hdr.slice(i, i + 3)).join(','));
    const f = (c: number[]) => c.map((x) => Math.fround(x)).join(',');
    for (const c of colours) expect([f(TABLE[0].color!), f(TABLE[1].color!), '0,0,0']).toContain(c);
    expect(colours.size).toBe(3);
    const palette = await page().render(scene('mip', { volume: undefined, labels: { volume: raw } }), opts);
    expect(bitsDiffer(palette.hdr, alone.hdr)).toBeGreaterThan(10);
  });

  it('an OME-Zarr label group (labels/<name>) brings its image-label colours as the default table', async () => {
    const dir = path.join(TMP, 'ct.ome.zarr', 'labels', 'organs');
    await writeZarrFolder(dir, { dims: [N, N, N], type: 'uint8', spacing: [1, 1, 1], images: [[ids]] });
    const attrsFile = path.join(dir, '.zattrs');
    const attrs = JSON.parse(fs.readFileSync(attrsFile, 'utf8'));
    // sRGB bytes whose linear values are exact in float32: 0 and 255 (1).
    attrs['image-label'] = {
      colors: [
        { 'label-value': 1, rgba: [255, 0, 0, 255] },
        { 'label-value': 2, rgba: [0, 0, 255, 255] },
      ],
      properties: [{ 'label-value': 1, name: 'liver' }],
    };
    fs.writeFileSync(attrsFile, JSON.stringify(attrs));
    const fromZarr = await page().render(
      scene('mip', { volume: undefined, labels: { volume: { zarr: 'ct.ome.zarr/labels/organs' } } }),
      opts,
    );
    const given = await page().render(
      scene('mip', {
        volume: undefined,
        labels: {
          volume: raw,
          table: [
            { id: 1, name: 'liver', color: [1, 0, 0], opacity: 1, visible: true },
            { id: 2, color: [0, 0, 1], opacity: 1, visible: true },
          ],
        },
      }),
      opts,
    );
    expect(bitsDiffer(fromZarr.hdr, given.hdr)).toBe(0);
    const palette = await page().render(scene('mip', { volume: undefined, labels: { volume: raw } }), opts);
    expect(bitsDiffer(fromZarr.hdr, palette.hdr)).toBeGreaterThan(10);
  });

  it('bad label descriptions fail before a browser starts, naming the field', () => {
    const bad = (labels: unknown) => () => validateSceneDescription({ ...scene('eam', {}), labels });
    expect(bad({ table: TABLE })).toThrow(/labels\.volume: is required/);
    expect(bad({ volume: { raw: 'labels.raw', dims: [N, N, N], type: 'float32' } })).toThrow(
      /labels\.volume\.type: must be "uint8" or "uint16"/,
    );
    expect(bad({ volume: { procedural: 'sphere' } })).toThrow(/labels\.volume: a label volume is a file/);
    expect(bad({ volume: raw, table: [{ id: 0, color: [1, 0, 0] }] })).toThrow(/labels\.table\[0\]\.id/);
    expect(bad({ volume: raw, table: [{ id: 1, color: [1, 2, 0] }] })).toThrow(/labels\.table\[0\]\.color\[1\]/);
    expect(bad({ volume: raw, table: [{ id: 1 }, { id: 1 }] })).toThrow(/labels\.table\[1\]\.id: 1 is listed twice/);
    expect(bad({ volume: raw, table: [{ id: 1, colour: [1, 0, 0] }] })).toThrow(/labels\.table\[0\]/);
    expect(bad({ volume: raw, table: [{ id: 1, visible: 1 }] })).toThrow(/labels\.table\[0\]\.visible/);
    expect(bad({ volume: raw, extra: 1 })).toThrow(/labels/);
  });

  it('a label volume of another grid is refused at setScene (typed, naming the dims)', async () => {
    fs.writeFileSync(path.join(TMP, 'small.raw'), new Uint8Array(8 * N * N));
    await expect(
      page().render(
        scene('eam', { labels: { volume: { raw: 'small.raw', dims: [8, N, N], type: 'uint8' }, table: TABLE } }),
        opts,
      ),
    ).rejects.toThrow(/labels\.volume\.dims \[8, 16, 16\] differ/);
  });
});
