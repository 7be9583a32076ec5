import { describe, expect, it } from 'vitest';
import {
  colormapTable,
  commonChunks,
  rendererNames,
  reference,
  type Scene,
  type SceneSlicePlane,
  type Vec3,
} from '../packages/core/src/index.js';
import { validateSceneDescription } from '../packages/headless/src/validate-description.js';
import { usePage } from './helpers/session.js';

/**
 * "Slice in 3D": a scene's `slicePlane` drawn by MIP, EAM, ISO and MCRT as an opaque, unlit plane
 * (core's scene/slice-plane.ts, the shared chunk SLICE_PLANE). An analytic uint8 volume: zero in
 * front of the plane (the camera's side), a ramp of data values behind it, all below the value
 * range so every renderer sees an empty medium, and an obstacle at the top of the range in one
 * corner in front. Checked: where nothing is in front the pixel is the windowed (colour-mapped)
 * voxel the CPU finds on the plane; behind the obstacle MIP shows m + (1 − m)·plane and EAM
 * front + T·plane; both backends give the same image; and a scene without the field renders the
 * same bits before and after one with it, with no slice-plane code compiled.
 */
const page = usePage({ mcrt: true });

const N = 16;
const K0 = 8; // the plane's voxel layer along z
const W = 32,
  H = 32;
const CAMERA = { position: [0.12, 0.08, -1.3] as Vec3, target: [0, 0, 0.03] as Vec3, up: [0, 1, 0] as Vec3, fovy: 0.8 };
const RANGE: [number, number] = [250, 255];
/** Obstacle voxels (data 255, normalized 1) in front of the plane: i < 5, j < 6, 2 <= k <= 4. */
const OBSTACLE = { i: [0, 5], j: [0, 6], k: [2, 5] } as const;
const WINDOW: [number, number] = [150, 100];

function dataAt(i: number, j: number, k: number): number {
  if (k >= K0) return 100 + 7 * i + 2 * j + (k - K0);
  const inObstacle =
    i >= OBSTACLE.i[0] &&
    i < OBSTACLE.i[1] &&
    j >= OBSTACLE.j[0] &&
    j < OBSTACLE.j[1] &&
    k >= OBSTACLE.k[0] &&
    k < OBSTACLE.k[1];
  return inObstacle ? 255 : 0;
}
const voxels = (() => {
  const a: number[] = [];
  for (let k = 0; k < N; k++) for (let j = 0; j < N; j++) for (let i = 0; i < N; i++) a.push(dataAt(i, j, k));
  return a;
})();

type Image = number[];

async function render(
  backend: string,
  renderer: string,
  plane: SceneSlicePlane | null,
  iterations: number,
  params: object = {},
  sampling: 'exact' | 'fast' = 'exact',
): Promise<Image> {
  return page.run(
    async ({ core, t }, backend, renderer, plane, iterations, params, sampling, voxels, n, range, camera, w, h) => {
      const volume = core.createVolume([n, n, n], 'uint8', new Uint8Array(voxels));
      volume.valueRange = range;
      const ctx = await t.context({ backend, renderer, width: w, height: h, params, sampling });
      const transferFunction = t.tf1d([0, [1, 1, 1], 0], [0.5, [0.2, 0.6, 1], 0.5], [1, [0.9, 0.5, 0.3], 1]);
      const lights = [
        { type: 'directional' as const, direction: [0.3, -1, 0.5] as Vec3, irradiance: [1, 1, 1] as Vec3 },
      ];
      ctx.setScene({
        ...t.scene({ volume, camera, transferFunction, densityScale: 40 }),
        lights,
        ...(plane ? { slicePlane: plane } : {}),
      });
      return t.finalHDR(ctx, iterations);
    },
    backend,
    renderer,
    plane,
    iterations,
    params,
    sampling,
    voxels,
    N,
    RANGE,
    CAMERA,
    W,
    H,
  );
}

const scene = { camera: CAMERA } as Scene;
const ray = (u: number, v: number) => reference.cameraRay(scene, W, H, u / W, v / H);
const PLANE_Z = -0.5 + (K0 + 0.5) / N;
const VOXEL = 1 / N;

/** Where a ray (float64) meets the plane, or null outside the box. */
function onPlane(u: number, v: number): Vec3 | null {
  const { origin: o, dir: d } = ray(u, v);
  const t = (PLANE_Z - o[2]) / d[2];
  const p: Vec3 = [o[0] + d[0] * t, o[1] + d[1] * t, PLANE_Z];
  return Math.abs(p[0]) < 0.5 && Math.abs(p[1]) < 0.5 ? p : null;
}
const voxelOf = (p: Vec3) => [Math.floor((p[0] + 0.5) * N), Math.floor((p[1] + 0.5) * N)];

/** Whether the segment from the camera to p passes within `margin` of the obstacle's box. */
function nearObstacle(p: Vec3, margin: number): boolean {
  const o = CAMERA.position;
  const lo = [OBSTACLE.i[0], OBSTACLE.j[0], OBSTACLE.k[0]].map((x) => -0.5 + x * VOXEL - margin);
  const hi = [OBSTACLE.i[1], OBSTACLE.j[1], OBSTACLE.k[1]].map((x) => -0.5 + x * VOXEL + margin);
  let t0 = 0,
    t1 = 1;
  for (let a = 0; a < 3; a++) {
    const d = p[a] - o[a];
    const ta = (lo[a] - o[a]) / d,
      tb = (hi[a] - o[a]) / d;
    t0 = Math.max(t0, Math.min(ta, tb));
    t1 = Math.min(t1, Math.max(ta, tb));
  }
  return t0 <= t1;
}

/**
 * Pixels whose whole footprint (the four corners and the centre) lands on one voxel of the plane
 * with nothing in front (`clearOf` clear of the obstacle; < 0: anything may be), with that voxel's data value; `centre`:
 * only the pixel-centre ray (MIP, ISO without jitter), away from a voxel border by 1e-3 voxel.
 */
function clearPixels(centre: boolean, clearOf = 2 * VOXEL): { x: number; y: number; data: number }[] {
  const out: { x: number; y: number; data: number }[] = [];
  for (let y = 0; y < H; y++)
    for (let x = 0; x < W; x++) {
      const pts = centre
        ? [[x + 0.5, y + 0.5]]
        : [
            [x, y],
            [x + 1, y],
            [x, y + 1],
            [x + 1, y + 1],
            [x + 0.5, y + 0.5],
          ];
      const hits = pts.map(([u, v]) => onPlane(u, v));
      if (hits.some((p) => p === null || (clearOf >= 0 && nearObstacle(p, clearOf)))) continue;
      const cells = hits.map((p) => voxelOf(p!));
      if (cells.some((c) => c[0] !== cells[0][0] || c[1] !== cells[0][1])) continue;
      if (centre) {
        const g = hits[0]!.slice(0, 2).map((c) => (c + 0.5) * N);
        if (g.some((c) => Math.abs(c - Math.round(c)) < 1e-3)) continue;
      }
      out.push({ x, y, data: dataAt(cells[0][0], cells[0][1], K0) });
    }
  return out;
}

const windowed = (d: number) => Math.min(1, Math.max(0, (d - (WINDOW[0] - WINDOW[1] / 2)) / WINDOW[1]));
function viridis(w: number): Vec3 {
  const t = colormapTable('viridis');
  const n = t.length / 4;
  const x = w * (n - 1),
    i0 = Math.floor(x),
    i1 = Math.min(i0 + 1, n - 1),
    f = x - i0;
  return [0, 1, 2].map((c) => t[4 * i0 + c] + (t[4 * i1 + c] - t[4 * i0 + c]) * f) as Vec3;
}

function bitsDiffer(a: Image, b: Image): number {
  const u = new Uint32Array(new Float32Array(a).buffer),
    v = new Uint32Array(new Float32Array(b).buffer);
  let n = 0;
  for (let i = 0; i < u.length; i++) if (u[i] !== v[i]) n++;
  return n;
}

const PLANE: SceneSlicePlane = { axis: 'z', index: K0, window: WINDOW };
/** Renderer parameters that make each deterministic where it can be (ISO: the pixel-centre ray). */
const PARAMS: Record<string, object> = {
  iso: { surfaces: [{ value: 0.5, color: [1, 1, 1] }], jitter: false },
};
const ITERATIONS: Record<string, number> = { mip: 2, eam: 2, iso: 2, mcrt: 4 };

/** The renderers of the catalog that draw a slice plane (all but the slice renderer itself). */
const DRAWING = rendererNames().filter((n) => n !== 'slice');

describe('slice in 3D: the plane where nothing is in front is the windowed voxel, on both backends', () => {
  for (const renderer of DRAWING) {
    it(renderer, async () => {
      const params = PARAMS[renderer] ?? {};
      const gl = await render('webgl2', renderer, PLANE, ITERATIONS[renderer], params);
      const gpu = await render('webgpu', renderer, PLANE, ITERATIONS[renderer], params);
      expect(gl.every(Number.isFinite)).toBe(true);
      const pixels = clearPixels(renderer === 'mip' || renderer === 'iso');
      expect(pixels.length).toBeGreaterThan(renderer === 'mip' || renderer === 'iso' ? 200 : 80);
      const errors: string[] = [];
      for (const { x, y, data } of pixels) {
        const i = 4 * (x + W * y);
        const want = windowed(data);
        for (let c = 0; c < 3; c++)
          if (!(Math.abs(gl[i + c] - want) <= 1e-6)) errors.push(`(${x}, ${y})[${c}]: ${gl[i + c]}, want ${want}`);
        if (gl[i + 3] !== 1) errors.push(`(${x}, ${y}) alpha ${gl[i + 3]}`);
      }
      expect(errors.slice(0, 8).join('\n')).toBe('');
      expect(bitsDiffer(gl, gpu)).toBe(0);
    });
  }
});

describe('slice in 3D: composited behind what is in front', () => {
  it('MIP: the obstacle (normalized 1) in front gives m + (1 − m)·plane = 1; EAM: front + T·plane', async () => {
    const mip = await render('webgl2', 'mip', PLANE, 2);
    let behind = 0;
    for (let y = 0; y < H; y++)
      for (let x = 0; x < W; x++) {
        const p = onPlane(x + 0.5, y + 0.5);
        // Through the obstacle's core (shrunk by 1.5 voxels: the samples there are the top of the range).
        if (!p || !nearObstacle(p, -1.5 * VOXEL)) continue;
        behind++;
        expect(mip[4 * (x + W * y)]).toBe(1);
      }
    expect(behind).toBeGreaterThan(2);
    // EAM: without the plane the medium behind it is empty, so that image is (front, 1 − T).
    const eam = await render('webgl2', 'eam', PLANE, 64);
    const open = await render('webgl2', 'eam', null, 64);
    let worst = 0,
      checked = 0;
    // Pixels whose footprint lands on one voxel of the plane, whatever is in front.
    for (const { x, y, data } of clearPixels(false, -1)) {
      const i = 4 * (x + W * y);
      const T = 1 - open[i + 3];
      if (T > 0.99) continue;
      checked++;
      for (let c = 0; c < 3; c++) worst = Math.max(worst, Math.abs(eam[i + c] - (open[i + c] + T * windowed(data))));
    }
    expect(checked).toBeGreaterThan(3);
    // In expectation exact; the two marches' lattices differ (one ends at the plane, one at the box).
    expect(worst).toBeLessThan(0.03);
  });
});

describe('slice in 3D: colour maps, sampling, clip', () => {
  it('EAM with viridis: the plane is the colour map at the windowed value (fast sampling too)', async () => {
    const plane = { ...PLANE, colormap: 'viridis' as const };
    for (const sampling of ['exact', 'fast'] as const) {
      const img = await render('webgl2', 'eam', plane, 2, {}, sampling);
      const pixels = clearPixels(false);
      let worst = 0;
      for (const { x, y, data } of pixels) {
        const want = viridis(windowed(data));
        for (let c = 0; c < 3; c++) worst = Math.max(worst, Math.abs(img[4 * (x + W * y) + c] - want[c]));
      }
      expect(worst, sampling).toBeLessThan(1e-5);
    }
  });

  it('a forced brick atlas gives the unbricked image (the nearest voxel read through the page table)', async () => {
    const plain = await render('webgl2', 'eam', PLANE, 2);
    const bricked = await page.run(
      async ({ core, t }, voxels, n, range, camera, w, h, plane) => {
        const volume = core.createVolume([n, n, n], 'uint8', new Uint8Array(voxels));
        volume.valueRange = range;
        const ctx = await t.context({
          backend: 'webgl2',
          renderer: 'eam',
          width: w,
          height: h,
          sampling: 'exact',
          bricking: 'force',
          brickSize: 8,
        });
        const transferFunction = t.tf1d([0, [1, 1, 1], 0], [0.5, [0.2, 0.6, 1], 0.5], [1, [0.9, 0.5, 0.3], 1]);
        const lights = [
          { type: 'directional' as const, direction: [0.3, -1, 0.5] as Vec3, irradiance: [1, 1, 1] as Vec3 },
        ];
        ctx.setScene({ ...t.scene({ volume, camera, transferFunction, densityScale: 40 }), lights, slicePlane: plane });
        const settled = await ctx.whenBricksSettled();
        return { image: await t.finalHDR(ctx, 2), bricked: settled !== null };
      },
      voxels,
      N,
      RANGE,
      CAMERA,
      W,
      H,
      PLANE,
    );
    expect(bricked.bricked).toBe(true);
    let worst = 0;
    for (let i = 0; i < plain.length; i++) worst = Math.max(worst, Math.abs(plain[i] - bricked.image[i]));
    expect(worst).toBeLessThan(1e-6);
  });

  it('a clip plane removes the slice plane where it cuts (the volume is empty there, so the background shows)', async () => {
    const clipped = await page.run(
      async ({ core, t }, voxels, n, range, camera, w, h, plane) => {
        const volume = core.createVolume([n, n, n], 'uint8', new Uint8Array(voxels));
        volume.valueRange = range;
        const ctx = await t.context({ backend: 'webgl2', renderer: 'eam', width: w, height: h, sampling: 'exact' });
        ctx.setScene({
          ...t.scene({ volume, camera }),
          slicePlane: plane,
          clip: { planes: [{ normal: [1, 0, 0], offset: 0 }] },
        });
        return t.finalHDR(ctx, 2);
      },
      voxels,
      N,
      RANGE,
      CAMERA,
      W,
      H,
      PLANE,
    );
    let kept = 0,
      removed = 0;
    for (const { x, y, data } of clearPixels(false)) {
      const i = 4 * (x + W * y);
      const p = onPlane(x + 0.5, y + 0.5)!;
      if (Math.abs(p[0]) < 2 * VOXEL) continue;
      if (p[0] > 0) {
        removed++;
        expect(clipped[i + 3]).toBe(0);
      } else {
        kept++;
        expect(Math.abs(clipped[i] - windowed(data))).toBeLessThan(1e-6);
      }
    }
    expect(kept).toBeGreaterThan(20);
    expect(removed).toBeGreaterThan(20);
  });

  it('a bad slicePlane is a typed error naming the field, and the context keeps its scene', async () => {
    const messages = await page.run(
      async ({ core, t }, voxels, n, range) => {
        const volume = core.createVolume([n, n, n], 'uint8', new Uint8Array(voxels));
        volume.valueRange = range;
        const ctx = await t.context({ backend: 'webgl2', renderer: 'eam', width: 8, height: 8 });
        const out: string[] = [];
        for (const slicePlane of [
          { index: n },
          { colormap: 'jet' },
          { window: [0, 0] },
          { axis: 'x', normal: [1, 0, 0] },
        ])
          try {
            ctx.setScene({ ...t.scene({ volume }), slicePlane } as never);
            out.push('accepted');
          } catch (e) {
            out.push(`${(e as { code?: string }).code}: ${(e as Error).message}`);
          }
        ctx.dispose();
        return out;
      },
      voxels,
      N,
      RANGE,
    );
    expect(messages[0]).toMatch(/^invalid-scene: Scene: slicePlane\.index: 16 is past the last/);
    expect(messages[1]).toMatch(/^invalid-scene: Scene: slicePlane\.colormap/);
    expect(messages[2]).toMatch(/^invalid-scene: Scene: slicePlane\.window\[1\]/);
    expect(messages[3]).toMatch(/^invalid-scene: Scene: slicePlane\.axis: is for an axis-aligned plane/);
  });
});

describe('slice in 3D: scene files', () => {
  it('vpt-render checks a slicePlane before a browser starts, errors naming the field', () => {
    expect(() => validateSceneDescription({ slicePlane: { axis: 'z', index: 3, window: [40, 400] } })).not.toThrow();
    expect(() => validateSceneDescription({ slicePlane: { colormap: 'jet' } })).toThrow(
      /^Scene description: slicePlane\.colormap/,
    );
    expect(() => validateSceneDescription({ slicePlane: { index: 1, position: 0 } })).toThrow(
      /^Scene description: slicePlane\.position/,
    );
    expect(() => validateSceneDescription({ slicePlane: { sampling: 'cubic', extra: 1 } })).toThrow(/slicePlane/);
  });
});

describe('slice in 3D: a scene without the field is unchanged', () => {
  it('the shared chunks hold no slice-plane code unless asked', () => {
    for (const lang of ['glsl', 'wgsl'] as const) {
      expect(commonChunks({})[lang]).not.toMatch(/slicePlane/);
      expect(commonChunks({ slicePlane: true })[lang]).toMatch(/slicePlaneHit/);
    }
  });

  for (const renderer of DRAWING)
    it(`${renderer}: the same bits before and after a render with a slice plane, on one context`, async () => {
      const out = await page.run(
        async ({ core, t }, renderer, params, voxels, n, range, camera, w, h, plane) => {
          const volume = core.createVolume([n, n, n], 'uint8', new Uint8Array(voxels));
          volume.valueRange = range;
          const ctx = await t.context({ backend: 'webgl2', renderer, width: w, height: h, params, sampling: 'exact' });
          const base = t.scene({ volume, camera, densityScale: 40 });
          const read = async (s: object) => {
            ctx.setScene(s as never);
            await ctx.renderIterations(2);
            return Array.from(await ctx.readHDR()) as number[];
          };
          const before = await read(base);
          const withPlane = await read({ ...base, slicePlane: plane });
          const after = await read(base);
          ctx.dispose();
          return { before, withPlane, after };
        },
        renderer,
        PARAMS[renderer] ?? {},
        voxels,
        N,
        RANGE,
        CAMERA,
        W,
        H,
        PLANE,
      );
      expect(bitsDiffer(out.before, out.after)).toBe(0);
      expect(bitsDiffer(out.before, out.withPlane)).toBeGreaterThan(100);
    });
});
