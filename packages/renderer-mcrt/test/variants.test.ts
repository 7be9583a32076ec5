import { describe, expect, it } from 'vitest';
import { testScene } from '../../../tests/helpers/test-scene.js';
import { createProceduralVolume, isVptError, preprocess, rampTransferFunction, type Scene } from '@vpt/core';
import { computeFeatures, generateKernel, McrtRenderer, resolveParams, type McrtFeatures } from '../src/index.js';

const scene = (over: Partial<Scene> = {}): Scene =>
  testScene({
    camera: { position: [0, 0, 2], target: [0, 0, 0], up: [0, 1, 0], fovy: 0.8 },
    densityScale: 10,
    seed: 1,
    ...over,
  });

describe('MCRT feature variants', () => {
  // The flags of a plain scene under the default parameters: a constant sky, no lights.
  const base: McrtFeatures = {
    ENV_MAP: false,
    ENV_LIGHT: true,
    LIGHT_COUNT: 0,
    SINGLE_SCATTERING: false,
    LIGHT_SAMPLES: 1,
    MAJORANT_GRID: true,
    TRACKING: 2,
    ENV_SAMPLING: 2,
    MIS_POWER: true,
    DEBUG_OUTPUT: 0,
    GENERIC: false,
    BLUE_NOISE: false,
  };

  it('derives the flags from the scene and the parameters', () => {
    const f = computeFeatures(
      scene({
        lights: [
          { type: 'directional', direction: [0, 1, 0], irradiance: [1, 1, 1] },
          { type: 'directional', direction: [1, 0, 0], irradiance: [0, 0, 0] },
        ],
      }),
      resolveParams({}),
    );
    expect(f).toEqual({ ...base, LIGHT_COUNT: 1 });
    const black = computeFeatures(
      scene({ environment: { type: 'constant', radiance: [0, 0, 0] } }),
      resolveParams({ environmentSampling: 'light', misHeuristic: 'balance' }),
    );
    expect(black.ENV_LIGHT).toBe(false);
    expect(black.ENV_SAMPLING).toBe(0); // irrelevant flags are canonical: no extra variants
    expect(black.MIS_POWER).toBe(false);
    const map = computeFeatures(
      scene({ environment: { type: 'latlong', width: 2, height: 1, data: new Float32Array([0, 0, 0, 1, 2, 3]) } }),
      resolveParams({ scattering: 'single', tracking: 'ratio', majorantGrid: false }),
    );
    expect(map).toMatchObject({
      ENV_MAP: true,
      ENV_LIGHT: true,
      SINGLE_SCATTERING: true,
      TRACKING: 1,
      MAJORANT_GRID: false,
    });
    // Light samples are compiled in for single scattering only: multiple scattering keeps one variant.
    expect(computeFeatures(scene(), resolveParams({ scattering: 'single', lightSamples: 3 })).LIGHT_SAMPLES).toBe(3);
    expect(computeFeatures(scene(), resolveParams({ lightSamples: 3 })).LIGHT_SAMPLES).toBe(1);
    const darkMap = computeFeatures(
      scene({ environment: { type: 'latlong', width: 1, height: 1, data: new Float32Array(3) } }),
      resolveParams({}),
    );
    expect(darkMap.ENV_MAP).toBe(false);
  });

  // The context's own flags (VPT_GUIDES, VPT_CLIP, VPT_DEPTH_LIMIT, deferred by generateKernel)
  // resolved as RenderContext does without a denoiser, for an unclipped scene, without a depth limit.
  const both = (f: McrtFeatures) => {
    const k = generateKernel(f);
    return [k.glsl, k.wgsl].map((src) =>
      preprocess(src, {
        VPT_GUIDES: false,
        VPT_CLIP: false,
        VPT_DEPTH_LIMIT: false,
        VPT_SLICE_PLANE: false,
        VPT_LABELS: false,
      }),
    );
  };

  it('compiles only the code a variant needs, in both languages', () => {
    for (const src of both(base)) {
      expect(src).not.toMatch(/^\s*#(if|elif|else|endif)/m);
      expect(src).not.toContain('envMap');
      expect(src).not.toContain('lightDirection');
      expect(src).toContain('majorantGrid');
      expect(src).toContain('misPower(a, b)');
      expect(src).toContain('u.rouletteDepth');
    }
    for (const src of both({ ...base, ENV_MAP: true, LIGHT_COUNT: 2 })) {
      expect(src).toContain('sampleEnvironment(xi1, xi2)');
      expect(src).toContain('u.lightDirection[i]');
    }
    // Unclipped: every ray meets the volume box alone; clipped: every ray (camera, scattered, shadow) its kept interval.
    for (const src of both(base)) expect(src).not.toContain('keptInterval');
    for (const lang of ['glsl', 'wgsl'] as const) {
      const clipped = preprocess(generateKernel({ ...base, LIGHT_COUNT: 1 })[lang], {
        VPT_GUIDES: false,
        VPT_CLIP: true,
        VPT_DEPTH_LIMIT: false,
        VPT_SLICE_PLANE: false,
        VPT_LABELS: false,
      });
      expect(clipped).toContain('keptInterval(');
      expect(clipped).not.toContain('intersectBox(');
    }
    for (const src of both({ ...base, MAJORANT_GRID: false })) {
      expect(src).not.toContain('majorantGrid');
      expect(src).not.toContain('ddaNext');
      expect(src).toContain('u.globalMajorant');
    }
    for (const src of both({ ...base, SINGLE_SCATTERING: true })) {
      expect(src).not.toContain('u.rouletteDepth');
      expect(src).not.toContain('LIGHT_SAMPLES');
    }
    for (const src of both({ ...base, SINGLE_SCATTERING: true, LIGHT_SAMPLES: 2 }))
      expect(src).toContain('k < LIGHT_SAMPLES && severalSamples;');
    for (const src of both({ ...base, TRACKING: 0 })) expect(src).not.toMatch(/exp\(-ctl/);
    for (const src of both({ ...base, ENV_SAMPLING: 1, MIS_POWER: false })) {
      expect(src).not.toContain('misWeight');
      expect(src).toContain('sampleUniformSphere(xi1, xi2)');
    }
    for (const src of both({ ...base, ENV_SAMPLING: 0, MIS_POWER: false }))
      expect(src).not.toContain('sampleUniformSphere(xi1, xi2)');
    for (const src of both({ ...base, ENV_LIGHT: false, ENV_SAMPLING: 0, MIS_POWER: false })) {
      expect(src).not.toContain('sampleUniformSphere(xi1, xi2)');
      expect(src).not.toContain('misWeight');
    }
    const full = generateKernel({ ...base, ENV_MAP: true, LIGHT_COUNT: 2 }).glsl.length;
    expect(
      generateKernel({
        ...base,
        ENV_LIGHT: false,
        ENV_SAMPLING: 0,
        MIS_POWER: false,
        MAJORANT_GRID: false,
        SINGLE_SCATTERING: true,
      }).glsl.length,
    ).toBeLessThan(full * 0.8);
  });

  it('serves the variant of the last features() call and caches it', () => {
    const r = new McrtRenderer();
    r.features(scene());
    const a = r.kernels.generate;
    r.features(scene({ environment: { type: 'constant', radiance: [0, 0, 0] } }));
    const b = r.kernels.generate;
    expect(b).not.toBe(a);
    r.features(scene());
    expect(r.kernels.generate).toBe(a);
  });

  it('lists the majorant grid (value ranges, TF bounds, grid) and environment tables as auxiliary textures with content keys', () => {
    const r = new McrtRenderer({ majorantGrid: true }); // set: the rules would take the global majorant for this blob under the ramp TF
    const s = scene({
      volume: createProceduralVolume('blob', 20),
      environment: { type: 'latlong', width: 4, height: 2, data: new Float32Array(24).fill(1) },
    });
    const aux = r.auxiliaryTextures(s);
    expect(aux.map((a) => a.name)).toEqual([
      'majorantRanges',
      'opacityBounds',
      'majorantGrid',
      'envMap',
      'envMarginal',
      'envConditional',
    ]);
    expect(aux.map((a) => a.bind !== false)).toEqual([false, false, true, true, true, true]);
    const keys = (x: Scene) =>
      r
        .auxiliaryTextures(x)
        .slice(0, 3)
        .map((a) => a.key);
    const [ranges, bounds, grid] = keys(s);
    // A camera move keeps every key; the volume changes the ranges, the TF the bounds, and all of them the grid.
    expect(keys({ ...s, camera: { ...s.camera, position: [1, 2, 3] } })).toEqual([ranges, bounds, grid]);
    const dense = keys({ ...s, densityScale: 11 });
    expect([dense[0], dense[1]]).toEqual([ranges, bounds]);
    expect(dense[2]).not.toBe(grid);
    const recoloured = keys({ ...s, transferFunction: rampTransferFunction([1, 0, 0]) });
    expect(recoloured[0]).toBe(ranges);
    expect(recoloured[1]).not.toBe(bounds);
    expect(recoloured[2]).not.toBe(grid);
    const other = keys({ ...s, volume: createProceduralVolume('blob', 20) });
    expect(other[0]).not.toBe(ranges);
    expect(other[2]).not.toBe(grid);
    // 20³ voxels in cells of 8: 3³ cells in a 2 × 2 slice atlas of 3 × 3 tiles, all made on the GPU.
    expect(aux.slice(0, 3).every((a) => a.render && !a.create)).toBe(true);
    expect([aux[0].render!.width, aux[0].render!.height, aux[2].render!.width, aux[2].render!.height]).toEqual([
      6, 6, 6, 6,
    ]);
    expect(aux[0].render!.inputs.map((i) => i.name)).toEqual(['volume']);
    expect(aux[0].render!.values.gridCells).toEqual([3, 3, 3, 2]);
    // Without a RenderContext's volume binding: the exact path's data values, here already in [0, 1].
    expect(aux[2].render!.values).toEqual({ gridCells: [3, 3, 3, 2], gridDensity: 10, valueScale: 1, valueOffset: 0 });
    expect(aux[1].render!.inputs.map((i) => i.name)).toEqual(['transferFunction']);
    expect(aux[2].render!.inputs.map((i) => i.name)).toEqual(['majorantRanges', 'opacityBounds']);
    const cdf = aux[4].create!();
    expect([cdf.width, cdf.height]).toEqual([3, 1]);
    r.setParams({ majorantGrid: false });
    expect(r.auxiliaryTextures(scene()).length).toBe(0);
  });

  it('specialize: false compiles one generic kernel for every scene, with the scene features as data', () => {
    const light = {
      type: 'directional' as const,
      direction: [0, 1, 0] as [number, number, number],
      irradiance: [1, 1, 1] as [number, number, number],
    };
    const scenes = [
      scene(),
      scene({ environment: { type: 'constant', radiance: [0, 0, 0] }, lights: [light, light] }),
      scene({
        environment: { type: 'latlong', width: 2, height: 1, data: new Float32Array([0, 0, 0, 1, 2, 3]) },
        lights: [light],
      }),
    ];
    const specialised = new Set(scenes.map((s) => JSON.stringify(computeFeatures(s, resolveParams({})))));
    expect(specialised.size).toBe(3);
    for (const scattering of ['single', 'multiple'] as const) {
      for (const majorantGrid of [true, false]) {
        const keys = new Set(
          scenes.map((s) =>
            JSON.stringify(computeFeatures(s, resolveParams({ specialize: false, scattering, majorantGrid }))),
          ),
        );
        expect(keys.size, `${scattering} grid=${majorantGrid}`).toBe(1);
      }
    }
    // Light samples of a single-scattering generic kernel are compiled in (applied where the runtime maxDepth is 1).
    expect(
      new McrtRenderer({ specialize: false, scattering: 'single', lightSamples: 3 }).features(scenes[0]).LIGHT_SAMPLES,
    ).toBe(3);
    const r = new McrtRenderer({ specialize: false, scattering: 'single', majorantGrid: false });
    const f = r.features(scenes[1]);
    expect(f).toMatchObject({
      GENERIC: true,
      ENV_MAP: true,
      SINGLE_SCATTERING: false,
      MAJORANT_GRID: true,
      LIGHT_COUNT: 8,
      LIGHT_SAMPLES: 1, // auto: phase sampling of the constant sky, one sample
    });
    for (const src of both(f as unknown as McrtFeatures)) expect(src).toContain('u.lightCount');
    for (const src of both({ ...base, LIGHT_COUNT: 2 })) expect(src).not.toContain('u.lightCount');
    // The scene's features arrive as data: light count and depth as uniforms, a constant sky
    // as a constant map, the global majorant as a one-cell grid.
    const v = r.paramValues(scenes[1]);
    expect([v.lightCount, v.maxDepth]).toEqual([2, 1]);
    const aux = r.auxiliaryTextures(scenes[1]);
    expect(aux.map((a) => a.name)).toEqual([
      'majorantRanges',
      'opacityBounds',
      'majorantGrid',
      'envMap',
      'envMarginal',
      'envConditional',
    ]);
    expect(aux[2].render!.values.gridCells).toEqual([1, 1, 1, 1]);
    const map = aux[3].create!().data as Float32Array;
    expect(map.length).toBeGreaterThan(4);
    for (let i = 0; i < map.length; i += 4) expect([map[i], map[i + 1], map[i + 2]]).toEqual([0, 0, 0]);
    expect(() => new McrtRenderer({ specialize: 'no' as unknown as boolean })).toThrow(/specialize/);
  });

  it('rejects bad parameters with a typed error', () => {
    const bad: object[] = [
      { anisotropy: 1 },
      { anisotropy: NaN },
      { maxDepth: 0 },
      { maxDepth: 2.5 },
      { tracking: 'woodcock' },
      { rouletteDepth: 0 },
      { majorantCellSize: 0 },
      { environmentSampling: 'nee' },
    ];
    for (const p of bad) {
      let err: unknown;
      try {
        new McrtRenderer(p);
      } catch (e) {
        err = e;
      }
      expect(isVptError(err) && err.code === 'invalid-scene', JSON.stringify(p)).toBe(true);
    }
    const r = new McrtRenderer();
    expect(() => r.setParams({ anisotropy: -2 })).toThrow(/anisotropy/);
    expect(r.resolvedParams.anisotropy).toBe(0); // a rejected change leaves the renderer as it was
    const many = Array.from({ length: 9 }, () => ({
      type: 'directional' as const,
      direction: [0, 1, 0] as [number, number, number],
      irradiance: [1, 1, 1] as [number, number, number],
    }));
    expect(() => r.features(scene({ lights: many }))).toThrow(/at most 8/);
  });
});
