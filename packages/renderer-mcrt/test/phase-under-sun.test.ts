// Issue 28: `environmentSampling: 'phase'` under a lat-long map with a small sun still had
// fireflies at 512 iterations. Under `estimator: 'auto'` (the default) such a map switches
// to MIS, and the renderer's reported choice says why; a near-uniform map and
// `estimator: 'fixed'` keep phase sampling as set.
import { describe, expect, it } from 'vitest';
import { createProceduralVolume, type Environment } from '@vpt/core';
import { testScene } from '../../../tests/helpers/test-scene.js';
import { ENV_PEAK_RATIO_PHASE_TO_MIS, environmentPeakRatio, McrtRenderer } from '../src/index.js';

/** A lat-long sky of 32 × 16 texels: `base` everywhere, `sun` in one texel near the zenith. */
function skyMap(base: number, sun: number): Environment {
  const W = 32,
    H = 16;
  const data = new Float32Array(W * H * 3).fill(base);
  data.fill(sun, 3 * (W * 2 + 5), 3 * (W * 2 + 6));
  return { type: 'latlong', width: W, height: H, data };
}

const scene = (environment: Environment) =>
  testScene({ volume: createProceduralVolume('blob', 32), densityScale: 20, environment });

describe("environmentSampling 'phase' under a small sun", () => {
  it("switches to MIS under estimator 'auto', with the reason in stats()", () => {
    const sun = skyMap(0.1, 2000);
    expect(environmentPeakRatio(sun)).toBeGreaterThan(ENV_PEAK_RATIO_PHASE_TO_MIS);
    const r = new McrtRenderer({ environmentSampling: 'phase' });
    expect(r.paramsFor(scene(sun)).environmentSampling).toBe('mis');
    expect(r.stats()).toMatchObject({ environmentSampling: 'mis' });
    expect(String(r.stats().environmentSamplingReason)).toMatch(/phase was set, but the map's peak\/mean .* MIS/);
  });

  it("keeps phase for a near-uniform map, a constant environment and estimator 'fixed'", () => {
    const phase = { environmentSampling: 'phase' } as const;
    expect(new McrtRenderer(phase).paramsFor(scene(skyMap(1, 2))).environmentSampling).toBe('phase');
    const constant: Environment = { type: 'constant', radiance: [1, 1, 1] };
    expect(new McrtRenderer(phase).paramsFor(scene(constant)).environmentSampling).toBe('phase');
    const fixed = new McrtRenderer({ ...phase, estimator: 'fixed' });
    expect(fixed.paramsFor(scene(skyMap(0.1, 2000))).environmentSampling).toBe('phase');
  });
});
