import { describe, expect, it } from 'vitest';
import { expectVptError, testScene } from '../../../tests/helpers/test-scene.js';
import { createProceduralVolume, isVptError, preprocess, type Scene } from '@vpt/core';
import { IsoRenderer, resolveIsoParams, type IsoParams } from '../src/index.js';

const scene = (overrides: Partial<Scene> = {}): Scene =>
  testScene({ volume: createProceduralVolume('sphere', 8), ...overrides });

function expectInvalid(p: IsoParams, pattern: RegExp): void {
  expectVptError(() => resolveIsoParams(p), 'invalid-scene', pattern);
}

describe('IsoRenderer parameters', () => {
  it('rejects bad values with errors that name them', () => {
    expectInvalid({ surfaces: [] }, /surfaces must be an array of 1 to 4/);
    expectInvalid(
      { surfaces: Array.from({ length: 5 }, () => ({ value: 0.5, color: [1, 1, 1] as [number, number, number] })) },
      /1 to 4 isosurfaces, got 5/,
    );
    expectInvalid({ surfaces: [{ value: 1.5, color: [1, 1, 1] }] }, /surface 0: value must be in \[0, 1\]/);
    expectInvalid(
      {
        surfaces: [
          { value: 0.5, color: [1, 1, 1] },
          { value: 0.2, color: [1, 2, 1] },
        ],
      },
      /surface 1: color must be three numbers in \[0, 1\]/,
    );
    expectInvalid(
      { surfaces: [{ value: 0.5, color: [1, 1, 1], opacity: -0.1 }] },
      /surface 0: opacity must be in \[0, 1\]/,
    );
    expectInvalid({ surfaces: [{ value: NaN, color: [1, 1, 1] }] }, /value must be in \[0, 1\]/);
    expectInvalid({ stepSize: 0 }, /stepSize must be in \[1e-4, 1\]/);
    expectInvalid({ specular: 2 }, /specular must be in \[0, 1\]/);
    expectInvalid({ shininess: -1 }, /shininess must be in \(0, 10000\]/);
    expectInvalid({ lightAngularRadius: 2 }, /lightAngularRadius must be in \[0, π\/2\)/);
    expectInvalid({ aoRadius: NaN }, /aoRadius must be positive/);
    expectInvalid({ output: 'albedo' as 'depth' }, /output must be one of shaded, depth, normal/);
  });

  it('leaves the renderer unchanged when setParams gets a bad value', () => {
    const r = new IsoRenderer({ surfaces: [{ value: 0.3, color: [1, 0, 0] }] });
    const v = r.version;
    expect(() => r.setParams({ specular: -1 })).toThrow(/specular/);
    expect(r.version).toBe(v);
    expect(r.resolvedParams.specular).toBe(0.1);
    r.setParams({ specular: 0.5 });
    expect(r.version).toBe(v + 1);
    expect(r.resolvedParams.specular).toBe(0.5);
  });

  it('derives compile-time features from the scene and refuses more than 4 lights', () => {
    const r = new IsoRenderer({
      surfaces: [
        { value: 0.3, color: [1, 0, 0] },
        { value: 0.6, color: [0, 1, 0], opacity: 0.5 },
      ],
      lightAngularRadius: 0.1,
    });
    const light = {
      type: 'directional' as const,
      direction: [0, 2, 0] as [number, number, number],
      irradiance: [1, 1, 1] as [number, number, number],
    };
    expect(r.features(scene({ lights: [light] }))).toMatchObject({
      ISO_COUNT: 2,
      ISO_LIGHTS: 1,
      ISO_ENV: 1,
      ISO_SOFT_LIGHTS: true,
      ISO_OUTPUT: 0,
    });
    expect(r.features(scene({ environment: { type: 'constant', radiance: [0, 0, 0] } })).ISO_ENV).toBe(0);
    expect(
      r.features(
        scene({ environment: { type: 'latlong', width: 2, height: 1, data: new Float32Array([0, 0, 0, 1, 1, 1]) } }),
      ).ISO_ENV,
    ).toBe(2);
    try {
      r.features(scene({ lights: Array(5).fill(light) }));
      throw new Error('expected a VptError');
    } catch (e) {
      expect(isVptError(e, 'limit-exceeded')).toBe(true);
      expect((e as Error).message).toMatch(/5 lights; at most 4/);
    }
  });

  it('packs surfaces and normalized light directions, with the cone cosine in w', () => {
    const r = new IsoRenderer({
      surfaces: [{ value: 0.3, color: [1, 0.5, 0.25], opacity: 0.75 }],
      lightAngularRadius: 0.2,
    });
    const v = r.paramValues(scene({ lights: [{ type: 'directional', direction: [0, 3, 4], irradiance: [1, 2, 3] }] }));
    expect(Array.from(v.isoValues as Float32Array)).toEqual([Math.fround(0.3), 0, 0, 0]);
    expect(Array.from((v.isoSurface as Float32Array).slice(0, 4))).toEqual([1, 0.5, 0.25, 0.75]);
    expect(Array.from((v.isoLightDirection as Float32Array).slice(0, 4))).toEqual([
      0,
      Math.fround(0.6),
      Math.fround(0.8),
      Math.fround(Math.cos(0.2)),
    ]);
    expect(Array.from((v.isoLightIrradiance as Float32Array).slice(0, 4))).toEqual([1, 2, 3, 0]);
    expect(v.stepSize).toBeCloseTo(0.5 / 8, 12);
    expect(v.aoRadius).toBe(1e30);
  });

  it('binds environment textures for a lat-long map only (the map and its CDFs); a constant sky compiles a variant that names none', () => {
    const r = new IsoRenderer();
    // The blue-noise mask (the default sampler) is bound with every sky; the environment's textures are the question here.
    const environmentTextures = (s: Scene) => r.auxiliaryTextures(s).filter((a) => a.name !== 'blueNoise');
    expect(r.auxiliaryTextures(scene()).map((a) => a.name)).toEqual(['blueNoise']);
    expect(environmentTextures(scene())).toEqual([]);
    for (const lang of ['glsl', 'wgsl'] as const) {
      const constantVariant = preprocess(r.kernels.generate[lang], {
        ...r.features(scene()),
        VPT_TF_2D: false,
        VPT_GRADIENT: false,
        VPT_GUIDES: false,
        VPT_CLIP: false,
        VPT_DEPTH_LIMIT: false,
        VPT_SLICE_PLANE: false,
        VPT_CHANNELS: 0,
        VPT_LABELS: false,
      });
      expect(constantVariant).not.toMatch(/envMap|envMarginal|envConditional/);
      expect(constantVariant).toMatch(/u\.background/);
    }
    const data = new Float32Array(4 * 2 * 3).fill(1);
    const latlong = environmentTextures(scene({ environment: { type: 'latlong', width: 4, height: 2, data } }));
    expect(latlong.map((a) => [a.create!().width, a.create!().height])).toEqual([
      [4, 2],
      [3, 1],
      [5, 2],
    ]);
    // The key follows the image's identity, so a camera move rebuilds nothing.
    expect(environmentTextures(scene({ environment: { type: 'latlong', width: 4, height: 2, data } }))[0].key).toBe(
      latlong[0].key,
    );
    expect(
      environmentTextures(scene({ environment: { type: 'latlong', width: 4, height: 2, data: data.slice() } }))[0].key,
    ).not.toBe(latlong[0].key);
  });
});
