import { describe, expect, it } from 'vitest';
import { defaultCamera, reference, type Scene, type Vec3, type VoxelType } from '../packages/core/src/index.js';
import { readFileSync } from 'node:fs';
import { decodePFM, encodePFM, readSceneFile, validateSceneDescription } from '../packages/headless/src/index.js';
import { colormapTable, type SliceColormap, type SliceParams } from '../packages/renderer-slice/src/index.js';
import { clippedAt } from './helpers/clip-volumes.js';
import { BACKENDS, usePage } from './helpers/session.js';

/**
 * The slice renderer against CPU expectations written here from the definitions (the voxel
 * at a pixel, the cell-centred trilinear filter, the window (d − (c − w/2)) / w clamped, the
 * published colour tables read linearly), on both backends, and the two backends against
 * each other. Small volumes and images: every test is a handful of 1-iteration renders.
 */

const page = usePage();

interface SliceRender {
  backend: (typeof BACKENDS)[number];
  dims: [number, number, number];
  type: VoxelType;
  data: number[];
  valueRange?: [number, number];
  params: SliceParams;
  width: number;
  height: number;
  sampling?: 'fast' | 'exact';
  camera?: Scene['camera'];
  transferFunction?: Scene['transferFunction'];
  iterations?: number;
  bricking?: 'off' | 'force';
  clip?: Scene['clip'];
}

/** One render in the page: RGBA float32 HDR, top row first. */
function render(o: SliceRender): Promise<number[]> {
  return page.run(async ({ core, t }, o) => {
    const arrays = { uint8: Uint8Array, uint16: Uint16Array, int16: Int16Array, float32: Float32Array };
    const ctx = await t.context({
      backend: o.backend,
      renderer: 'slice',
      width: o.width,
      height: o.height,
      params: o.params,
      sampling: o.sampling,
      bricking: o.bricking,
      brickSize: 8,
      brickUploadsPerFrame: 256,
    });
    const volume = core.createVolume(o.dims, o.type, new arrays[o.type](o.data));
    if (o.valueRange) volume.valueRange = o.valueRange;
    const scene = t.scene({ volume, camera: o.camera, transferFunction: o.transferFunction });
    ctx.setScene(o.clip ? { ...scene, clip: o.clip } : scene);
    if (o.bricking === 'force') await ctx.whenBricksSettled();
    return t.finalHDR(ctx, o.iterations ?? 1);
  }, o);
}

/** Deterministic voxels (an LCG): integers in [lo, hi]. */
function voxels(n: number, lo: number, hi: number, seed = 1): number[] {
  let s = seed >>> 0;
  return Array.from({ length: n }, () => {
    s = (Math.imul(s, 1664525) + 1013904223) >>> 0;
    return lo + (s % (hi - lo + 1));
  });
}

const windowed = (d: number, [c, w]: readonly [number, number]) => Math.min(1, Math.max(0, (d - (c - w / 2)) / w));

/** A colour map at a windowed value: grey is the value; a table is read linearly between entries at i/(N − 1). */
function colour(name: SliceColormap, w: number): Vec3 {
  if (name === 'grey') return [w, w, w];
  if (name === 'transfer-function') throw new Error('not a table');
  const table = colormapTable(name);
  const n = table.length / 4;
  const x = w * (n - 1),
    i0 = Math.floor(x),
    i1 = Math.min(i0 + 1, n - 1),
    f = x - i0;
  return [0, 1, 2].map((c) => table[4 * i0 + c] + (table[4 * i1 + c] - table[4 * i0 + c]) * f) as Vec3;
}

/** Cell-centred trilinear interpolation with clamp-to-edge of the data at box coordinates tc ∈ [0, 1]³, in float64. */
function trilinear(data: number[], dims: [number, number, number], tc: Vec3): number {
  const g = tc.map((x, a) => x * dims[a] - 0.5);
  const g0 = g.map(Math.floor);
  const f = g.map((x, a) => x - g0[a]);
  const at = (i: number, j: number, k: number) => {
    const c = [i, j, k].map((x, a) => Math.min(dims[a] - 1, Math.max(0, x)));
    return data[c[0] + dims[0] * (c[1] + dims[1] * c[2])];
  };
  let v = 0;
  for (let dz = 0; dz < 2; dz++)
    for (let dy = 0; dy < 2; dy++)
      for (let dx = 0; dx < 2; dx++) {
        const w = (dx ? f[0] : 1 - f[0]) * (dy ? f[1] : 1 - f[1]) * (dz ? f[2] : 1 - f[2]);
        v += w * at(g0[0] + dx, g0[1] + dy, g0[2] + dz);
      }
  return v;
}

/** The largest difference per channel between an image and the expected RGBA at every pixel. */
function maxError(hdr: number[], width: number, height: number, expected: (x: number, y: number) => number[]): number {
  let worst = 0;
  for (let y = 0; y < height; y++)
    for (let x = 0; x < width; x++) {
      const e = expected(x, y);
      for (let c = 0; c < 4; c++) worst = Math.max(worst, Math.abs(hdr[4 * (x + width * y) + c] - e[c]));
    }
  return worst;
}

const differingWords = (a: number[], b: number[]) =>
  a.length !== b.length ? -1 : a.reduce((n, x, i) => n + (Object.is(x, b[i]) ? 0 : 1), 0);

describe.each(BACKENDS)('slice renderer on %s', (backend) => {
  // (a) fit, image size = slice size: each pixel is its voxel, windowed and colour-mapped.
  it('fit with the image the size of the slice: every pixel is its voxel, windowed and colour-mapped (nearest)', async () => {
    const dims: [number, number, number] = [12, 10, 6];
    const data = voxels(12 * 10 * 6, 0, 255);
    const voxel = (x: number, y: number, z: number) => data[x + dims[0] * (y + dims[1] * z)];
    const window: [number, number] = [110, 120];
    // Image axes per slice axis (columns, rows): z → (x, y), y → (x, z), x → (y, z).
    const cases: {
      axis: 'x' | 'y' | 'z';
      index: number;
      size: [number, number];
      at: (c: number, r: number) => number;
    }[] = [
      { axis: 'z', index: 3, size: [12, 10], at: (c, r) => voxel(c, r, 3) },
      { axis: 'y', index: 7, size: [12, 6], at: (c, r) => voxel(c, 7, r) },
      { axis: 'x', index: 0, size: [10, 6], at: (c, r) => voxel(0, c, r) },
    ];
    for (const sampling of ['fast', 'exact'] as const) {
      for (const { axis, index, size, at } of cases) {
        for (const colormap of ['grey', 'viridis', 'coolwarm'] as const) {
          const params: SliceParams = { axis, index, fit: true, window, colormap };
          const hdr = await render({
            backend,
            dims,
            type: 'uint8',
            data,
            params,
            width: size[0],
            height: size[1],
            sampling,
          });
          const err = maxError(hdr, size[0], size[1], (c, r) => [...colour(colormap, windowed(at(c, r), window)), 1]);
          expect(err, `${sampling} ${axis}=${index} ${colormap}`).toBeLessThan(1e-6);
        }
      }
    }
  });

  // The scene's clip cuts the plane as it cuts the volume: the cut part is background (0, 0, 0, 0).
  it('a clip plane and a crop box cut the slice where the CPU says the points are clipped', async () => {
    const n = 8;
    const dims: [number, number, number] = [n, n, n];
    const data = voxels(n * n * n, 0, 255, 7);
    const window: [number, number] = [128, 256];
    const clip = {
      planes: [{ normal: [1, 1, 0] as Vec3, offset: 0.1 }],
      box: { min: [-0.3, -0.5, -0.5] as Vec3, max: [0.5, 0.5, 0.5] as Vec3 },
    };
    const hdr = await render({
      backend,
      dims,
      type: 'uint8',
      data,
      params: { axis: 'z', index: 3, fit: true, window },
      width: n,
      height: n,
      clip,
    });
    // A cube's box is [-0.5, 0.5]³ with cell-centred voxels: pixel (c, r) of the fitted z = 3 slice is voxel (c, r, 3).
    const centre = (i: number) => (i + 0.5) / n - 0.5;
    let cut = 0;
    const err = maxError(hdr, n, n, (c, r) => {
      if (clippedAt(clip, [centre(c), centre(r), centre(3)])) return (cut++, [0, 0, 0, 0]);
      const w = windowed(data[c + n * (r + n * 3)], window);
      return [w, w, w, 1];
    });
    expect(cut, 'the clip removes part of the slice, not all of it').toBeGreaterThan(8);
    expect(cut).toBeLessThan(n * n - 8);
    expect(err).toBeLessThan(1e-6);
  });

  // (b) linear sampling of an oblique plane against a CPU trilinear expectation.
  it('linear, oblique, fit: the diagonal plane of a cube equals CPU trilinear interpolation', async () => {
    const dims: [number, number, number] = [8, 8, 8];
    const data = voxels(512, 0, 1000, 7).map((v) => v / 10); // float32 data in [0, 100]
    const window: [number, number] = [50, 100];
    const W = 16,
      H = 16;
    const params: SliceParams = { normal: [1, 1, 0], sampling: 'linear', fit: true, window };
    const hdr = await render({ backend, dims, type: 'float32', data, params, width: W, height: H, sampling: 'exact' });
    // The plane x + y = 0 cuts the box [-0.5, 0.5]³ in a √2 × 1 rectangle: columns from (0.5, -0.5)
    // to (-0.5, 0.5) (the in-plane direction of +y), rows along +z; at s, t the box point is
    // (1 − s, s, t) in [0, 1]³ coordinates.
    const err = maxError(hdr, W, H, (x, y) => {
      const s = (x + 0.5) / W,
        t = (y + 0.5) / H;
      return [...colour('grey', windowed(trilinear(data, dims, [1 - s, s, t]), window)), 1];
    });
    expect(err).toBeLessThan(1e-5);
    // The fast path's hardware filter on a uint8 volume (r8unorm is filterable): the same
    // interpolation up to the filter's weight precision (SwiftShader's matched to 6e-8; GPUs may use
    // 8-bit weights, hence 1e-2), not a shifted one (half a voxel off: ~0.5 here).
    const bytes = voxels(512, 0, 255, 7);
    const byteWindow: [number, number] = [128, 256];
    const fast = await render({
      backend,
      dims,
      type: 'uint8',
      data: bytes,
      params: { ...params, window: byteWindow },
      width: W,
      height: H,
      sampling: 'fast',
    });
    const fastErr = maxError(fast, W, H, (x, y) => {
      const s = (x + 0.5) / W,
        t = (y + 0.5) / H;
      return [...colour('grey', windowed(trilinear(bytes, dims, [1 - s, s, t]), byteWindow)), 1];
    });
    expect(fastErr).toBeLessThan(1e-2);
  });

  it('linear, oblique, under the camera: the pixel-centre ray meets the plane where the CPU says', async () => {
    const dims: [number, number, number] = [10, 8, 6];
    const data = voxels(480, 0, 1000, 3).map((v) => v / 10);
    const window: [number, number] = [40, 60];
    const W = 32,
      H = 24;
    const normal: Vec3 = [0.2, 1, 0.3],
      point: Vec3 = [0.05, 0.02, 0];
    // From above the plane (its normal is mostly +y), a little off its axis.
    const camera = { position: [0.4, 1.6, 0.8] as Vec3, target: [0, 0, 0] as Vec3, up: [0, 0, -1] as Vec3, fovy: 0.8 };
    const params: SliceParams = { normal, point, sampling: 'linear', window, colormap: 'viridis' };
    const hdr = await render({
      backend,
      dims,
      type: 'float32',
      data,
      params,
      width: W,
      height: H,
      sampling: 'exact',
      camera,
    });
    const scene = { camera, volume: { dims, spacing: [1, 1, 1] } } as unknown as Scene;
    const box = { min: [-0.5, -0.4, -0.3], size: [1, 0.8, 0.6] }; // [10, 8, 6] voxels of unit spacing
    let covered = 0,
      nearEdge = 0,
      worst = 0;
    for (let y = 0; y < H; y++)
      for (let x = 0; x < W; x++) {
        const { origin, dir } = reference.cameraRay(scene, W, H, (x + 0.5) / W, (y + 0.5) / H);
        const dot = (a: readonly number[], b: readonly number[]) => a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
        const tHit =
          dot(
            [0, 1, 2].map((a) => point[a] - origin[a]),
            normal,
          ) / dot(dir, normal);
        const tc = [0, 1, 2].map((a) => (origin[a] + dir[a] * tHit - box.min[a]) / box.size[a]) as Vec3;
        const margin = Math.min(...tc.map((c) => Math.min(c, 1 - c)));
        if (Math.abs(margin) < 1e-4) {
          nearEdge++; // the float32 ray may land on either side of the box's face
          continue;
        }
        const inside = tHit > 0 && margin > 0;
        const expected = inside ? [...colour('viridis', windowed(trilinear(data, dims, tc), window)), 1] : [0, 0, 0, 0];
        if (inside) covered++;
        for (let c = 0; c < 4; c++) worst = Math.max(worst, Math.abs(hdr[4 * (x + W * y) + c] - expected[c]));
      }
    expect(covered).toBeGreaterThan(W * H * 0.2);
    expect(covered).toBeLessThan(W * H - nearEdge);
    expect(nearEdge).toBeLessThan(5);
    expect(worst).toBeLessThan(1e-4);
  });

  // (f) every voxel type, with its own value range and an inverted one: nearest is the voxel, linear the CPU trilinear.
  it('every voxel type, value range as given or inverted: nearest is the voxel, linear is CPU trilinear', async () => {
    const dims: [number, number, number] = [8, 6, 4];
    const n = dims[0] * dims[1] * dims[2];
    const types: [VoxelType, number[]][] = [
      ['uint8', voxels(n, 0, 255, 3)],
      ['uint16', voxels(n, 0, 60000, 5)],
      ['int16', voxels(n, -1000, 3000, 9)],
      ['float32', voxels(n, 0, 20000, 11).map((v) => v / 100 - 50)],
    ];
    const W = 16,
      H = 12;
    for (const [type, data] of types) {
      const [lo, hi] = [Math.min(...data), Math.max(...data)];
      const window: [number, number] = [(lo + hi) / 2, (hi - lo) * 0.8];
      for (const valueRange of [undefined, [hi, lo]] as ([number, number] | undefined)[]) {
        const what = `${type} ${JSON.stringify(valueRange)}`;
        const base = { backend, dims, type, data, valueRange, sampling: 'exact' as const };
        const nearest = await render({
          ...base,
          params: { axis: 'z', index: 2, fit: true, window },
          width: 8,
          height: 6,
        });
        const nearestErr = maxError(nearest, 8, 6, (c, r) => {
          const w = windowed(data[c + dims[0] * (r + dims[1] * 2)], window);
          return [w, w, w, 1];
        });
        expect(nearestErr, `nearest ${what}`).toBeLessThan(1e-5);
        // The box is 1 × 0.75 × 0.5; the plane through its diagonal corners (0.5, -0.375) and (-0.5, 0.375) has the
        // normal (0.75, 1, 0) ∝ (6, 8, 0), dominant y, so columns run along +x and rows along +z: (s, 1 − s, t) in [0, 1]³.
        const params: SliceParams = { normal: [dims[1], dims[0], 0], sampling: 'linear', fit: true, window };
        const linear = await render({ ...base, params, width: W, height: H });
        const lin = maxError(linear, W, H, (x, y) => {
          const s = (x + 0.5) / W,
            t = (y + 0.5) / H;
          const w = windowed(trilinear(data, dims, [s, 1 - s, t]), window);
          return [w, w, w, 1];
        });
        expect(lin, `linear ${what}`).toBeLessThan(1e-5);
      }
    }
  });

  // (c) the window is in data units: an int16 CT in HU, whatever value range normalizes it.
  it('an int16 CT: the window [40, 400] is in HU, whatever the volume value range', async () => {
    // The ranges: a CT's, inverted, narrower than the data (the window reads past the range's clamp), none (the data's own).
    const dims: [number, number, number] = [16, 12, 3];
    const hu = voxels(16 * 12 * 3, -1000, 2000, 5);
    const window: [number, number] = [40, 400];
    const params: SliceParams = { axis: 'z', index: 1, fit: true, window };
    for (const sampling of ['fast', 'exact'] as const) {
      for (const valueRange of [[-1024, 3071], [2000, -2000], [-100, 300], undefined] as (
        [number, number] | undefined
      )[]) {
        const hdr = await render({
          backend,
          dims,
          type: 'int16',
          data: hu,
          valueRange,
          params,
          width: 16,
          height: 12,
          sampling,
        });
        const err = maxError(hdr, 16, 12, (x, y) => [...colour('grey', windowed(hu[x + 16 * (y + 12)], window)), 1]);
        // The window composes with the value mapping in float32: a few ulps of the normalized value × (range / width) ≈ 10.
        expect(err, `${sampling} ${JSON.stringify(valueRange)}`).toBeLessThan(4e-6);
      }
    }
  });

  it('the transfer function as the colour map: its colour at the windowed value', async () => {
    const dims: [number, number, number] = [8, 8, 2];
    const data = voxels(128, 0, 255, 11);
    const window: [number, number] = [128, 256];
    const tf = {
      dimensions: '1d' as const,
      points: [
        { value: 0, color: [0, 0.2, 1] as Vec3, opacity: 0 },
        { value: 1, color: [1, 0.6, 0] as Vec3, opacity: 1 },
      ],
    };
    const params: SliceParams = { index: 1, fit: true, window, colormap: 'transfer-function' };
    const hdr = await render({ backend, dims, type: 'uint8', data, params, width: 8, height: 8, transferFunction: tf });
    // The TF is rasterized to 256 texels and read linearly: within its linear ramp, a line.
    const err = maxError(hdr, 8, 8, (x, y) => {
      const w = windowed(data[x + 8 * (y + 8)], window);
      return [w, 0.2 + 0.4 * w, 1 - w, 1];
    });
    expect(err).toBeLessThan(1e-5);
  });

  it('renders the same bits every iteration, bricked or not', async () => {
    const dims: [number, number, number] = [20, 12, 10];
    const data = voxels(2400, 0, 1000, 9).map((v) => v / 10);
    const base = { backend, dims, type: 'float32' as const, data, width: 24, height: 20, sampling: 'exact' as const };
    const oblique: SliceParams = { normal: [0.4, -0.3, 1], point: [0.02, 0, 0.01], sampling: 'linear', fit: true };
    const one = await render({ ...base, params: oblique });
    expect(one.some((v, i) => i % 4 === 3 && v === 1)).toBe(true);
    expect(differingWords(await render({ ...base, params: oblique, iterations: 5 }), one)).toBe(0);
    // A brick atlas (8³ bricks with aprons): the exact filter reads the same texels with the same weights.
    expect(differingWords(await render({ ...base, params: oblique, bricking: 'force' }), one)).toBe(0);
    // Nearest on a bricked volume goes through the filter at the voxel's centre: the voxel, up to float32 weights.
    const axial: SliceParams = { axis: 'z', index: 4, fit: true };
    const plain = await render({ ...base, params: axial, width: 20, height: 12 });
    const bricked = await render({ ...base, params: axial, width: 20, height: 12, bricking: 'force' });
    expect(Math.max(...plain.map((v, i) => Math.abs(v - bricked[i])))).toBeLessThan(1e-6);
  });

  // (e) bad parameters: typed errors naming the field; a plane that does not fit the scene is refused by setScene.
  it('refuses bad parameters with typed errors naming the field, and keeps the previous scene', async () => {
    const result = await page.run(async ({ core, t }, backend) => {
      const errorOf = (f: () => unknown) => {
        try {
          f();
          return null;
        } catch (e) {
          return { code: (e as { code?: string }).code, message: (e as Error).message };
        }
      };
      const ctor = [
        errorOf(() => window.vpt.createRenderer('slice', { window: [40, 0] })),
        errorOf(() => window.vpt.createRenderer('slice', { axis: 'w' })),
        errorOf(() => window.vpt.createRenderer('slice', { normal: [0, 0, 1], index: 2 })),
        errorOf(() => window.vpt.createRenderer('slice', { colour: 'grey' })),
      ];
      const ctx = await t.context({ backend, renderer: 'slice', width: 4, height: 4, params: { index: 3 } });
      const scene = t.scene({ volume: core.createVolume([4, 4, 4], 'uint8') });
      ctx.setScene(scene);
      const thin = errorOf(() => ctx.setScene(t.scene({ volume: core.createVolume([4, 4, 2], 'uint8') })));
      const kept = ctx.getScene().volume.dims;
      // setRenderer keeps the scene and does not validate it: a plane that does not fit draws nothing and says so.
      ctx.setRenderer(window.vpt.createRenderer('slice', { index: 9 }));
      await ctx.renderIterations(1);
      const blank = Array.from(await ctx.readHDR()).every((v) => v === 0);
      const stats = ctx.stats.renderer;
      ctx.dispose();
      return { ctor, thin, kept, blank, stats };
    }, backend);
    expect(result.ctor.map((e) => e?.code)).toEqual([
      'invalid-scene',
      'invalid-scene',
      'invalid-scene',
      'invalid-scene',
    ]);
    expect(result.ctor[0]!.message).toMatch(/^SLICE\.window\[1\]: must be a number > 0/);
    expect(result.ctor[1]!.message).toMatch(/^SLICE\.axis: must be one of "x", "y", "z"/);
    expect(result.ctor[2]!.message).toMatch(/^SLICE\.index: is for an axis-aligned plane/);
    expect(result.ctor[3]!.message).toMatch(/unknown key "colour"/);
    expect(result.thin).toEqual({
      code: 'invalid-scene',
      message: expect.stringMatching(/^SLICE\.index: 3 is past the last of the volume's 2 layers along z/),
    });
    expect(result.kept).toEqual([4, 4, 4]);
    expect(result.blank).toBe(true);
    expect(result.stats.slice).toMatch(/^nothing drawn: SLICE\.index: 9 is past the last of the volume's 4 layers/);
  });
});

// (d) the two backends agree bit for bit (exact sampling; nearest reads texels on either path).
describe('slice renderer: WebGL 2 and WebGPU', () => {
  it('give the same bits for nearest, linear, 3D, colour tables and the transfer function', async () => {
    const dims: [number, number, number] = [12, 10, 8];
    const bytes = voxels(960, 0, 255, 13);
    const floats = bytes.map((v) => v * 0.37 - 20);
    const facing = (position: Vec3) => ({ ...defaultCamera(), position, up: [0, 1, 0] as Vec3 });
    const cases: Omit<SliceRender, 'backend'>[] = [
      {
        dims,
        type: 'uint8',
        data: bytes,
        params: { axis: 'y', index: 4, fit: true, colormap: 'hot' },
        width: 12,
        height: 8,
      },
      {
        dims,
        type: 'float32',
        data: floats,
        params: { normal: [1, 0.5, -0.4], sampling: 'linear', colormap: 'viridis', window: [30, 70] },
        width: 20,
        height: 16,
        sampling: 'exact',
        camera: facing([1.5, 0.9, -0.5]),
      },
      {
        dims,
        type: 'uint8',
        data: bytes,
        params: { axis: 'x', position: 0.1, colormap: 'transfer-function' },
        width: 20,
        height: 16,
        camera: facing([1.6, 0.3, 0.6]),
      },
    ];
    for (const c of cases) {
      const [a, b] = [await render({ ...c, backend: 'webgl2' }), await render({ ...c, backend: 'webgpu' })];
      expect(a.filter((v, i) => i % 4 === 3 && v === 1).length, JSON.stringify(c.params)).toBeGreaterThan(40);
      expect(differingWords(a, b), JSON.stringify(c.params)).toBe(0);
    }
  });

  it('vpt-render scene files: rendererParams go through the slice rules before a browser starts', () => {
    const desc = (rendererParams: unknown) => ({
      renderer: 'slice',
      volume: { procedural: 'sphere', size: 8 },
      rendererParams,
    });
    expect(() => validateSceneDescription(desc({ axis: 'y', index: 2, fit: true, window: [0.5, 1] }))).not.toThrow();
    expect(() => validateSceneDescription(desc({ window: [1, -1] }))).toThrow(/SLICE\.window\[1\]/);
    expect(() => validateSceneDescription(desc({ point: [0, 0, 0] }))).toThrow(/SLICE\.point: needs "normal"/);
  });
});

describe('slice gallery scene', () => {
  it('apps/gallery/scenes/head-slice.json: the PFM holds the windowed voxels of the axial slice, on both backends', async () => {
    const { description, baseDir } = readSceneFile('apps/gallery/scenes/head-slice.json');
    const p = description.rendererParams as unknown as SliceParams & { index: number; window: [number, number] };
    expect(description.renderer).toBe('slice');
    expect([p.axis, p.fit, p.sampling]).toEqual(['y', true, 'nearest']);
    const [W, H] = [description.width!, description.height!];
    const [nx, ny, nz] = [128, 128, 84];
    expect([W % nx, H % nz]).toEqual([0, 0]); // whole pixels per voxel: nearest picks voxel ⌊pixel · n / W⌋
    const voxels = readFileSync('data/mri_head_volpack_brainsmall_128x128x84_uint8.raw');
    for (const backend of BACKENDS) {
      const r = await page().render({ ...description, backend }, { baseDir });
      const pfm = decodePFM(encodePFM(r.hdr, W, H)); // what vpt-render --pfm writes (RGB)
      let worst = 0;
      for (let y = 0; y < H; y++)
        for (let x = 0; x < W; x++) {
          const d = voxels[Math.floor((x * nx) / W) + nx * (p.index + ny * Math.floor((y * nz) / H))];
          const w = windowed(d, p.window);
          for (let c = 0; c < 3; c++) worst = Math.max(worst, Math.abs(pfm.rgba[4 * (x + W * y) + c] - w));
        }
      expect(worst, backend).toBeLessThan(1e-6);
    }
  });
});
