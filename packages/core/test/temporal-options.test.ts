import { describe, expect, it } from 'vitest';
import { VptError, createProceduralVolume, defaultCamera, rampTransferFunction, type Scene } from '../src/index.js';
import {
  TEMPORAL_DEFAULTS,
  checkTemporalOptions,
  sameSceneButCamera,
  viewChange,
} from '../src/context/temporal-reuse.js';

describe('temporal reuse options', () => {
  it('fills in the defaults and refuses bad values naming the field', () => {
    expect(checkTemporalOptions(undefined)).toBeNull();
    expect(checkTemporalOptions(false)).toBeNull();
    expect(checkTemporalOptions(true)).toEqual(TEMPORAL_DEFAULTS);
    expect(checkTemporalOptions({ maxHistory: 4 })).toEqual({ ...TEMPORAL_DEFAULTS, maxHistory: 4 });
    expect(checkTemporalOptions({ historyFilter: 'bilinear' })).toEqual({
      ...TEMPORAL_DEFAULTS,
      historyFilter: 'bilinear',
    });
    for (const [bad, field] of [
      [{ maxHistory: -1 }, 'temporal.maxHistory'],
      [{ depthTolerance: NaN }, 'temporal.depthTolerance'],
      [{ normalCos: 2 }, 'temporal.normalCos'],
      [{ fadeSamples: 1.5 }, 'temporal.fadeSamples'],
      [{ viewDecay: 0 }, 'temporal.viewDecay'],
      [{ historyFilter: 'bicubic' }, 'temporal.historyFilter'],
      [{ history: 3 }, 'history'],
      ['on', 'temporal'],
    ] as const) {
      let err: unknown;
      try {
        checkTemporalOptions(bad);
      } catch (e) {
        err = e;
      }
      expect(err).toBeInstanceOf(VptError);
      expect((err as VptError).code).toBe('invalid-scene');
      expect((err as Error).message).toContain(field);
    }
  });

  it('measures the view change: 0 at rest, about 2φ for an orbit by φ', () => {
    const c = defaultCamera();
    expect(viewChange(c, c)).toBe(0);
    const phi = 0.1,
      r = 2;
    const orbited = { ...c, position: [r * Math.sin(phi), 0, r * Math.cos(phi)] as [number, number, number] };
    expect(viewChange(c, orbited)).toBeCloseTo(phi + 2 * Math.sin(phi / 2), 10);
  });

  it('tells a camera change from any other change', () => {
    const volume = createProceduralVolume('sphere', 8);
    const scene = (): Scene => ({
      volume,
      transferFunction: rampTransferFunction(),
      camera: defaultCamera(),
      lights: [],
      environment: { type: 'constant', radiance: [0, 0, 0] },
      densityScale: 1,
      seed: 1,
    });
    const a = scene();
    expect(sameSceneButCamera(a, { ...scene(), camera: { ...a.camera, position: [1, 0, 2] } })).toBe(true);
    expect(sameSceneButCamera(a, { ...scene(), seed: 2 })).toBe(false);
    expect(sameSceneButCamera(a, { ...scene(), densityScale: 2 })).toBe(false);
    expect(sameSceneButCamera(a, { ...scene(), environment: { type: 'constant', radiance: [0, 0, 1] } })).toBe(false);
    expect(sameSceneButCamera(a, { ...scene(), volume: createProceduralVolume('sphere', 8) })).toBe(false);
    expect(sameSceneButCamera(a, { ...scene(), clip: { planes: [{ normal: [1, 0, 0], offset: 0 }] } })).toBe(false);
  });
});
