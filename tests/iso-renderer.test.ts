import { describe, expect, it } from 'vitest';
import { reference, type Scene, type Vec3 } from '../packages/core/src/index.js';
import { readSceneFile } from '../packages/headless/src/index.js';
import { BACKENDS, usePage } from './helpers/session.js';

/**
 * The ISO renderer against analytic answers. The volume is a distance field, value(p) = |p|
 * (world units, valueRange [0, 1]), sampled at N³ voxel centres, so the isosurface at value r
 * is the sphere of radius r about the origin: depth, normal and shading have closed forms.
 */
const N = 32;
const VOXEL = 1 / N;
const W = 24,
  H = 24;
const CAMERA = { position: [0.35, 0.25, 1.5] as Vec3, target: [0, 0, 0] as Vec3, up: [0, 1, 0] as Vec3, fovy: 0.55 };

/** Render in the page: `params` for the IsoRenderer, `scene` merged over a default scene of the sphere field. */
async function renderIso(
  page: ReturnType<typeof usePage>,
  backend: string,
  params: object,
  scene: object,
  iterations: number,
  size = [W, H],
): Promise<number[]> {
  return page.run(
    async ({ t }, backend, params, scene, iterations, n, camera, size) => {
      const volume = window.tv.sphereDistance(n);
      const ctx = await t.context({ backend, renderer: 'iso', width: size[0], height: size[1], params });
      ctx.setScene({ ...t.scene({ volume, camera }), ...scene });
      return t.finalHDR(ctx, iterations);
    },
    backend,
    params,
    scene,
    iterations,
    N,
    CAMERA,
    size,
  );
}

/** Analytic ray–sphere intersection: the nearer t, and the ray's closest distance to the centre. */
function sphereHit(origin: Vec3, dir: Vec3, r: number): { t: number; dist: number } {
  const b = origin[0] * dir[0] + origin[1] * dir[1] + origin[2] * dir[2];
  const c = origin[0] ** 2 + origin[1] ** 2 + origin[2] ** 2 - r * r;
  const disc = b * b - c;
  const dist = Math.sqrt(Math.max(0, origin[0] ** 2 + origin[1] ** 2 + origin[2] ** 2 - b * b));
  return { t: disc >= 0 ? -b - Math.sqrt(disc) : NaN, dist };
}

const scene = { camera: CAMERA } as Scene;

/**
 * Pixel (x, y) of the W × H image against the sphere of radius r at the origin: 'inside' when
 * the rays through its four corners all pass within r − VOXEL of the centre (full coverage,
 * clear of the voxelised surface's error), 'outside' when all pass farther than r + VOXEL.
 */
function pixelAgainstSphere(x: number, y: number, r: number): 'inside' | 'outside' | 'edge' {
  const dists = [
    [0, 0],
    [1, 0],
    [0, 1],
    [1, 1],
  ].map(([cx, cy]) => {
    const ray = reference.cameraRay(scene, W, H, (x + cx) / W, (y + cy) / H);
    return sphereHit(ray.origin, ray.dir, r).dist;
  });
  return Math.max(...dists) < r - VOXEL ? 'inside' : Math.min(...dists) > r + VOXEL ? 'outside' : 'edge';
}
const centreRay = (x: number, y: number, w = W, h = H) =>
  reference.cameraRay(scene, w, h, (x + 0.5) / w, (y + 0.5) / h);
const at = (o: Vec3, d: Vec3, t: number): Vec3 => [o[0] + d[0] * t, o[1] + d[1] * t, o[2] + d[2] * t];
const angleDeg = (a: Vec3, b: Vec3) =>
  (Math.acos(Math.min(1, (a[0] * b[0] + a[1] * b[1] + a[2] * b[2]) / Math.hypot(...a) / Math.hypot(...b))) * 180) /
  Math.PI;

const page = usePage();
const R = 0.3;

describe.each(BACKENDS)('ISO renderer on %s', (backend) => {
  it('hits a sphere at the analytic depth (within 0.1 voxel) with the analytic normal (within 1°)', async () => {
    const surfaces = [{ value: R, color: [1, 1, 1] }];
    const depth = await renderIso(page, backend, { surfaces, jitter: false, output: 'depth' }, {}, 1);
    const normal = await renderIso(page, backend, { surfaces, jitter: false, output: 'normal' }, {}, 1);
    let inside = 0,
      outside = 0,
      maxDepthErr = 0,
      maxAngle = 0;
    for (let y = 0; y < H; y++) {
      for (let x = 0; x < W; x++) {
        const i = 4 * (x + W * y);
        const { origin, dir } = centreRay(x, y);
        const hit = sphereHit(origin, dir, R);
        if (hit.dist < R - VOXEL) {
          inside++;
          expect(depth[i + 3]).toBe(1);
          maxDepthErr = Math.max(maxDepthErr, Math.abs(depth[i] - hit.t));
          const p = at(origin, dir, hit.t);
          maxAngle = Math.max(maxAngle, angleDeg([normal[i], normal[i + 1], normal[i + 2]], p));
          expect(Math.hypot(normal[i], normal[i + 1], normal[i + 2])).toBeCloseTo(1, 5);
        } else if (hit.dist > R + VOXEL) {
          outside++;
          expect([depth[i], depth[i + 3], normal[i + 3]]).toEqual([0, 0, 0]);
        }
      }
    }
    expect(inside).toBeGreaterThan(150);
    expect(outside).toBeGreaterThan(100);
    expect(maxDepthErr).toBeLessThan(0.1 * VOXEL);
    expect(maxAngle).toBeLessThan(1);
  });

  it('keeps the nearest of the jittered hits inside each pixel', async () => {
    const depth = await renderIso(
      page,
      backend,
      { surfaces: [{ value: R, color: [1, 1, 1] }], output: 'depth' },
      {},
      16,
    );
    let checked = 0,
      nearerThanCentre = 0;
    for (let y = 0; y < H; y++) {
      for (let x = 0; x < W; x++) {
        const { origin, dir } = centreRay(x, y);
        if (sphereHit(origin, dir, R).dist > R - 2 * VOXEL) continue;
        // The analytic depth over the pixel footprint (a 9 x 9 grid, corners included).
        let lo = Infinity,
          hi = -Infinity;
        for (let j = 0; j <= 8; j++)
          for (let k = 0; k <= 8; k++) {
            const ray = reference.cameraRay(scene, W, H, (x + k / 8) / W, (y + j / 8) / H);
            const t = sphereHit(ray.origin, ray.dir, R).t;
            lo = Math.min(lo, t);
            hi = Math.max(hi, t);
          }
        const d = depth[4 * (x + W * y)];
        const centre = sphereHit(origin, dir, R).t;
        expect(d).toBeGreaterThan(lo - 0.05 * VOXEL);
        expect(d).toBeLessThan(hi + 0.05 * VOXEL);
        if (d < centre) nearerThanCentre++;
        checked++;
      }
    }
    expect(checked).toBeGreaterThan(120);
    // The minimum of 16 jittered depths lies below the pixel-centre depth almost always.
    expect(nearerThanCentre / checked).toBeGreaterThan(0.9);
  });

  it('shades a Lambertian sphere under a directional light as albedo/π · E · cos, and its dark side black', async () => {
    const albedo: Vec3 = [0.9, 0.6, 0.3];
    const E: Vec3 = [2, 3, 4];
    const l: Vec3 = [1, 0.4, -0.5];
    const ll = Math.hypot(...l);
    const img = await renderIso(
      page,
      backend,
      { surfaces: [{ value: R, color: albedo }], specular: 0, jitter: false },
      {
        lights: [{ type: 'directional', direction: l, irradiance: E }],
        environment: { type: 'constant', radiance: [0, 0, 0] },
      },
      2,
    );
    let lit = 0,
      dark = 0;
    for (let y = 0; y < H; y++) {
      for (let x = 0; x < W; x++) {
        const { origin, dir } = centreRay(x, y);
        const hit = sphereHit(origin, dir, R);
        if (hit.dist > R - VOXEL) continue;
        const p = at(origin, dir, hit.t);
        const cos = (p[0] * l[0] + p[1] * l[1] + p[2] * l[2]) / (R * ll);
        const i = 4 * (x + W * y);
        for (let c = 0; c < 3; c++) {
          // A 1° normal error moves cos by at most sin(1°) < 0.018.
          expect(Math.abs(img[i + c] - (albedo[c] / Math.PI) * E[c] * Math.max(0, cos))).toBeLessThan(
            (albedo[c] / Math.PI) * E[c] * 0.018 + 1e-6,
          );
        }
        if (cos > 0.1) lit++;
        if (cos < -0.05) {
          dark++;
          expect([img[i], img[i + 1], img[i + 2]]).toEqual([0, 0, 0]);
        }
      }
    }
    expect(lit).toBeGreaterThan(40);
    expect(dark).toBeGreaterThan(20);
  });

  it('converges to the soft shadow of a light of finite angular size (penumbra vs a CPU visibility integral)', async () => {
    // A small sphere (blocker) above a larger one (receiver), lit from above by a light of angular
    // radius 0.15 rad: the receiver's radiance is albedo/π · E · cos · V, V the visible fraction of
    // the light's cone, integrated here on a fine grid of cone directions.
    const A = { c: [0, 0.17, 0] as Vec3, r: 0.1 },
      B = { c: [0, -0.24, 0] as Vec3, r: 0.2 };
    const cam = { position: [0, 0.75, 1.0] as Vec3, target: [0, -0.2, 0] as Vec3, up: [0, 1, 0] as Vec3, fovy: 0.5 };
    const radius = 0.15,
      E = 3,
      ITER = 64;
    const img: number[] = await page.run(
      async ({ core, t }, backend, A, B, cam, radius, E, ITER, n) => {
        const data = new Float32Array(n * n * n);
        for (let z = 0; z < n; z++)
          for (let y = 0; y < n; y++)
            for (let x = 0; x < n; x++) {
              const p = [(x + 0.5) / n - 0.5, (y + 0.5) / n - 0.5, (z + 0.5) / n - 0.5];
              data[x + n * (y + n * z)] =
                0.5 +
                Math.min(
                  Math.hypot(p[0] - A.c[0], p[1] - A.c[1], p[2] - A.c[2]) - A.r,
                  Math.hypot(p[0] - B.c[0], p[1] - B.c[1], p[2] - B.c[2]) - B.r,
                );
            }
        const volume = core.createVolume([n, n, n], 'float32', data);
        volume.valueRange = [0, 1];
        const ctx = await t.context({
          backend,
          renderer: 'iso',
          width: 24,
          height: 24,
          params: {
            surfaces: [{ value: 0.5, color: [1, 1, 1] }],
            specular: 0,
            jitter: false,
            lightAngularRadius: radius,
          },
        });
        ctx.setScene({
          ...t.scene({ volume, camera: cam }),
          lights: [{ type: 'directional', direction: [0, 1, 0], irradiance: [E, E, E] }],
        });
        return t.finalHDR(ctx, ITER);
      },
      backend,
      A,
      B,
      cam,
      radius,
      E,
      ITER,
      N,
    );
    const sc = { camera: cam } as Scene;
    const hitSphere = (o: Vec3, d: Vec3, s: { c: Vec3; r: number }) =>
      sphereHit([o[0] - s.c[0], o[1] - s.c[1], o[2] - s.c[2]], d, s.r);
    let umbra = 0,
      penumbra = 0,
      maxZ = 0;
    for (let y = 0; y < 24; y++) {
      for (let x = 0; x < 24; x++) {
        const { origin, dir } = reference.cameraRay(sc, 24, 24, (x + 0.5) / 24, (y + 0.5) / 24);
        const a = hitSphere(origin, dir, A),
          b = hitSphere(origin, dir, B);
        if (!(b.dist < B.r - VOXEL) || (a.dist < A.r + VOXEL && a.t < b.t)) continue; // receiver pixels only
        const p = at(origin, dir, b.t);
        const nrm: Vec3 = [(p[0] - B.c[0]) / B.r, (p[1] - B.c[1]) / B.r, (p[2] - B.c[2]) / B.r];
        if (nrm[1] < 0.3) continue;
        const o = at(p, nrm, 0.5 * VOXEL);
        // Uniform over the cone about +y: cosθ = 1 − u(1 − cos r), φ = 2πv, on a 24 x 24 midpoint grid.
        let visible = 0;
        const G = 24;
        for (let i = 0; i < G; i++)
          for (let j = 0; j < G; j++) {
            const ct = 1 - ((i + 0.5) / G) * (1 - Math.cos(radius)),
              st = Math.sqrt(1 - ct * ct),
              ph = (2 * Math.PI * (j + 0.5)) / G;
            const w: Vec3 = [st * Math.cos(ph), ct, st * Math.sin(ph)];
            const blocked = hitSphere(o, w, A);
            if (!(blocked.t > 0)) visible++;
          }
        const V = visible / (G * G);
        const lit = (1 / Math.PI) * E * nrm[1];
        const gpu = img[4 * (x + 24 * y)];
        const sd = lit * Math.sqrt((V * (1 - V)) / ITER) + 0.03 * lit; // Bernoulli noise, plus grid and surface error
        maxZ = Math.max(maxZ, Math.abs(gpu - lit * V) / sd);
        if (V === 0) {
          umbra++;
          expect(gpu).toBe(0);
        }
        if (V > 0.15 && V < 0.85) penumbra++;
      }
    }
    expect(umbra).toBeGreaterThan(4);
    expect(penumbra).toBeGreaterThan(8);
    expect(maxZ).toBeLessThan(5);
  });

  it('reflects albedo × L under a constant environment: a convex surface occludes none of its own sky', async () => {
    // Cosine-weighted ambient-occlusion rays: f·L·cos/pdf = albedo·L exactly when nothing blocks them,
    // so any self-shadowing (rays re-hitting the surface they leave) would show as a deficit.
    const albedo: Vec3 = [0.8, 0.5, 0.2];
    const L: Vec3 = [1.5, 1, 2];
    const img = await renderIso(
      page,
      backend,
      { surfaces: [{ value: R, color: albedo }], specular: 0 },
      { environment: { type: 'constant', radiance: L } },
      8,
    );
    let interior = 0,
      background = 0;
    for (let y = 0; y < H; y++) {
      for (let x = 0; x < W; x++) {
        const i = 4 * (x + W * y);
        const where = pixelAgainstSphere(x, y, R);
        if (where === 'inside') {
          interior++;
          for (let c = 0; c < 3; c++) expect(img[i + c]).toBeCloseTo(albedo[c] * L[c], 4);
          expect(img[i + 3]).toBe(1);
        } else if (where === 'outside') {
          background++;
          expect(Array.from(img.slice(i, i + 4))).toEqual([...L.map((v) => Math.fround(v)), 0]);
        }
      }
    }
    expect(interior).toBeGreaterThan(100);
    expect(background).toBeGreaterThan(100);
  });

  it('lights a convex surface by a uniform lat-long map as by the same constant sky (environment sampling with MIS)', async () => {
    const albedo: Vec3 = [0.8, 0.5, 0.2];
    const L: Vec3 = [1.5, 1, 2];
    const ITER = 24;
    const env = { type: 'latlong', width: 16, height: 8, data: Array.from({ length: 16 * 8 * 3 }, (_, i) => L[i % 3]) };
    const img: number[] = await page.run(
      async ({ t }, backend, albedo, env, ITER, n, camera) => {
        const ctx = await t.context({
          backend,
          renderer: 'iso',
          width: 24,
          height: 24,
          params: { surfaces: [{ value: 0.3, color: albedo }], specular: 0 },
        });
        ctx.setScene({
          ...t.scene({ volume: window.tv.sphereDistance(n), camera }),
          environment: { ...env, data: Float32Array.from(env.data) },
        });
        return t.finalHDR(ctx, ITER);
      },
      backend,
      albedo,
      env,
      ITER,
      N,
      CAMERA,
    );
    const sum = [0, 0, 0];
    let interior = 0;
    for (let y = 0; y < H; y++) {
      for (let x = 0; x < W; x++) {
        const i = 4 * (x + W * y);
        const where = pixelAgainstSphere(x, y, R);
        if (where === 'inside') {
          interior++;
          for (let c = 0; c < 3; c++) sum[c] += img[i + c];
        } else if (where === 'outside') {
          // The background is the map itself.
          for (let c = 0; c < 3; c++) expect(img[i + c]).toBeCloseTo(L[c], 5);
        }
      }
    }
    expect(interior).toBeGreaterThan(100);
    // Mean over ~4000 MIS estimates per channel; their spread is well under the 2 % allowed here.
    for (let c = 0; c < 3; c++) expect(Math.abs(sum[c] / interior / (albedo[c] * L[c]) - 1)).toBeLessThan(0.02);
  });

  it('composites semi-transparent surfaces stochastically: camera and occlusion rays pass with probability 1 − opacity', async () => {
    // Outer sphere r = 0.35 (red, opacity 0.5) around an opaque blue sphere r = 0.2, sky L = 1,
    // no specular. Through the inner sphere: the outer one is seen with probability 0.5 (red,
    // nothing occludes it); otherwise the inner one (blue), whose every occlusion ray crosses the
    // outer shell once and passes with probability 0.5. Expected rgb = (0.5, 0, 0.25).
    const ITER = 96;
    const img = await renderIso(
      page,
      backend,
      {
        surfaces: [
          { value: 0.35, color: [1, 0, 0], opacity: 0.5 },
          { value: 0.2, color: [0, 0, 1] },
        ],
        specular: 0,
      },
      { environment: { type: 'constant', radiance: [1, 1, 1] } },
      ITER,
    );
    const sum = [0, 0, 0];
    let n = 0;
    for (let y = 0; y < H; y++) {
      for (let x = 0; x < W; x++) {
        if (pixelAgainstSphere(x, y, 0.2) !== 'inside') continue;
        const i = 4 * (x + W * y);
        for (let c = 0; c < 3; c++) sum[c] += img[i + c];
        expect(img[i + 3]).toBe(1);
        n++;
      }
    }
    expect(n).toBeGreaterThan(30);
    const mean = sum.map((s) => s / n);
    // Standard errors over n·ITER independent samples: red sqrt(.25/(n·ITER)) ≈ 0.007, blue ≈ 0.006 at n = 40.
    const se = (p: number) => Math.sqrt((p * (1 - p)) / (n * ITER));
    expect(Math.abs(mean[0] - 0.5)).toBeLessThan(5 * se(0.5));
    expect(mean[1]).toBe(0);
    expect(Math.abs(mean[2] - 0.25)).toBeLessThan(5 * se(0.25));
  });
});

describe('ISO renderer: WebGL 2 / WebGPU parity', () => {
  it('gives bit-identical images and depth buffers (2 surfaces, transparency, soft shadows, lat-long environment)', async () => {
    const r = await page.run(async ({ t }, camera) => {
      const volume = window.tv.sphereDistance(20);
      const env = {
        type: 'latlong',
        width: 8,
        height: 4,
        data: Float32Array.from({ length: 96 }, (_, i) => ((i * 37) % 11) / 4),
      };
      const out: Record<string, Float32Array[]> = {};
      for (const backend of ['webgl2', 'webgpu']) {
        out[backend] = [];
        for (const output of ['shaded', 'depth']) {
          const ctx = await t.context({
            backend,
            renderer: 'iso',
            width: 20,
            height: 16,
            params: {
              surfaces: [
                { value: 0.36, color: [0.9, 0.3, 0.2], opacity: 0.4 },
                { value: 0.22, color: [0.3, 0.6, 0.9] },
              ],
              lightAngularRadius: 0.2,
              specular: 0.3,
              shininess: 20,
              output,
            },
          });
          ctx.setScene({
            ...t.scene({ volume, camera, seed: 5 }),
            environment: env,
            lights: [
              { type: 'directional', direction: [1, 1, 0.5], irradiance: [2, 2, 2] },
              { type: 'directional', direction: [-1, 0.2, 1], irradiance: [0.5, 0.3, 0.1] },
            ],
          });
          await ctx.renderIterations(3);
          out[backend].push(await ctx.readHDR());
          ctx.dispose();
        }
      }
      const a = out.webgl2[0];
      let varied = 0;
      for (let i = 4; i < a.length; i += 4) if (a[i] !== a[0]) varied++;
      return {
        shadedDiff: t.sameBits(out.webgl2[0], out.webgpu[0]),
        depthDiff: t.sameBits(out.webgl2[1], out.webgpu[1]),
        varied,
        n: a.length / 4,
        finite: !t.hasNonFinite(a),
      };
    }, CAMERA);
    expect(r.varied).toBeGreaterThan(r.n / 4);
    expect(r.finite).toBe(true);
    expect(r.shadedDiff).toBe(0);
    expect(r.depthDiff).toBe(0);
  });
});

describe('ISO gallery scene', () => {
  it('smoke: renders apps/gallery/scenes/head-iso.json through the headless page (renderer "iso" with its parameters)', async () => {
    const { description, baseDir } = readSceneFile('apps/gallery/scenes/head-iso.json');
    expect(description.renderer).toBe('iso');
    const r = await page().render(
      { ...description, width: 24, height: 24, iterations: 2, backend: 'webgl2' },
      { baseDir },
    );
    let hit = 0;
    for (let i = 0; i < r.hdr.length; i += 4) {
      for (let c = 0; c < 4; c++) expect(Number.isFinite(r.hdr[i + c])).toBe(true);
      if (r.hdr[i + 3] > 0) hit++;
    }
    // The head covers the middle of the frame, not the corners.
    expect(r.hdr[4 * (12 + 24 * 12) + 3]).toBe(1);
    expect(r.hdr[3]).toBe(0);
    expect(hit).toBeGreaterThan(24 * 24 * 0.1);
    expect(hit).toBeLessThan(24 * 24 * 0.9);
  });
});
