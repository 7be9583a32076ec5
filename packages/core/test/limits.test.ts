import { describe, expect, it } from 'vitest';
import {
  createProceduralVolume,
  createVolume,
  defaultCamera,
  FLOAT32_MAX,
  MAX_CAMERA_COORDINATE,
  MAX_DENSITY_SCALE,
  MAX_RADIANCE,
  normalizationRange,
  normalizedData,
  validateParams,
  validateScene,
  validateSceneForDevice,
  type Renderer,
} from '../src/index.js';
import { testScene as scene, thrownVptError as thrown } from '../../../tests/helpers/test-scene.js';

describe('numbers the GPU cannot represent (float32) are refused, naming the field and the limit', () => {
  // 1e39 is finite in float64 but Infinity in float32: it used to pass and render black.
  it('constant environment 1e39', () => {
    const e = thrown(() => validateScene(scene({ environment: { type: 'constant', radiance: [1e39, 1, 1] } })));
    expect(e.code).toBe('invalid-scene');
    expect(e.message).toMatch(/Environment: radiance\[0\]: 1e\+39 exceeds the float32 range/);
  });
  it('environment 3e38 (finite in float32) is above MAX_RADIANCE', () => {
    expect(
      thrown(() => validateScene(scene({ environment: { type: 'constant', radiance: [3e38, 3e38, 3e38] } }))).message,
    ).toContain(String(MAX_RADIANCE));
    expect(() =>
      validateScene(scene({ environment: { type: 'constant', radiance: [MAX_RADIANCE, MAX_RADIANCE, MAX_RADIANCE] } })),
    ).not.toThrow();
  });
  it('lat-long texel × scale above MAX_RADIANCE', () => {
    const data = new Float32Array(2 * 1 * 3).fill(1);
    expect(
      thrown(() => validateScene(scene({ environment: { type: 'latlong', width: 2, height: 1, data, scale: 1e19 } })))
        .message,
    ).toMatch(/scale|MAX_RADIANCE/);
  });
  it('directional light 1e39', () => {
    const e = thrown(() =>
      validateScene(scene({ lights: [{ type: 'directional', direction: [0, 1, 0], irradiance: [1e39, 0, 0] }] })),
    );
    expect(e.message).toMatch(/Light 0: irradiance\[0\]: 1e\+39 exceeds the float32 range/);
  });
  it('camera at z = 1e39 and beyond MAX_CAMERA_COORDINATE', () => {
    expect(
      thrown(() => validateScene(scene({ camera: { ...defaultCamera(), position: [0, 0, 1e39] } }))).message,
    ).toMatch(/position\[2\] = 1e\+39 exceeds the limit/);
    expect(
      thrown(() =>
        validateScene(scene({ camera: { ...defaultCamera(), position: [0, 0, 2 * MAX_CAMERA_COORDINATE] } })),
      ).message,
    ).toContain('MAX_CAMERA_COORDINATE');
    expect(() =>
      validateScene(scene({ camera: { ...defaultCamera(), position: [0, 0, MAX_CAMERA_COORDINATE] } })),
    ).not.toThrow();
  });
  it('densityScale and opacity 1e39', () => {
    expect(thrown(() => validateScene(scene({ densityScale: 1e39 }))).message).toMatch(
      /densityScale: 1e\+39 exceeds the float32 range/,
    );
    expect(thrown(() => validateScene(scene({ densityScale: 2 * MAX_DENSITY_SCALE }))).message).toContain(
      String(MAX_DENSITY_SCALE),
    );
    // Extinction = densityScale × opacity is bounded too: free flights must stay above float32 resolution.
    const dense = {
      dimensions: '1d' as const,
      points: [{ value: 0, color: [1, 1, 1] as [number, number, number], opacity: 1000 }],
    };
    expect(thrown(() => validateScene(scene({ densityScale: 1e6, transferFunction: dense }))).message).toMatch(
      /1000000 × the transfer function's largest opacity 1000 = 1000000000 exceeds the limit 100000000 \(MAX_EXTINCTION/,
    );
    expect(() => validateScene(scene({ densityScale: 1e5, transferFunction: dense }))).not.toThrow();
    const tf = {
      dimensions: '1d' as const,
      points: [{ value: 0, color: [1, 1, 1] as [number, number, number], opacity: 1e39 }],
    };
    expect(thrown(() => validateScene(scene({ transferFunction: tf }))).message).toMatch(
      /opacity 1e\+39 exceeds the limit/,
    );
  });
  it('FLOAT32_MAX is the largest finite float32', () => {
    expect(Math.fround(FLOAT32_MAX)).toBe(FLOAT32_MAX);
    expect(Math.fround(FLOAT32_MAX * (1 + 2 ** -23))).toBe(Infinity);
  });
});

describe('untyped or late errors become typed VptErrors at validation', () => {
  it('a light without a direction', () => {
    const e = thrown(() => validateScene(scene({ lights: [{ type: 'directional', irradiance: [1, 1, 1] } as never] })));
    expect(e.message).toMatch(/Light 0: direction: must be an array of 3 numbers, got nothing/);
  });
  it('procedural size 100000 is a limit-exceeded error', () => {
    const e = thrown(() => createProceduralVolume('sphere', 100000));
    expect(e.code).toBe('limit-exceeded');
    expect(e.message).toMatch(/100000 exceeds the limit of 256 voxels per side/);
  });
  it('a lat-long width of 1.5', () => {
    const e = thrown(() =>
      validateScene(scene({ environment: { type: 'latlong', width: 1.5, height: 1, data: new Float32Array(3) } })),
    );
    expect(e.message).toMatch(/width, height\]\[0\]: must be an integer/);
  });
  it('a lat-long map wider than the device allows is limit-exceeded at setScene', () => {
    const s = scene({ environment: { type: 'latlong', width: 64, height: 32, data: new Float32Array(64 * 32 * 3) } });
    const renderer = { name: 'eam' } as Renderer;
    expect(thrown(() => validateSceneForDevice(s, renderer, { maxTextureDimension2D: 64 })).code).toBe(
      'limit-exceeded',
    );
    expect(() => validateSceneForDevice(s, renderer, { maxTextureDimension2D: 65 })).not.toThrow();
  });
});

describe('declared renderer parameters', () => {
  const specs = {
    stepSize: { kind: 'step' },
    mode: { kind: 'enum', values: ['a', 'b'] },
    n: { kind: 'number', min: 1, max: 4, integer: true },
  } as const;
  it('refuses unknown keys, listing the known ones', () => {
    expect(thrown(() => validateParams('X', specs, { stepsize: 0.1 })).message).toMatch(
      /unknown key "stepsize" \(known: stepSize, mode, n\)/,
    );
  });
  it('refuses steps of 0, negative, 1e-9 and above 1, and wrong types', () => {
    for (const bad of [0, -0.01, 1e-9, 2, '0.1', NaN, Infinity])
      expect(thrown(() => validateParams('X', specs, { stepSize: bad })).message).toMatch(/X\.stepSize/);
    expect(() => validateParams('X', specs, { stepSize: 0.01, mode: 'b', n: 4 })).not.toThrow();
    expect(thrown(() => validateParams('X', specs, { n: 2.5 })).message).toMatch(/X\.n: must be an integer/);
    expect(thrown(() => validateParams('X', specs, { mode: 'c' })).message).toMatch(/X\.mode: must be one of "a", "b"/);
  });
  it('a step below MIN_STEP_VOXELS voxels of the scene is refused at setScene', () => {
    const s = scene({ volume: createVolume([128, 64, 32], 'uint8') });
    const renderer = (stepSize: number) =>
      ({ name: 'eam', paramSpecs: specs, getParams: () => ({ stepSize }) }) as unknown as Renderer;
    expect(thrown(() => validateSceneForDevice(s, renderer(1e-4), { maxTextureDimension2D: 8192 })).message).toMatch(
      /EAM\.stepSize: 0\.0001 is below the smallest step .* 0\.00078125 world units/,
    );
    expect(() => validateSceneForDevice(s, renderer(0.1 / 128), { maxTextureDimension2D: 8192 })).not.toThrow();
  });
});

describe('a constant volume has a defined mapping', () => {
  it('a positive constant float32 volume normalizes to 1 (the box it fills renders)', () => {
    const v = createVolume([2, 2, 1], 'float32', new Float32Array([0.7, 0.7, 0.7, 0.7]));
    expect(normalizationRange(v)).toEqual([0, Math.fround(0.7)]);
    expect(Array.from(normalizedData(v))).toEqual([1, 1, 1, 1]);
  });
  it('a negative constant int16 volume normalizes to 0, and so does all-zero data', () => {
    expect(Array.from(normalizedData(createVolume([3, 1, 1], 'int16', new Int16Array([-1000, -1000, -1000]))))).toEqual(
      [0, 0, 0],
    );
    expect(Array.from(normalizedData(createVolume([2, 1, 1], 'float32', new Float32Array([0, 0]))))).toEqual([0, 0]);
    expect(Array.from(normalizedData(createVolume([2, 1, 1], 'int16', new Int16Array([300, 300]))))).toEqual([1, 1]);
  });
});
