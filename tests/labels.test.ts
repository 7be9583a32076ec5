import { describe, expect, it } from 'vitest';
import { labelEntryOf, labelIdAt } from '../packages/core/src/scene/labels.js';
import { downsampleLabels } from '../packages/core/src/scene/label-downsample.js';
import {
  createVolume,
  downsampleVolume,
  rasterizeTransferFunction,
  reference,
  TF_RESOLUTION,
  type LabelEntry,
  type Scene,
  type TransferFunction,
  type Vec3,
} from '../packages/core/src/index.js';
import { tf1d } from './helpers/test-scene.js';
import { zSummary } from './helpers/mcrt-stats.js';
import { BACKENDS, usePage } from './helpers/session.js';

/**
 * Label volumes (scene/labels.ts): ids are read nearest, never blended (a checkerboard of two ids
 * at an oblique view shows only table colours); EAM and MIP with labels against CPU twins and
 * bit-identical across backends; a hidden label renders as if its voxels were background (bit for
 * bit); MCRT's image + labels mixture against a scalar volume holding the same medium (z-test);
 * typed errors.
 */
const page = usePage({ mcrt: true });

const N = 16;
const W = 20,
  H = 16;
const CAMERA = { position: [0.9, 0.5, 1.6] as Vec3, target: [0, 0, 0] as Vec3, up: [0, 1, 0] as Vec3, fovy: 0.5 };

/** A smooth uint8 image (a Gaussian blob). */
function blob(): number[] {
  const d: number[] = [];
  for (let z = 0; z < N; z++)
    for (let y = 0; y < N; y++)
      for (let x = 0; x < N; x++) {
        const q = ((x + 0.5) / N - 0.45) ** 2 + ((y + 0.5) / N - 0.5) ** 2 + ((z + 0.5) / N - 0.55) ** 2;
        d.push(Math.round(255 * Math.exp(-q / 0.05)));
      }
  return d;
}
/** Labels: a ball of id 1, a box of id 3 (id 2 listed in the tables but absent), background 0. */
function organs(): number[] {
  const d: number[] = [];
  for (let z = 0; z < N; z++)
    for (let y = 0; y < N; y++)
      for (let x = 0; x < N; x++) {
        const q = ((x + 0.5) / N - 0.6) ** 2 + ((y + 0.5) / N - 0.45) ** 2 + ((z + 0.5) / N - 0.5) ** 2;
        d.push(q < 0.06 ? 1 : x < 5 && y > 8 && z > 3 && z < 12 ? 3 : 0);
      }
  return d;
}
/** A 3D checkerboard of ids 1 and 3 in 4³ blocks. */
function checkerboard(): number[] {
  const d: number[] = [];
  for (let z = 0; z < N; z++)
    for (let y = 0; y < N; y++) for (let x = 0; x < N; x++) d.push(((x >> 2) + (y >> 2) + (z >> 2)) % 2 ? 3 : 1);
  return d;
}
const BLOB = blob();
const ORGANS = organs();

const IMAGE_TF = tf1d([0.1, [0.9, 0.8, 0.7], 0], [0.6, [1, 0.9, 0.8], 0.5], [1, [1, 1, 1], 0.9]);
const TABLE: LabelEntry[] = [
  { id: 1, name: 'liver', color: [0.8, 0.2, 0.1], opacity: 1.5, visible: true },
  { id: 2, name: 'never present', color: [0.1, 0.9, 0.1], opacity: 1, visible: true },
  { id: 3, name: 'tumour', color: [0.2, 0.3, 0.9], opacity: 0.8, visible: true },
];

type Image = number[];
interface Spec {
  backend: string;
  renderer: string;
  image: number[];
  labels: number[] | null;
  table: LabelEntry[];
  transferFunction: TransferFunction;
  params?: object;
  iterations: number;
  camera?: typeof CAMERA;
}

async function render(spec: Spec): Promise<Image> {
  return page.run(
    async ({ core, t }, spec, n, camera, w, h) => {
      const volume = core.createVolume([n, n, n], 'uint8', new Uint8Array(spec.image));
      const ctx = await t.context({
        backend: spec.backend as 'webgl2',
        renderer: spec.renderer,
        width: w,
        height: h,
        params: spec.params ?? {},
        sampling: 'exact',
      });
      const scene = t.scene({
        volume,
        camera: spec.camera ?? camera,
        densityScale: 10,
        transferFunction: spec.transferFunction,
        environment: { type: 'constant', radiance: [0.1, 0.12, 0.15] },
      });
      const labels = spec.labels
        ? { volume: core.createVolume([n, n, n], 'uint8', new Uint8Array(spec.labels)), table: spec.table }
        : undefined;
      ctx.setScene({ ...scene, ...(labels ? { labels } : {}) });
      const out = await t.finalHDR(ctx, spec.iterations);
      ctx.dispose();
      return out;
    },
    spec,
    N,
    CAMERA,
    W,
    H,
  );
}

function bitsDiffer(a: Image, b: Image): number {
  const u = new Uint32Array(new Float32Array(a).buffer),
    v = new Uint32Array(new Float32Array(b).buffer);
  let n = 0;
  for (let i = 0; i < u.length; i++) if (u[i] !== v[i]) n++;
  return u.length === v.length ? n : -1;
}
function maxAbsDiff(a: ArrayLike<number>, b: ArrayLike<number>): number {
  let m = 0;
  for (let i = 0; i < a.length; i++) m = Math.max(m, Math.abs(a[i] - b[i]));
  return m;
}

const cpuScene = { camera: CAMERA, seed: 1 } as Scene;
function cpuParts(labels: number[], table: LabelEntry[], tf: TransferFunction) {
  const sampler = new reference.CpuVolumeSampler({ volume: createVolume([N, N, N], 'uint8', new Uint8Array(BLOB)) });
  const lv = { volume: createVolume([N, N, N], 'uint8', new Uint8Array(labels)), table };
  const tex = rasterizeTransferFunction(tf, TF_RESOLUTION);
  const lookup = (v: number) => {
    const x = Math.min(1, Math.max(0, v)) * (TF_RESOLUTION - 1);
    const i0 = Math.floor(x),
      i1 = Math.min(i0 + 1, TF_RESOLUTION - 1);
    return [0, 1, 2, 3].map((c) => tex[4 * i0 + c] + (tex[4 * i1 + c] - tex[4 * i0 + c]) * (x - i0));
  };
  const label = (p: Vec3) => labelEntryOf(lv, labelIdAt(lv.volume, p));
  return { sampler, lookup, label, box: sampler.box };
}

/** CPU EAM of image + labels: σ = opacity_image + opacity_label, colour share-weighted (the kernel's march and RNG). */
function cpuEam(labels: number[], table: LabelEntry[], tf: TransferFunction, iterations: number, step: number) {
  const { sampler, lookup, label, box } = cpuParts(labels, table, tf);
  const bg = [0.1, 0.12, 0.15];
  const out = new Float64Array(4 * W * H);
  for (let y = 0; y < H; y++)
    for (let x = 0; x < W; x++)
      for (let it = 0; it < iterations; it++) {
        const rng = new reference.CpuRng(x, y, it, 1);
        const { origin, dir } = reference.jitteredCameraRay(cpuScene, W, H, x, y, rng);
        const [t0, t1] = reference.intersectBox(origin, dir, box.min, box.max);
        const color = [0, 0, 0];
        let T = 1;
        if (t0 < t1) {
          const offset = rng.next();
          const n = Math.max(1, Math.ceil((t1 - t0) / step));
          const seg = (t1 - t0) / n;
          for (let k = 0; k < n; k++) {
            const s = t0 + (k + offset) * seg;
            const p = [0, 1, 2].map((a) => origin[a] + dir[a] * s) as Vec3;
            const a = lookup(sampler.sample(p));
            const l = label(p);
            const sigma = a[3] + l[3];
            const alpha = 1 - Math.exp(-10 * sigma * seg);
            for (let c = 0; c < 3; c++) {
              const mixed = sigma > 0 ? (a[3] / sigma) * a[c] + (l[3] / sigma) * l[c] : a[c];
              color[c] += T * alpha * mixed;
            }
            T *= 1 - alpha;
          }
        }
        const i = 4 * (x + W * y);
        for (let c = 0; c < 3; c++) out[i + c] += (color[c] + T * bg[c]) / iterations;
        out[i + 3] += (1 - T) / iterations;
      }
  return out;
}

/** CPU MIP with labels: the grey maximum, the most opaque visible label (ties: smaller id) over it with its opacity. */
function cpuMip(labels: number[], table: LabelEntry[], iterations: number, step: number) {
  const { sampler, label, box } = cpuParts(labels, table, IMAGE_TF);
  const lv = createVolume([N, N, N], 'uint8', new Uint8Array(labels));
  const out = new Float64Array(4 * W * H);
  for (let y = 0; y < H; y++)
    for (let x = 0; x < W; x++) {
      const { origin, dir } = reference.cameraRay(cpuScene, W, H, (x + 0.5) / W, (y + 0.5) / H);
      const [t0, t1] = reference.intersectBox(origin, dir, box.min, box.max);
      if (!(t0 < t1)) continue;
      let m = 0,
        la = 0,
        lid = 0;
      for (let it = 0; it < iterations; it++) {
        const rng = new reference.CpuRng(x, y, it, 1);
        const offset = rng.next();
        const n = Math.max(1, Math.ceil((t1 - t0) / step));
        const seg = (t1 - t0) / n;
        for (let k = 0; k < n; k++) {
          const s = t0 + (k + offset) * seg;
          const p = [0, 1, 2].map((a) => origin[a] + dir[a] * s) as Vec3;
          m = Math.max(m, sampler.sample(p));
          const id = labelIdAt(lv, p);
          const a = label(p)[3];
          if (a > la || (a === la && a > 0 && id < lid)) [la, lid] = [a, id];
        }
      }
      const i = 4 * (x + W * y);
      const w = Math.min(1, la);
      const c = labelEntryOf({ volume: lv, table }, lid);
      for (let k = 0; k < 3; k++) out[i + k] = la > 0 ? m + (c[k] - m) * w : m;
      out[i + 3] = la > 0 ? Math.max(1, w) : 1;
    }
  return out;
}

describe('labels are read nearest: a checkerboard of two ids shows only table colours', () => {
  const table: LabelEntry[] = [
    { id: 1, color: [1, 0, 0], opacity: 1 },
    { id: 2, color: [0, 1, 0], opacity: 1 },
    { id: 3, color: [0, 0, 1], opacity: 1 },
  ];
  const oblique = { position: [1.1, 0.8, 1.3] as Vec3, target: [0, 0, 0] as Vec3, up: [0, 1, 0] as Vec3, fovy: 0.6 };
  const zero = new Array(N * N * N).fill(0);
  for (const backend of BACKENDS)
    for (const [renderer, params] of [
      ['mip', {}],
      ['slice', { normal: [0.5, 0.7, 0.3], point: [0.02, 0.01, 0.03], colormap: 'grey', window: [0, 1] }],
    ] as const)
      it(`${renderer} on ${backend}`, async () => {
        const img = await render({
          backend,
          renderer,
          image: zero,
          labels: checkerboard(),
          table,
          transferFunction: IMAGE_TF,
          params,
          iterations: 2,
          camera: oblique,
        });
        const seen = new Set<string>();
        for (let i = 0; i < img.length; i += 4) {
          const rgb = img.slice(i, i + 3).join(',');
          seen.add(rgb);
        }
        // Red (id 1), blue (id 3) and black (background or a miss); an id blended between 1 and 3 would read 2 (green) or a mix.
        for (const c of seen) expect(['1,0,0', '0,0,1', '0,0,0']).toContain(c);
        expect(seen.has('1,0,0') && seen.has('0,0,1')).toBe(true);
      });
});

describe('EAM and MIP with labels against CPU twins, bit-identical across backends', () => {
  it('EAM: image + labels mixture', async () => {
    const step = 1 / N / 1.5;
    const imgs = await Promise.all(
      BACKENDS.map((backend) =>
        render({
          backend,
          renderer: 'eam',
          image: BLOB,
          labels: ORGANS,
          table: TABLE,
          transferFunction: IMAGE_TF,
          params: { stepSize: step, cutoff: 0, sampler: 'pcg' }, // the CPU twin's march offsets are the PCG stream's
          iterations: 3,
        }),
      ),
    );
    const cpu = cpuEam(ORGANS, TABLE, IMAGE_TF, 3, step);
    expect(maxAbsDiff(imgs[0], cpu)).toBeLessThan(2e-4);
    if (imgs.length > 1) expect(bitsDiffer(imgs[0], imgs[1])).toBe(0);
    // The labels change the image (the test can fail): without them the CPU EAM differs.
    const bare = cpuEam(new Array(N * N * N).fill(0), TABLE, IMAGE_TF, 3, step);
    expect(maxAbsDiff(imgs[0], bare)).toBeGreaterThan(0.05);
  });
  it('EAM: labels alone (image opacity 0) show the organs in their colours', async () => {
    const step = 1 / N / 1.5;
    const clear = tf1d([0, [1, 1, 1], 0], [1, [1, 1, 1], 0]);
    const img = await render({
      backend: 'webgl2',
      renderer: 'eam',
      image: BLOB,
      labels: ORGANS,
      table: TABLE,
      transferFunction: clear,
      params: { stepSize: step, cutoff: 0, sampler: 'pcg' },
      iterations: 2,
    });
    expect(maxAbsDiff(img, cpuEam(ORGANS, TABLE, clear, 2, step))).toBeLessThan(2e-4);
  });
  it('MIP: the label colour over the maximum', async () => {
    const step = 1 / N / 1.5;
    const imgs = await Promise.all(
      BACKENDS.map((backend) =>
        render({
          backend,
          renderer: 'mip',
          image: BLOB,
          labels: ORGANS,
          table: TABLE,
          transferFunction: IMAGE_TF,
          params: { stepSize: step },
          iterations: 3,
        }),
      ),
    );
    expect(maxAbsDiff(imgs[0], cpuMip(ORGANS, TABLE, 3, step))).toBeLessThan(2e-4);
    if (imgs.length > 1) expect(bitsDiffer(imgs[0], imgs[1])).toBe(0);
  });
});

describe('a hidden label renders as if absent (bit for bit)', () => {
  const hidden = TABLE.map((e) => (e.id === 3 ? { ...e, visible: false } : e));
  const without = ORGANS.map((id) => (id === 3 ? 0 : id));
  for (const renderer of ['eam', 'mip', 'mcrt', 'slice'])
    it(renderer, async () => {
      const params =
        renderer === 'slice'
          ? { axis: 'x', index: 2, colormap: 'grey' }
          : renderer === 'mcrt'
            ? { majorantCellSize: 4 }
            : {};
      const spec = {
        backend: 'webgl2',
        renderer,
        image: BLOB,
        transferFunction: IMAGE_TF,
        params,
        iterations: renderer === 'mcrt' ? 4 : 2,
      };
      const a = await render({ ...spec, labels: ORGANS, table: hidden });
      const b = await render({ ...spec, labels: without, table: TABLE });
      const c = await render({ ...spec, labels: ORGANS, table: TABLE });
      expect(bitsDiffer(a, b)).toBe(0);
      // Counter-check: shown, the label changes the image.
      expect(bitsDiffer(a, c)).toBeGreaterThan(0);
    });
});

describe('MCRT: image + labels are one mixture (z-test against a scalar volume holding it)', () => {
  const MW = 20,
    MH = 16,
    MN = 64;
  const c1: [number, number, number] = [0.9, 0.4, 0.3],
    c2: [number, number, number] = [0.3, 0.6, 0.9];
  // Slabs along z: ids 1 (z < 7) and 2; the scalar twin holds 0.25 / 0.75 with a TF step at 0.5 (the
  // trilinear value crosses 0.5 on the slab face, where the nearest id changes).
  const ids = Array.from({ length: N * N * N }, (_, i) => (Math.floor(i / (N * N)) < 7 ? 1 : 2));
  const values = ids.map((id) => (id === 1 ? 64 : 191));
  const step = tf1d([0.25, c1, 0.6], [0.498, c1, 0.6], [0.502, c2, 1.4], [0.75, c2, 1.4]);
  async function mcrt(
    image: number[],
    tf: TransferFunction,
    labels: number[] | null,
    table: LabelEntry[],
    seed: number,
  ) {
    return page.run(
      async ({ core, mt, t }, image, tf, labels, table, seed, n, camera, w, h, iterations) => {
        const volume = core.createVolume([n, n, n], 'uint8', new Uint8Array(image));
        const scene = {
          ...t.scene({
            volume,
            camera,
            transferFunction: tf,
            environment: { type: 'constant', radiance: [0.4, 0.5, 0.7] },
            densityScale: 6,
            seed,
          }),
          lights: [
            { type: 'directional' as const, direction: [-0.5, 1, 0.4] as Vec3, irradiance: [2, 1.8, 1.5] as Vec3 },
          ],
          ...(labels
            ? { labels: { volume: core.createVolume([n, n, n], 'uint8', new Uint8Array(labels)), table } }
            : {}),
        };
        const r = await mt.run({
          backend: 'webgl2',
          width: w,
          height: h,
          iterations,
          scene,
          params: { majorantCellSize: 4 },
        });
        return { mean: r.mean!, se: r.se!, nonFinite: r.nonFinite };
      },
      image,
      tf,
      labels,
      table,
      seed,
      N,
      CAMERA,
      MW,
      MH,
      MN,
    );
  }
  function z(a: { mean: number[]; se: number[] }, b: { mean: number[]; se: number[] }) {
    const out: number[] = [];
    for (let i = 0; i < a.mean.length; i += 4)
      for (let c = 0; c < 3; c++) {
        const se = Math.hypot(a.se[i + c], b.se[i + c]);
        if (se === 0 && a.mean[i + c] === b.mean[i + c]) continue;
        out.push((a.mean[i + c] - b.mean[i + c]) / se);
      }
    return zSummary(out, 3);
  }
  it('label opacity over a transparent image = a scalar volume of the same extinction and albedo', async () => {
    const clear = tf1d([0, [1, 1, 1], 0], [1, [1, 1, 1], 0]);
    const table: LabelEntry[] = [
      { id: 1, color: c1, opacity: 0.6 },
      { id: 2, color: c2, opacity: 1.4 },
    ];
    const labelled = await mcrt(values, clear, ids, table, 3);
    const scalar = await mcrt(values, step, null, [], 4);
    // Counter-test: the second label's opacity halved is a different medium.
    const other = await mcrt(values, clear, ids, [table[0], { ...table[1], opacity: 0.7 }], 5);
    expect(labelled.nonFinite || scalar.nonFinite).toBe(false);
    const s = z(labelled, scalar),
      s0 = z(other, scalar);
    const msg = `labels vs scalar ${JSON.stringify(s)}; other vs scalar ${JSON.stringify(s0)}`;
    expect(Math.abs(s.meanScaled), msg).toBeLessThan(4);
    expect(s.maxAbs, msg).toBeLessThan(5.5);
    expect(s.n, msg).toBeGreaterThan(300);
    expect(Math.abs(s0.meanScaled), msg).toBeGreaterThan(8);
  });
});

describe('label errors are typed and name the field', () => {
  const cases: [string, string, RegExp][] = [
    ['dims', 'dims', /labels\.volume\.dims \[8, 16, 16\] differ/],
    ['type', 'type', /labels\.volume\.type must be "uint8" or "uint16"/],
    ['id', 'id', /labels\.table\[0\]\.id must be an integer in \[1, 255\]/],
    ['color', 'color', /labels\.table\[0\]\.color\[1\]/],
    ['duplicate', 'duplicate', /labels\.table\[1\]\.id 1 is listed twice/],
  ];
  for (const [name, kind, re] of cases)
    it(name, async () => {
      const r = await page.run(
        async ({ core, t }, kind, n) => {
          const volume = core.createVolume([n, n, n], 'uint8', new Uint8Array(n * n * n));
          const ctx = await t.context({ backend: 'webgl2', renderer: 'eam', width: 8, height: 8 });
          const dims: [number, number, number] = kind === 'dims' ? [8, n, n] : [n, n, n];
          const lv =
            kind === 'type'
              ? core.createVolume(dims, 'float32', new Float32Array(dims[0] * dims[1] * dims[2]))
              : core.createVolume(dims, 'uint8', new Uint8Array(dims[0] * dims[1] * dims[2]));
          const table =
            kind === 'id'
              ? [{ id: 300, color: [1, 0, 0] }]
              : kind === 'color'
                ? [{ id: 1, color: [1, 2, 0] }]
                : kind === 'duplicate'
                  ? [
                      { id: 1, color: [1, 0, 0] },
                      { id: 1, color: [0, 1, 0] },
                    ]
                  : [{ id: 1, color: [1, 0, 0] }];
          try {
            ctx.setScene({ ...t.scene({ volume }), labels: { volume: lv, table } } as never);
            return { code: 'none', message: '' };
          } catch (e) {
            return { code: (e as { code?: string }).code ?? 'untyped', message: String((e as Error).message) };
          } finally {
            ctx.dispose();
          }
        },
        kind,
        N,
      );
      expect(r.code).toBe('invalid-scene');
      expect(r.message).toMatch(re);
    });
});

describe('ISO: the surface between the visible labels and the rest', () => {
  // A ball of id 1 (colour c): its surface is the 0.5 level of the trilinear mask, so it is the
  // isosurface at 0.5 of a float volume holding the same binary mask, bit for bit.
  const c: [number, number, number] = [0.9, 0.5, 0.2];
  const ball = ORGANS.map((id) => (id === 1 ? 1 : 0));
  async function iso(backend: string, withLabels: boolean, surfaceOpacity: number, visible = true) {
    return page.run(
      async ({ core, t }, ball, n, camera, w, h, backend, withLabels, surfaceOpacity, visible, c) => {
        const volume = core.createVolume([n, n, n], 'float32', new Float32Array(ball));
        volume.valueRange = [0, 1];
        const ctx = await t.context({
          backend: backend as 'webgl2',
          renderer: 'iso',
          width: w,
          height: h,
          params: { surfaces: [{ value: 0.5, color: c, opacity: surfaceOpacity }], jitter: false },
          sampling: 'exact',
        });
        const scene = {
          ...t.scene({ volume, camera, environment: { type: 'constant', radiance: [0.3, 0.35, 0.4] } }),
          lights: [
            { type: 'directional' as const, direction: [-0.5, 1, 0.4] as Vec3, irradiance: [2, 1.8, 1.5] as Vec3 },
          ],
          ...(withLabels
            ? {
                labels: {
                  volume: core.createVolume([n, n, n], 'uint8', Uint8Array.from(ball)),
                  table: [{ id: 1, color: c, opacity: 1, visible }],
                },
              }
            : {}),
        };
        ctx.setScene(scene);
        const out = await t.finalHDR(ctx, 3);
        ctx.dispose();
        return out;
      },
      ball,
      N,
      CAMERA,
      W,
      H,
      backend,
      withLabels,
      surfaceOpacity,
      visible,
      c,
    );
  }
  it('= the 0.5 isosurface of the mask as a scalar volume; hidden = absent; WebGL 2 = WebGPU', async () => {
    // The image's own surface at opacity 0 is never drawn: only the label surface shows.
    const labelled = await iso('webgl2', true, 0);
    const scalar = await iso('webgl2', false, 1);
    const hidden = await iso('webgl2', true, 0, false);
    const none = await iso('webgl2', false, 0);
    expect(bitsDiffer(labelled, scalar)).toBe(0);
    expect(bitsDiffer(hidden, none)).toBe(0);
    // Counter-check: the label surface is there (it differs from nothing drawn).
    expect(bitsDiffer(labelled, none)).toBeGreaterThan(20);
    if (BACKENDS.includes('webgpu')) expect(bitsDiffer(await iso('webgpu', true, 0), labelled)).toBe(0);
  });
});

describe('labels on the slice plane, the fast path, and a scene without labels afterwards', () => {
  const table: LabelEntry[] = [
    { id: 1, color: [1, 0, 0], opacity: 1 },
    { id: 3, color: [0, 0, 1], opacity: 1 },
  ];
  it('MIP with a slice plane: the plane shows the label colours (a hidden label shows the grey slice)', async () => {
    const run = (tbl: LabelEntry[], plane: boolean) =>
      page.run(
        async ({ core, t }, ids, n, camera, w, h, tbl, plane) => {
          const volume = core.createVolume([n, n, n], 'uint8', new Uint8Array(n * n * n));
          const ctx = await t.context({ backend: 'webgl2', renderer: 'mip', width: w, height: h, sampling: 'exact' });
          ctx.setScene({
            ...t.scene({ volume, camera }),
            labels: { volume: core.createVolume([n, n, n], 'uint8', Uint8Array.from(ids)), table: tbl },
            ...(plane ? { slicePlane: { axis: 'z' as const, index: 8, sampling: 'nearest' as const } } : {}),
          });
          const out = await t.finalHDR(ctx, 2);
          ctx.dispose();
          return out;
        },
        checkerboard(),
        N,
        CAMERA,
        W,
        H,
        tbl,
        plane,
      );
    const shown = await run(table, true);
    const hidden = await run([table[0], { ...table[1], visible: false }], true);
    const noPlane = await run(table, false);
    const colours = (img: Image) => {
      const s = new Set<string>();
      for (let i = 0; i < img.length; i += 4) s.add(img.slice(i, i + 3).join(','));
      return s;
    };
    // The empty image's slice is black (window over its zero range): every pixel is a table colour or black.
    for (const c of colours(shown)) expect(['1,0,0', '0,0,1', '0,0,0']).toContain(c);
    expect(colours(shown).has('0,0,1')).toBe(true);
    expect(colours(hidden).has('0,0,1')).toBe(false);
    // The plane is drawn: it ends the rays, so the image differs from the plane-less one.
    expect(bitsDiffer(shown, noPlane)).toBeGreaterThan(10);
  });

  it('EAM on the fast path (hardware filter) draws labels as the exact path does (within 0.02)', async () => {
    const step = 1 / N / 1.5;
    const spec = {
      backend: 'webgl2',
      renderer: 'eam',
      image: BLOB,
      labels: ORGANS,
      table: TABLE,
      transferFunction: IMAGE_TF,
      params: { stepSize: step, cutoff: 0 },
      iterations: 2,
    };
    const exact = await render(spec);
    const fast = await page.run(
      async ({ core, t }, spec, n, camera, w, h) => {
        const ctx = await t.context({ backend: 'webgl2', renderer: 'eam', width: w, height: h, params: spec.params });
        ctx.setScene({
          ...t.scene({
            volume: core.createVolume([n, n, n], 'uint8', new Uint8Array(spec.image)),
            camera,
            densityScale: 10,
            transferFunction: spec.transferFunction,
            environment: { type: 'constant', radiance: [0.1, 0.12, 0.15] },
          }),
          labels: { volume: core.createVolume([n, n, n], 'uint8', new Uint8Array(spec.labels)), table: spec.table },
        });
        const out = await t.finalHDR(ctx, spec.iterations);
        ctx.dispose();
        return out;
      },
      spec,
      N,
      CAMERA,
      W,
      H,
    );
    expect(maxAbsDiff(fast, exact)).toBeLessThan(0.02);
    expect(maxAbsDiff(fast, cpuEam(new Array(N * N * N).fill(0), TABLE, IMAGE_TF, 2, step))).toBeGreaterThan(0.05);
  });

  for (const renderer of ['eam', 'mip', 'mcrt', 'iso'])
    it(`${renderer}: the same bits before and after a render with labels, on one context`, async () => {
      const r = await page.run(
        async ({ core, t }, renderer, image, labels, table, n, camera, w, h) => {
          const ctx = await t.context({ backend: 'webgl2', renderer, width: w, height: h, sampling: 'exact' });
          const scene = t.scene({ volume: core.createVolume([n, n, n], 'uint8', new Uint8Array(image)), camera });
          const read = async (s: object) => {
            ctx.setScene(s as never);
            await ctx.renderIterations(2);
            return Array.from(await ctx.readHDR()) as number[];
          };
          const before = await read(scene);
          const withLabels = await read({
            ...scene,
            labels: { volume: core.createVolume([n, n, n], 'uint8', new Uint8Array(labels)), table },
          });
          const after = await read(scene);
          ctx.dispose();
          return { before, withLabels, after };
        },
        renderer,
        BLOB,
        ORGANS,
        TABLE,
        N,
        CAMERA,
        W,
        H,
      );
      expect(bitsDiffer(r.before, r.after)).toBe(0);
      expect(bitsDiffer(r.before, r.withLabels)).toBeGreaterThan(0);
    });
});

describe('labels in the memory budget: counted beside the image and downsampled with it by majority vote', () => {
  // A budget where the image fits alone but not with its labels: the context downsamples both
  // by the same factors (labels by majority vote) and renders what a scene holding those two
  // downsampled volumes renders with room to spare, bit for bit.
  for (const backend of BACKENDS)
    for (const renderer of ['eam', 'mcrt'])
      it(`${renderer} on ${backend}`, async () => {
        const over = await page.run(
          async ({ core, t }, backend, renderer, image, labels, table, n, camera, w, h) => {
            const spec = { backend: backend as 'webgl2', renderer, width: w, height: h, sampling: 'exact' as const };
            const scene = t.scene({
              volume: core.createVolume([n, n, n], 'uint8', new Uint8Array(image)),
              camera,
              densityScale: 10,
              environment: { type: 'constant', radiance: [0.1, 0.12, 0.15] },
            });
            // The image's bytes and the render targets' share, read off a context with room.
            const roomy = await t.context({ ...spec, maxGpuBytes: 1 << 28 });
            roomy.setScene(scene);
            await roomy.renderIterations(1);
            const imageBytes = roomy.stats.gpuBytes.volume;
            const overhead = (1 << 28) - roomy.volumeBudgetBytes;
            roomy.dispose();
            // Room for the image and half the labels' n³ bytes.
            const budget = overhead + imageBytes + Math.floor(n ** 3 / 2);
            const ctx = await t.context({ ...spec, maxGpuBytes: budget });
            const warnings: { code: string; factors: number[]; message: string }[] = [];
            ctx.onWarning((w: never) => warnings.push(w));
            const lv = core.createVolume([n, n, n], 'uint8', new Uint8Array(labels));
            ctx.setScene({ ...scene, labels: { volume: lv, table } });
            await ctx.renderIterations(2);
            const hdr = Array.from(await ctx.readHDR()) as number[];
            const fitted = ctx.getScene()!;
            const out = {
              hdr,
              warnings,
              imageBytes,
              imageDims: fitted.volume.dims,
              labelDims: fitted.labels!.volume.dims,
              total: ctx.stats.gpuBytes.total,
              budget,
            };
            ctx.dispose();
            return out;
          },
          backend,
          renderer,
          BLOB,
          ORGANS,
          TABLE,
          N,
          CAMERA,
          W,
          H,
        );
        expect(over.warnings).toHaveLength(1);
        expect(over.warnings[0].code).toBe('volume-downsampled');
        expect(over.warnings[0].message).toMatch(/label volume/);
        const factors = over.warnings[0].factors as [number, number, number];
        expect(factors.some((f) => f > 1)).toBe(true);
        expect(over.labelDims).toEqual(over.imageDims);
        expect(over.total).toBeLessThanOrEqual(over.budget);
        // The reference: both volumes downsampled here, rendered with room to spare.
        const image = downsampleVolume(createVolume([N, N, N], 'uint8', new Uint8Array(BLOB)), factors);
        const labels = downsampleLabels(createVolume([N, N, N], 'uint8', new Uint8Array(ORGANS)), factors);
        const ref = await page.run(
          async ({ core, t }, backend, renderer, image, labels, dims, spacing, table, camera, w, h) => {
            const ctx = await t.context({
              backend: backend as 'webgl2',
              renderer,
              width: w,
              height: h,
              sampling: 'exact',
            });
            const volume = core.createVolume(dims, 'uint8', new Uint8Array(image), spacing);
            const scene = t.scene({
              volume,
              camera,
              densityScale: 10,
              environment: { type: 'constant', radiance: [0.1, 0.12, 0.15] },
            });
            const lv = core.createVolume(dims, 'uint8', new Uint8Array(labels), spacing);
            ctx.setScene({ ...scene, labels: { volume: lv, table } });
            const hdr = await t.finalHDR(ctx, 2);
            const plain = await t.context({
              backend: backend as 'webgl2',
              renderer,
              width: w,
              height: h,
              sampling: 'exact',
            });
            plain.setScene(scene);
            return { hdr, without: await t.finalHDR(plain, 2) };
          },
          backend,
          renderer,
          Array.from(image.data),
          Array.from(labels.data),
          image.dims,
          image.spacing,
          TABLE,
          CAMERA,
          W,
          H,
        );
        expect(bitsDiffer(over.hdr, ref.hdr)).toBe(0);
        // Counter-check: the labels show in it (the image without them differs).
        expect(bitsDiffer(over.hdr, ref.without)).toBeGreaterThan(0);
      });
});
