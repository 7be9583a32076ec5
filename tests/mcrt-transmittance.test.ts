import { describe, expect, it } from 'vitest';
import { tf1d } from './helpers/test-scene.js';
import { createProceduralVolume, type Scene, type Vec3 } from '../packages/core/src/index.js';
import { binomialZ, zSummary } from './helpers/mcrt-stats.js';
import { opticalDepth, pixelExpectations } from './helpers/mcrt-reference.js';
import { BACKENDS, usePage } from './helpers/session.js';

/**
 * Transmittance. With albedo 0 a path ends at its first real collision, so the image is the
 * environment times the probability of crossing the box: exp(−σ·chord) for a homogeneous cube.
 * The shadow-ray estimators (delta, ratio, residual ratio tracking, with and without the
 * majorant grid) are checked through the renderer's debug output, which returns that
 * estimator along each camera ray, against a fine CPU quadrature of a heterogeneous medium.
 * Tolerances are the standard errors measured from the frames: aggregate bias |Σz|/√n < 3,
 * no pixel beyond 5σ, at most 3 % beyond 3σ.
 */
const page = usePage({ mcrt: true });

const W = 16,
  H = 16,
  N = 64;
// Float32 arithmetic and the 8×8 sub-pixel quadrature of the footprint: an absolute floor under the measured σ.
const FLOOR = 5e-4;

/**
 * z-scores of the interior pixels. `binaryOf` (delta tracking): each sample is 0 or L (the
 * ray got through or not), so the count of L's is binomial(N, p) with p = E/L the pixel's
 * expected transmittance: an exact binomial test, expressed as the equivalent z (the
 * sample variance is 0 when 64 samples happen to agree, likely for p near 0 or 1).
 */
function compare(
  gpu: { mean: number[]; se: number[] },
  expect_: ReturnType<typeof pixelExpectations>,
  channels = 3,
  binaryOf?: Vec3,
) {
  const z: number[] = [];
  let interior = 0;
  expect_.forEach((p, k) => {
    if (!p.interior) return;
    interior++;
    for (let c = 0; c < channels; c++) {
      if (binaryOf) z.push(binomialZ(gpu.mean[4 * k + c] / binaryOf[c], N, p.value[c] / binaryOf[c]));
      else z.push((gpu.mean[4 * k + c] - p.value[c]) / Math.hypot(gpu.se[4 * k + c], FLOOR));
    }
  });
  return { ...zSummary(z, channels), interior };
}

function expectUnbiased(s: ReturnType<typeof compare>, msg: string) {
  expect(s.interior, msg).toBeGreaterThan(60);
  expect(Math.abs(s.meanScaled), msg).toBeLessThan(3);
  expect(s.maxAbs, msg).toBeLessThan(5);
  expect(s.over3 / s.n, msg).toBeLessThan(0.03);
}

const camera = { position: [0.4, 0.5, 2.6] as Vec3, target: [0, 0, 0] as Vec3, up: [0, 1, 0] as Vec3, fovy: 0.7 };

describe.each(BACKENDS)('MCRT homogeneous slab transmittance on %s', (backend) => {
  it.each([0.5, 3])('albedo 0: the image is L_env · exp(−σ·chord), σ = %s', async (sigma) => {
    const env: Vec3 = [0.8, 0.9, 1.0];
    const gpu = await page.run(
      ({ mt }, backend, W, H, N, sigma, camera, env) => {
        return mt.run({
          backend,
          width: W,
          height: H,
          iterations: N,
          scene: mt.cubeScene({
            albedo: [0, 0, 0],
            density: sigma,
            camera,
            environment: { type: 'constant', radiance: env },
          }),
        });
      },
      backend,
      W,
      H,
      N,
      sigma,
      camera,
      env,
    );
    expect(gpu.nonFinite).toBe(false);
    const scene = { volume: createProceduralVolume('cube', 8), camera } as Scene;
    const ref = pixelExpectations(scene, W, H, (_o, _d, t0, t1) => {
      const T = Math.exp(-sigma * Math.max(0, t1 - t0));
      return [env[0] * T, env[1] * T, env[2] * T];
    });
    const s = compare(gpu, ref, 3, env);
    expectUnbiased(s, `σ ${sigma}: ${JSON.stringify(s)}`);
    // Pixels that miss the box show the environment exactly.
    ref.forEach((p, k) => {
      if (p.miss) for (let c = 0; c < 3; c++) expect(gpu.mean[4 * k + c]).toBeCloseTo(env[c], 6);
    });
  });
});

describe('MCRT shadow-ray estimators on a heterogeneous medium (webgl2)', () => {
  // A blob with a transfer function that peaks inside the value range (the majorant grid
  // must bound the peak, not just the cell's end values).
  const tf = tf1d(
    [0, [1, 1, 1], 0],
    [0.3, [1, 1, 1], 0.2],
    [0.55, [1, 1, 1], 1],
    [0.7, [1, 1, 1], 0.1],
    [1, [1, 1, 1], 0.6],
  );
  const hetCamera = { position: [0.6, 0.4, 2.2] as Vec3, target: [0, 0, 0] as Vec3, up: [0, 1, 0] as Vec3, fovy: 0.55 };
  const scene: Scene = {
    volume: createProceduralVolume('blob', 16),
    transferFunction: tf,
    camera: hetCamera,
    lights: [],
    environment: { type: 'constant', radiance: [1, 1, 1] },
    densityScale: 6,
    seed: 2,
  };
  const tau = opticalDepth(scene, 1000);
  const ref = pixelExpectations(scene, W, H, (o, d, t0, t1) => {
    const T = Math.exp(-tau(o, d, t0, t1));
    return [T, T, T];
  });

  it.each([
    ['delta', true],
    ['ratio', true],
    ['residual', true],
    ['delta', false],
    ['ratio', false],
    ['residual', false],
  ] as const)('%s tracking (majorant grid %s) estimates exp(−∫σ_t) without bias', async (tracking, majorantGrid) => {
    const gpu = await page.run(
      ({ core, mt }, W, H, N, scene, tracking, majorantGrid) => {
        return mt.run({
          backend: 'webgl2',
          width: W,
          height: H,
          iterations: N,
          params: { debugOutput: 'transmittance', tracking, majorantGrid, majorantCellSize: 4 },
          scene: { ...scene, volume: core.createProceduralVolume('blob', 16) },
        });
      },
      W,
      H,
      N,
      { ...scene, volume: null },
      tracking,
      majorantGrid,
    );
    expect(gpu.nonFinite).toBe(false);
    const s = compare(gpu, ref, 1, tracking === 'delta' ? [1, 1, 1] : undefined);
    expectUnbiased(s, `${tracking} grid=${majorantGrid}: ${JSON.stringify(s)}`);
    // The medium really attenuates (the test has something to measure).
    const minT = Math.min(...ref.filter((p) => p.interior).map((p) => p.value[0]));
    expect(minT).toBeLessThan(0.5);
  });
});

describe.each(BACKENDS)('MCRT ratio tracking in a dense medium (Russian roulette) on %s', (backend) => {
  // Density 60: most shadow-ray estimates fall below 0.1 and go through the roulette, whose
  // survivors must be rescaled to 0.1 (unbiased: E = P(survive)·0.1 = T). A pixel's estimate
  // is then a sum of draws of 0 or about 0.1, so its sample variance can be 0 when 64 draws
  // agree: the per-pixel σ has a floor of √(E·(0.1 − E)/N), the spread of a 0/0.1 draw with mean E.
  const tf = tf1d([0, [1, 1, 1], 0], [0.3, [1, 1, 1], 0.2], [0.55, [1, 1, 1], 1], [1, [1, 1, 1], 0.6]);
  const DENSE_N = 128; // cheap at 16×16, and it sharpens the aggregate
  const denseCamera = {
    position: [0.6, 0.4, 2.2] as Vec3,
    target: [0, 0, 0] as Vec3,
    up: [0, 1, 0] as Vec3,
    fovy: 0.55,
  };
  // sampling: 'exact': the expectation integrates the CPU twin's exact trilinear field, which at
  // density 60 a hardware filter's coarse weights would shift by more than the z-test allows.
  const scene: Scene = {
    volume: createProceduralVolume('blob', 16),
    transferFunction: tf,
    camera: denseCamera,
    lights: [],
    environment: { type: 'constant', radiance: [1, 1, 1] },
    densityScale: 60,
    seed: 5,
    sampling: 'exact',
  };
  const tau = opticalDepth(scene, 1000);
  const ref = pixelExpectations(scene, W, H, (o, d, t0, t1) => {
    const T = Math.exp(-tau(o, d, t0, t1));
    return [T, T, T];
  });

  it.each(['ratio', 'residual'] as const)(
    '%s tracking (majorant grid) estimates exp(−∫σ_t) without bias where roulette decides',
    async (tracking) => {
      const gpu = await page.run(
        ({ core, mt }, backend, W, H, N, scene, tracking) => {
          return mt.run({
            backend,
            width: W,
            height: H,
            iterations: N,
            params: { debugOutput: 'transmittance', tracking, majorantGrid: true, majorantCellSize: 4 },
            scene: { ...scene, volume: core.createProceduralVolume('blob', 16) },
          });
        },
        backend,
        W,
        H,
        DENSE_N,
        { ...scene, volume: null },
        tracking,
      );
      expect(gpu.nonFinite).toBe(false);
      const z: number[] = [];
      let dense = 0;
      ref.forEach((p, k) => {
        if (!p.interior) return;
        const E = p.value[0];
        if (E < 0.1) dense++;
        const rouletteFloor = Math.sqrt(Math.max(0, E * (0.1 - E)) / DENSE_N);
        z.push((gpu.mean[4 * k] - E) / Math.max(gpu.se[4 * k], rouletteFloor, FLOOR));
      });
      const s = zSummary(z, 1);
      const msg = `${tracking} ${backend}: ${JSON.stringify(s)}, ${dense} pixels below 0.1`;
      expect(dense, msg).toBeGreaterThan(40); // the roulette really decides most pixels
      expect(Math.abs(s.meanScaled), msg).toBeLessThan(3);
      expect(s.maxAbs, msg).toBeLessThan(5);
      expect(s.over3 / s.n, msg).toBeLessThan(0.03);
    },
  );
});
