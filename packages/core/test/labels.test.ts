import { describe, expect, it } from 'vitest';
import {
  createVolume,
  gridCells,
  labelSupport,
  registerLabelSupport,
  validateScene,
  volumeBox,
  VptError,
  type LabelEntry,
  type Scene,
} from '../src/index.js';
import {
  defaultLabelColor,
  defaultLabelTable,
  enableLabels,
  labelCellMajorants,
  labelEntryOf,
  labelIdAt,
  labelScaleOf,
  labelTableData,
  labelVolumeTexture,
  LABEL_PALETTE_SRGB,
  sceneMajorantGrid,
  withLabelColors,
} from '../src/scene/labels.js';
import { tf1d } from '../../../tests/helpers/test-scene.js';

enableLabels();
const N = 8;
const image = createVolume([N, N, N], 'uint8', new Uint8Array(N * N * N).fill(40));
const ids = (f: (x: number, y: number, z: number) => number) => {
  const d = new Uint8Array(N * N * N);
  for (let z = 0; z < N; z++)
    for (let y = 0; y < N; y++) for (let x = 0; x < N; x++) d[x + N * (y + N * z)] = f(x, y, z);
  return d;
};
const scene = (labels: unknown, densityScale = 4): Scene => ({
  volume: image,
  transferFunction: tf1d([0, [1, 1, 1], 0], [1, [1, 1, 1], 1]),
  camera: { position: [0, 0, 2], target: [0, 0, 0], up: [0, 1, 0], fovy: 0.6 },
  lights: [],
  environment: { type: 'constant', radiance: [1, 1, 1] },
  densityScale,
  seed: 1,
  labels: labels as Scene['labels'],
});
function message(f: () => void): string {
  try {
    f();
  } catch (e) {
    expect(e).toBeInstanceOf(VptError);
    expect((e as VptError).code).toBe('invalid-scene');
    return (e as Error).message;
  }
  throw new Error('no error');
}

describe('label model', () => {
  it('without enableLabels() a scene with labels fails typed, naming the call', () => {
    registerLabelSupport(null);
    try {
      expect(message(() => validateScene(scene({ volume: lv, table })))).toMatch(
        /call enableLabels\(\) from @vpt\/core\/labels/,
      );
    } finally {
      enableLabels();
    }
    expect(() => labelSupport()).not.toThrow();
  });

  const lv = createVolume(
    [N, N, N],
    'uint8',
    ids((x) => (x < 4 ? 1 : 7)),
  );
  const table: LabelEntry[] = [
    { id: 1, name: 'liver', color: [1, 0, 0], opacity: 2, visible: true },
    { id: 7, color: [0, 0, 1], opacity: 0.5, visible: false },
  ];

  it('a valid scene passes; typed errors name the field', () => {
    validateScene(scene({ volume: lv, table }));
    const small = createVolume([4, N, N], 'uint8', new Uint8Array(4 * N * N));
    expect(message(() => validateScene(scene({ volume: small, table })))).toMatch(
      /^Scene: labels\.volume\.dims \[4, 8, 8\] differ from the image volume's dims \[8, 8, 8\]/,
    );
    const f = createVolume([N, N, N], 'float32', new Float32Array(N * N * N));
    expect(message(() => validateScene(scene({ volume: f, table })))).toMatch(
      /labels\.volume\.type must be "uint8" or "uint16"/,
    );
    const i16 = createVolume([N, N, N], 'int16', new Int16Array(N * N * N));
    expect(message(() => validateScene(scene({ volume: i16, table })))).toMatch(/labels\.volume\.type/);
    expect(message(() => validateScene(scene({ volume: lv, table: [{ id: 256, color: [1, 0, 0] }] })))).toMatch(
      /labels\.table\[0\]\.id must be an integer in \[1, 255\]/,
    );
    expect(message(() => validateScene(scene({ volume: lv, table: [{ id: 0 }] })))).toMatch(/0 is the background/);
    expect(message(() => validateScene(scene({ volume: lv, table: [{ id: 1.5 }] })))).toMatch(/table\[0\]\.id/);
    expect(message(() => validateScene(scene({ volume: lv, table: [{ id: 1, color: [1, -1, 0] }] })))).toMatch(
      /labels\.table\[0\]\.color\[1\]/,
    );
    expect(message(() => validateScene(scene({ volume: lv, table: [{ id: 1, color: [1, 0] }] })))).toMatch(
      /labels\.table\[0\]\.color must be \[r, g, b\]/,
    );
    expect(message(() => validateScene(scene({ volume: lv, table: [{ id: 1, opacity: -1 }] })))).toMatch(
      /labels\.table\[0\]\.opacity/,
    );
    expect(message(() => validateScene(scene({ volume: lv, table: [{ id: 1, visible: 'yes' }] })))).toMatch(
      /labels\.table\[0\]\.visible must be true or false/,
    );
    expect(message(() => validateScene(scene({ volume: lv, table: [{ id: 1 }, { id: 1 }] })))).toMatch(
      /labels\.table\[1\]\.id 1 is listed twice/,
    );
    expect(message(() => validateScene(scene({ volume: lv, table: [{ id: 1, colour: [1, 0, 0] }] })))).toMatch(
      /unknown field "colour"/,
    );
    expect(message(() => validateScene(scene({ volume: lv })))).toMatch(/labels\.table must be an array/);
    expect(message(() => validateScene(scene([lv])))).toMatch(/labels must be \{ volume, table \}/);
    // uint16 takes ids up to 65535.
    const u16 = createVolume([N, N, N], 'uint16', new Uint16Array(N * N * N).fill(40000));
    validateScene(scene({ volume: u16, table: [{ id: 40000, color: [0, 1, 0] }] }));
    // The extinction bound counts the image's and the labels' largest opacities together.
    expect(message(() => validateScene(scene({ volume: lv, table: [{ id: 1, opacity: 1e6 }] }, 1e4)))).toMatch(
      /image's largest opacity \+ the labels' largest opacity/,
    );
  });

  it('the default palette: distinct colours, background absent, ids present listed', () => {
    const keys = new Set(LABEL_PALETTE_SRGB.map((c) => c.join(',')));
    expect(keys.size).toBe(20);
    expect(defaultLabelColor(1)).not.toEqual(defaultLabelColor(2));
    expect(defaultLabelColor(21)).toEqual(defaultLabelColor(1));
    for (const c of defaultLabelColor(3)) expect(c).toBeGreaterThanOrEqual(0);
    const t = defaultLabelTable(lv, { 1: 'liver' });
    expect(t.map((e) => [e.id, e.name, e.visible, e.opacity])).toEqual([
      [1, 'liver', true, 1],
      [7, undefined, true, 1],
    ]);
  });

  it("a file's label colours (OME-Zarr image-label): sRGB bytes to linear, alpha to opacity, names", () => {
    const t = withLabelColors(defaultLabelTable(lv), [
      { id: 7, rgba: [255, 0, 0, 0], name: 'spleen' },
      { id: 9, rgba: [0, 255, 0, 255] },
    ]);
    expect(t.map((e) => [e.id, e.name, e.color, e.opacity, e.visible])).toEqual([
      [1, undefined, defaultLabelColor(1), 1, true],
      [7, 'spleen', [1, 0, 0], 0, false],
      [9, undefined, [0, 1, 0], 1, true],
    ]);
  });

  it('table texture: 256 ids a row, hidden and background 0', () => {
    const t = labelTableData({ volume: lv, table });
    expect([t.width, t.height]).toEqual([256, 1]);
    expect(Array.from(t.data.subarray(4, 8))).toEqual([1, 0, 0, 2]);
    expect(Array.from(t.data.subarray(28, 32))).toEqual([0, 0, 0, 0]);
    expect(Array.from(t.data.subarray(0, 4))).toEqual([0, 0, 0, 0]);
    const big = labelTableData({
      volume: createVolume([N, N, N], 'uint16', new Uint16Array(N * N * N)),
      table: [{ id: 65535, color: [0, 1, 0], opacity: 1 }],
    });
    expect([big.width, big.height]).toEqual([256, 256]);
    expect(Array.from(big.data.subarray(4 * 65535))).toEqual([0, 1, 0, 1]);
  });

  it('texture formats keep every id exact (r8unorm, r16unorm, r32float), never filtered', () => {
    const caps = { norm16: true, float32Filterable: true };
    const a = labelVolumeTexture(lv, caps);
    expect([a.desc.format, a.labelScale, a.desc.filter ?? 'nearest']).toEqual(['r8unorm', 255, 'nearest']);
    expect(a.desc.data).toBe(lv.data);
    const u16 = createVolume(
      [N, N, N],
      'uint16',
      Uint16Array.from({ length: N * N * N }, (_, i) => i * 127),
    );
    const b = labelVolumeTexture(u16, caps);
    expect([b.desc.format, b.labelScale]).toEqual(['r16unorm', 65535]);
    const c = labelVolumeTexture(u16, { ...caps, norm16: false });
    expect([c.desc.format, c.labelScale]).toEqual(['r32float', 1]);
    expect(Array.from(c.desc.data as Float32Array)).toEqual(Array.from(u16.data));
    expect(labelScaleOf(u16, { ...caps, norm16: false })).toBe(1);
    // What the kernel computes: floor(texel · scale + 0.5) with the texel a float32 unorm value.
    const wrong: number[] = [];
    for (let id = 0; id < 65536; id++) if (Math.floor(Math.fround(id / 65535) * 65535 + 0.5) !== id) wrong.push(id);
    for (let id = 0; id < 256; id++) if (Math.floor(Math.fround(id / 255) * 255 + 0.5) !== id) wrong.push(id);
    expect(wrong).toEqual([]);
  });

  it('nearest lookup: the voxel holding the point', () => {
    const box = volumeBox(lv);
    const at = (vx: number) => [box.min[0] + (vx / N) * box.size[0], 0, 0];
    expect(labelIdAt(lv, at(3.99))).toBe(1);
    expect(labelIdAt(lv, at(4.01))).toBe(7);
    expect(labelIdAt(lv, at(-1))).toBe(1);
    expect(labelEntryOf({ volume: lv, table }, 1)).toEqual([1, 0, 0, 2]);
    expect(labelEntryOf({ volume: lv, table }, 7)).toEqual([0, 0, 0, 0]);
    expect(labelEntryOf({ volume: lv, table }, 0)).toEqual([0, 0, 0, 0]);
  });

  it('the majorant grid bounds image + labels; a hidden label adds nothing', () => {
    const cells = gridCells(lv.dims, 4);
    const add = labelCellMajorants({ volume: lv, table }, cells, 4);
    // id 1 fills x < 4, so every cell reads it (cell 1 through its one-voxel pad); id 7 is hidden.
    expect(Array.from(add)).toEqual(new Array(8).fill(Math.fround(8 * (1 + 1e-5))));
    const only7 = createVolume(
      [N, N, N],
      'uint8',
      ids(() => 7),
    );
    expect(Array.from(labelCellMajorants({ volume: only7, table }, cells, 4))).toEqual(new Array(8).fill(0));
    const s = scene({ volume: lv, table });
    const withLabels = sceneMajorantGrid(s, 4);
    const bare = sceneMajorantGrid({ ...s, labels: undefined }, 4);
    for (let c = 0; c < 8; c++) {
      expect(withLabels.data[4 * c]).toBeGreaterThanOrEqual(bare.data[4 * c] + 8);
      expect(withLabels.data[4 * c + 1]).toBe(bare.data[4 * c + 1]);
    }
    // Every point's extinction (image 40/255 through the ramp TF, plus its label) lies under its cell's majorant.
    const box = volumeBox(lv);
    for (let k = 0; k < 2000; k++) {
      const p = [0, 1, 2].map((a) => box.min[a] + ((k * [0.618, 0.414, 0.732][a]) % 1) * box.size[a]);
      const sigma = 4 * (40 / 255 + labelEntryOf({ volume: lv, table }, labelIdAt(lv, p))[3]);
      const c = [0, 1, 2].map((a) => Math.min(1, Math.floor(((p[a] - box.min[a]) / box.size[a]) * 2)));
      expect(sigma).toBeLessThanOrEqual(withLabels.data[4 * (c[0] + 2 * (c[1] + 2 * c[2]))]);
    }
  });
});
