import { describe, expect, it } from 'vitest';
import { testScene } from '../../../tests/helpers/test-scene.js';
import {
  createProceduralVolume,
  createVolume,
  rasterizeTransferFunction,
  TF_RESOLUTION,
  type Environment,
  type Scene,
} from '@vpt/core';
import {
  buildMajorantGrid,
  chooseEstimator,
  chooseLightSamples,
  DELTA_MINORANT_DEPTH,
  RESIDUAL_MINORANT_FRACTION,
  computeFeatures,
  environmentPeakRatio,
  ENV_PEAK_RATIO_FOR_MIS,
  GRID_GAIN_FOR_WALK,
  gridCells,
  gridStatistics,
  McrtRenderer,
  PHASE_PEAK_FOR_LIGHT_ONLY,
  phasePeakRatio,
  SINGLE_SCATTERING_LIGHT_SAMPLES,
  volumeCellRanges,
} from '../src/index.js';

/** A lat-long sky of W × H texels: `base` everywhere, `sun` in one texel near the zenith. */
function skyMap(base: number, sun: number, W = 32, H = 16): Environment {
  const data = new Float32Array(W * H * 3).fill(base);
  data.fill(sun, 3 * (W * 2 + 5), 3 * (W * 2 + 6));
  return { type: 'latlong', width: W, height: H, data };
}

/** A sparse blob (most cells empty, minorants a tenth of the majorants; global / mean cell majorant 4.3 with 8-voxel cells). */
const sparse = (over: Partial<Scene> = {}) =>
  testScene({ volume: createProceduralVolume('blob', 64), densityScale: 20, ...over });

/** A homogeneous cube: every cell's bounds equal. */
const homogeneous = (over: Partial<Scene> = {}) =>
  testScene({
    volume: createProceduralVolume('cube', 16),
    transferFunction: { dimensions: '1d', points: [{ value: 0, color: [0.8, 0.8, 0.8], opacity: 1 }] },
    densityScale: 5,
    ...over,
  });

/** An n³ float32 volume of values in [0, 1] under a grey TF whose opacity is the value, density 30. */
function opacityIsValueScene(n: number, data: Float32Array, over: Partial<Scene>): Scene {
  const volume = createVolume([n, n, n], 'float32', data);
  volume.valueRange = [0, 1];
  return testScene({
    volume,
    transferFunction: {
      dimensions: '1d',
      points: [
        { value: 0, color: [0.9, 0.9, 0.9], opacity: 0 },
        { value: 1, color: [0.9, 0.9, 0.9], opacity: 1 },
      ],
    },
    densityScale: 30,
    ...over,
  });
}

/** A dense medium that varies slowly (value 0.6–1 as a linear ramp along x) under a TF whose opacity never drops below 0.6. */
function denseRamp(over: Partial<Scene> = {}): Scene {
  const n = 32;
  const data = new Float32Array(n * n * n);
  for (let z = 0; z < n; z++)
    for (let y = 0; y < n; y++) for (let x = 0; x < n; x++) data[x + n * (y + n * z)] = 0.6 + (0.4 * x) / (n - 1);
  return opacityIsValueScene(n, data, over);
}

/** A dense, heterogeneous medium (as the benchmark cloud): per-voxel noise in [0.2, 1], opacity = value; a flat grid (global/mean majorant ≈ 1). */
function denseNoise(over: Partial<Scene> = {}): Scene {
  const n = 32;
  const data = new Float32Array(n * n * n);
  let h = 12345;
  for (let i = 0; i < data.length; i++) {
    h = (Math.imul(h, 1664525) + 1013904223) >>> 0;
    data[i] = 0.2 + 0.8 * (h / 4294967296);
  }
  return opacityIsValueScene(n, data, over);
}

const open = () => gridStatistics(sparse(), 8);

describe("MCRT estimator: 'auto' rules", () => {
  it('a constant environment is sampled by the phase function alone, with or without lights', () => {
    for (const lights of [
      [],
      [
        {
          type: 'directional' as const,
          direction: [0, 1, 0] as [number, number, number],
          irradiance: [3, 3, 3] as [number, number, number],
        },
      ],
    ]) {
      const c = chooseEstimator(sparse({ lights }), {}, open);
      expect(c.environmentSampling).toBe('phase');
      expect(c.reasons.environmentSampling).toBe('constant environment');
    }
  });

  it('a map gets MIS, even a smooth one; a map of one value is a constant sky', () => {
    const sun = skyMap(0.2, 2000);
    expect(environmentPeakRatio(sun)).toBeGreaterThan(ENV_PEAK_RATIO_FOR_MIS);
    const withSun = chooseEstimator(sparse({ environment: sun }), {}, open);
    // Shadow rays at every event, tracked by the multiple-scattering rule: ratio (minorants 0), residual where they are ≥ half.
    expect([withSun.environmentSampling, withSun.tracking]).toEqual(['mis', 'ratio']);
    expect(chooseEstimator(denseRamp({ environment: sun }), {}, () => gridStatistics(denseRamp(), 8)).tracking).toBe(
      'residual',
    );
    // The anchor sky of the VPT comparison: 0.05 at the nadir to 1 at the zenith, peak/mean ≈ 2.7.
    const H = 64,
      W = 4;
    const data = new Float32Array(W * H * 3);
    for (let j = 0; j < H; j++)
      data.fill(0.05 + 0.95 * ((1 + Math.cos((Math.PI * (j + 0.5)) / H)) / 2) ** 2, 3 * W * j, 3 * W * (j + 1));
    const smooth: Environment = { type: 'latlong', width: W, height: H, data };
    expect(environmentPeakRatio(smooth)).toBeCloseTo(1 / (0.05 + 0.95 / 3), 1);
    expect(chooseEstimator(sparse({ environment: smooth }), {}, open).environmentSampling).toBe('mis');
    const flat = skyMap(0.7, 0.7);
    expect(environmentPeakRatio(flat)).toBeCloseTo(1, 6);
    expect(chooseEstimator(sparse({ environment: flat }), {}, open).environmentSampling).toBe('phase');
    expect(environmentPeakRatio({ type: 'constant', radiance: [0.3, 0.3, 0.3] })).toBe(1);
  });

  it('a sparse volume walks the grid, and its shadow rays take ratio tracking (its minorants are small)', () => {
    const scene = sparse();
    const s = gridStatistics(scene, 8);
    expect(s.minorantFraction).toBeLessThan(0.15);
    expect(s.globalMajorant / s.meanMajorant).toBeGreaterThan(GRID_GAIN_FOR_WALK);
    const c = chooseEstimator(scene, {}, () => s);
    expect([c.tracking, c.majorantGrid]).toEqual(['ratio', true]);
  });

  it('multiple scattering: ratio tracking; residual where the minorants are ≥ half; delta in a dense medium under a phase-sampled sky', () => {
    const sun = {
      type: 'directional' as const,
      direction: [0, 1, 0] as [number, number, number],
      irradiance: [3, 3, 3] as [number, number, number],
    };
    const choose = (scene: Scene) => {
      const s = gridStatistics(scene, 8);
      const c = chooseEstimator(scene, {}, () => s);
      expect(c.reasons.tracking).toMatch(/^cell minorants \d+% of majorants, mean minorant \d+\.\d\d per box length/);
      return { c, fraction: s.minorantFraction, depth: s.minorantFraction * s.meanMajorant };
    };
    // Small minorants (empty and thin cells, as in the head and CT scans): ratio.
    const thin = choose(sparse({ lights: [sun] }));
    expect(thin.depth).toBeLessThan(DELTA_MINORANT_DEPTH / 2);
    expect([thin.c.environmentSampling, thin.c.tracking]).toEqual(['phase', 'ratio']);
    // Dense and heterogeneous (minorants a fifth of the majorants, mean minorant ≥ 5 per box length, as in the cloud): delta.
    const dense = choose(denseNoise({ lights: [sun] }));
    expect(dense.fraction).toBeGreaterThan(0.1);
    expect(dense.fraction).toBeLessThan(RESIDUAL_MINORANT_FRACTION);
    expect(dense.depth).toBeGreaterThan(5 * DELTA_MINORANT_DEPTH);
    expect([dense.c.environmentSampling, dense.c.tracking]).toEqual(['phase', 'delta']);
    expect(dense.c.reasons.tracking).toMatch(/shadow rays only toward the lights/);
    // The same medium 20× thinner: its minorants no longer block the shadow rays, so ratio.
    const thinned = choose(denseNoise({ lights: [sun], densityScale: 1.5 }));
    expect(thinned.depth).toBeLessThan(DELTA_MINORANT_DEPTH);
    expect(thinned.c.tracking).toBe('ratio');
    // The dense medium under a map (MIS: shadow rays at every event): ratio.
    const underMap = choose(denseNoise({ environment: skyMap(0.2, 2000) }));
    expect([underMap.c.environmentSampling, underMap.c.tracking]).toEqual(['mis', 'ratio']);
    // Dense but slowly varying (minorants ≥ half the majorants): residual, the control takes most in closed form.
    const ramp = choose(denseRamp({ lights: [sun] }));
    expect(ramp.depth).toBeGreaterThan(DELTA_MINORANT_DEPTH);
    expect(ramp.fraction).toBeGreaterThanOrEqual(RESIDUAL_MINORANT_FRACTION);
    expect(ramp.c.tracking).toBe('residual');
    // Without the grid the control is the global minorant: 0 in the sparse blob (ratio).
    expect(chooseEstimator(sparse({ lights: [sun] }), { majorantGrid: false }, open).tracking).toBe('ratio');
  });

  it('single scattering takes residual (ratio) tracking for its shadow rays, whatever the minorants', () => {
    const c = chooseEstimator(sparse(), { singleScattering: true }, open);
    expect(c.tracking).toBe('residual');
    expect(c.reasons.tracking).toMatch(/single scattering/);
    expect(new McrtRenderer({ scattering: 'single' }).features(sparse()).TRACKING).toBe(2);
  });

  it('a volume whose grid lowers the bound less than GRID_GAIN_FOR_WALK× takes the global majorant (the same blob, 32³)', () => {
    const filled = testScene({ volume: createProceduralVolume('blob', 32), densityScale: 20 });
    const s = gridStatistics(filled, 8);
    expect(s.globalMajorant / s.meanMajorant).toBeGreaterThan(1.5); // the previous threshold walked it
    expect(s.globalMajorant / s.meanMajorant).toBeLessThan(GRID_GAIN_FOR_WALK);
    const c = chooseEstimator(filled, {}, () => s);
    expect(c.majorantGrid).toBe(false);
    expect(c.reasons.majorantGrid).toMatch(/global\/mean cell majorant \d\.\d\d < 3/);
  });

  it('a homogeneous volume takes the global majorant and residual tracking (the control is the whole extinction)', () => {
    const c = chooseEstimator(homogeneous(), {}, () => gridStatistics(homogeneous(), 8));
    expect([c.tracking, c.majorantGrid]).toEqual(['residual', false]);
  });

  it('a dense, slowly varying volume keeps the grid and takes residual tracking', () => {
    const scene = denseRamp();
    const s = gridStatistics(scene, 8);
    expect(s.minorantFraction).toBeGreaterThan(0.7);
    const c = chooseEstimator(scene, {}, () => s);
    expect(c.tracking).toBe('residual');
  });

  it('what a parameter sets is kept, and the statistics are not computed when nothing is left to choose', () => {
    let computed = 0;
    const c = chooseEstimator(
      sparse(),
      { tracking: 'ratio', environmentSampling: 'light', majorantGrid: false, lightSamples: 3, singleScattering: true },
      () => (computed++, open()),
    );
    expect([c.tracking, c.environmentSampling, c.majorantGrid, c.lightSamples, computed]).toEqual([
      'ratio',
      'light',
      false,
      3,
      0,
    ]);
    expect(c.reasons).toEqual({
      tracking: 'set',
      environmentSampling: 'set',
      majorantGrid: 'set',
      lightSamples: 'set',
    });
  });

  it('the subsampled statistics of a small volume are those of the full CPU grid', () => {
    const scene = sparse();
    const full = buildMajorantGrid(
      volumeCellRanges(scene.volume, 8),
      rasterizeTransferFunction(scene.transferFunction, TF_RESOLUTION),
      scene.densityScale,
    );
    const s = gridStatistics(scene, 8);
    expect(gridCells(scene.volume.dims, 8)).toEqual(full.cells);
    expect(s.globalMajorant).toBe(full.globalMajorant);
    let sum = 0;
    for (let c = 0; c < full.data.length; c += 4) sum += full.data[c];
    expect(s.meanMajorant).toBeCloseTo(sum / (full.data.length / 4), 5);
  });
});

describe('McrtRenderer with the auto estimator', () => {
  it('compiles the chosen variant and reports it (and why) in stats()', () => {
    const r = new McrtRenderer();
    const f = r.features(sparse());
    expect([f.TRACKING, f.ENV_SAMPLING, f.MAJORANT_GRID]).toEqual([1, 0, true]);
    const s = r.stats();
    expect(s).toMatchObject({
      estimator: 'auto',
      tracking: 'ratio',
      environmentSampling: 'phase',
      majorantGrid: 'grid',
    });
    expect(s.trackingReason).toMatch(/minorants \d+% of majorants, mean minorant \d+\.\d\d per box length/);
  });

  it("'fixed' keeps the fixed defaults (residual, MIS, grid); 'auto' as a value equals unset", () => {
    const fixed = new McrtRenderer({ estimator: 'fixed' });
    const f = fixed.features(sparse());
    expect([f.TRACKING, f.ENV_SAMPLING, f.MAJORANT_GRID]).toEqual([2, 2, true]);
    expect(fixed.stats().trackingReason).toBeUndefined();
    const auto = new McrtRenderer({ tracking: 'auto', environmentSampling: 'auto' });
    expect(computeFeatures(sparse(), auto.paramsFor(sparse()))).toEqual(new McrtRenderer().features(sparse()));
  });

  it('an override of one choice leaves the others to the rules', () => {
    const r = new McrtRenderer({ tracking: 'delta' });
    const f = r.features(sparse());
    expect([f.TRACKING, f.ENV_SAMPLING]).toEqual([0, 0]);
    expect(r.stats().trackingReason).toBe('set');
  });
});

describe("MCRT estimator 'auto': light samples per scattering event", () => {
  it('single scattering with light sampling alone takes SINGLE_SCATTERING_LIGHT_SAMPLES (> 1); phase or MIS sampling and multiple scattering one; a set value is kept', () => {
    expect(SINGLE_SCATTERING_LIGHT_SAMPLES).toBeGreaterThan(1);
    const map = sparse({ environment: skyMap(0.5, 20) });
    const single = chooseEstimator(map, { singleScattering: true }, open);
    expect([single.environmentSampling, single.lightSamples]).toEqual(['light', SINGLE_SCATTERING_LIGHT_SAMPLES]);
    expect(single.reasons.lightSamples).toMatch(/^single scattering, light sampling/);
    const phase = chooseEstimator(sparse(), { singleScattering: true }, open); // constant sky: phase sampling
    expect([phase.environmentSampling, phase.lightSamples]).toEqual(['phase', 1]);
    expect(phase.reasons.lightSamples).toBe('single scattering, phase sampling: one per event');
    const mis = chooseEstimator(map, { singleScattering: true, anisotropy: 0.6 }, open);
    expect([mis.environmentSampling, mis.lightSamples]).toEqual(['mis', 1]);
    const multiple = chooseEstimator(map, { anisotropy: 0 }, open);
    expect([multiple.lightSamples, multiple.reasons.lightSamples]).toEqual([1, 'multiple scattering: one per event']);
    expect(chooseLightSamples({ singleScattering: true, lightSamples: 1 }, 'light')).toEqual({
      lightSamples: 1,
      reason: 'set',
    });
  });

  it('single scattering under a map samples the environment by light alone while the phase function is near isotropic', () => {
    const map = skyMap(0.5, 20); // peak/mean far above ENV_PEAK_RATIO_FOR_MIS
    expect(phasePeakRatio(0)).toBe(1);
    expect(phasePeakRatio(0.2)).toBeLessThanOrEqual(PHASE_PEAK_FOR_LIGHT_ONLY);
    expect(phasePeakRatio(-0.3)).toBeGreaterThan(PHASE_PEAK_FOR_LIGHT_ONLY);
    const pick = (request: Parameters<typeof chooseEstimator>[1]) =>
      chooseEstimator(sparse({ environment: map }), request, open).environmentSampling;
    expect(pick({ singleScattering: true })).toBe('light');
    expect(pick({ singleScattering: true, anisotropy: 0.2 })).toBe('light');
    expect(pick({ singleScattering: true, anisotropy: -0.3 })).toBe('mis');
    expect(pick({ anisotropy: 0 })).toBe('mis'); // multiple scattering: unchanged
    expect(pick({ singleScattering: true, environmentSampling: 'mis' })).toBe('mis');
    expect(chooseEstimator(sparse(), { singleScattering: true }, open).environmentSampling).toBe('phase');
    const c = chooseEstimator(sparse({ environment: map }), { singleScattering: true }, open);
    expect(c.reasons.environmentSampling).toMatch(/single scattering, phase peak 1\.00× isotropic/);
  });

  it('the renderer compiles the chosen count into the single-scattering kernel and reports it; fixed and multiple take one', () => {
    const mapped = sparse({ environment: skyMap(0.5, 20) });
    const auto = new McrtRenderer({ scattering: 'single' });
    const f = auto.features(mapped);
    expect([f.ENV_SAMPLING, f.LIGHT_SAMPLES]).toEqual([1, SINGLE_SCATTERING_LIGHT_SAMPLES]); // light alone, several samples
    expect(auto.stats()).toMatchObject({
      environmentSampling: 'light',
      lightSamples: String(SINGLE_SCATTERING_LIGHT_SAMPLES),
    });
    expect(auto.stats().lightSamplesReason).toMatch(/^single scattering, light sampling/);
    const anisotropic = new McrtRenderer({ scattering: 'single', anisotropy: 0.5 }).features(mapped);
    expect([anisotropic.ENV_SAMPLING, anisotropic.LIGHT_SAMPLES]).toEqual([2, 1]); // MIS, one sample
    const fixed = new McrtRenderer({ scattering: 'single', estimator: 'fixed' });
    expect([fixed.features(mapped).LIGHT_SAMPLES, fixed.stats().lightSamples]).toEqual([1, '1']);
    const set = new McrtRenderer({ scattering: 'single', lightSamples: 3 });
    expect([set.features(sparse()).LIGHT_SAMPLES, set.stats().lightSamplesReason]).toEqual([3, 'set']);
    expect(new McrtRenderer().features(mapped).LIGHT_SAMPLES).toBe(1);
    expect(() => new McrtRenderer({ lightSamples: 0 })).toThrow(/lightSamples/);
    expect(() => new McrtRenderer({ lightSamples: 1.5 })).toThrow(/lightSamples/);
  });
});
