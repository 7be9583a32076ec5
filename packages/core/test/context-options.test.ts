import { describe, expect, it } from 'vitest';
import {
  checkGpuBudget,
  checkRenderSize,
  checkVolumeOptions,
  DEFAULT_GPU_BYTES,
  type RenderContextOptions,
} from '../src/context/context-options.js';
import { thrownVptError as thrown } from '../../../tests/helpers/test-scene.js';

// The options' checks without a device: RenderContext.create runs exactly these.
const base = { width: 8, height: 8 } as RenderContextOptions;
const opts = (o: Partial<RenderContextOptions>) => ({ ...base, ...o }) as RenderContextOptions;

describe('RenderContext options are checked once, naming the option', () => {
  it('fills the documented defaults (RenderContextOptions: fast sampling, bricking off, 32-voxel bricks, 16 uploads)', () => {
    expect(checkVolumeOptions(base)).toEqual({
      sampling: 'fast',
      allowHalfFloat: false,
      bricking: 'off',
      brickSize: 32,
      brickUploadsPerFrame: 16,
      brickLod: false,
    });
  });

  it.each([
    ['sampling', { sampling: 'linear' }],
    ['bricking', { bricking: 'on' }],
    ['brickSize', { brickSize: 48 }],
    ['brickSize', { brickSize: 4 }],
    ['brickSize', { brickSize: 512 }],
    ['brickSize', { brickSize: NaN }],
    ['brickUploadsPerFrame', { brickUploadsPerFrame: 0 }],
    ['brickUploadsPerFrame', { brickUploadsPerFrame: 1.5 }],
  ] as const)('refuses a bad %s: %j', (field, o) => {
    const e = thrown(() => checkVolumeOptions(opts(o as Partial<RenderContextOptions>)));
    expect(e.code).toBe('invalid-scene');
    expect(e.message.startsWith(`${field}:`)).toBe(true);
  });

  it('takes every power of two from 8 to 256 as a brick size', () => {
    for (let b = 8; b <= 256; b *= 2) expect(checkVolumeOptions(opts({ brickSize: b })).brickSize).toBe(b);
  });

  it('maxGpuBytes: positive, else derived from the device within [1 GiB, 4 GiB]', () => {
    for (const bad of [0, -1, NaN, '1e9' as unknown as number]) {
      const e = thrown(() => checkGpuBudget(bad, {}));
      expect(e.code).toBe('invalid-scene');
      expect(e.message).toMatch(/^maxGpuBytes:/);
    }
    expect(checkGpuBudget(12345, { maxBufferSize: 1 })).toBe(12345);
    expect(checkGpuBudget(undefined, {})).toBe(DEFAULT_GPU_BYTES);
    expect(checkGpuBudget(undefined, { maxBufferSize: 1 })).toBe(2 ** 30);
    expect(checkGpuBudget(undefined, { maxBufferSize: 3 * 2 ** 30 })).toBe(3 * 2 ** 30);
    expect(checkGpuBudget(undefined, { maxBufferSize: 2 ** 40 })).toBe(4 * 2 ** 30);
  });

  it('render size: positive integers (invalid-scene), within the 2D texture limit (limit-exceeded)', () => {
    const limits = { maxTextureDimension2D: 64 };
    expect(() => checkRenderSize(64, 1, limits)).not.toThrow();
    for (const [w, h] of [
      [0, 8],
      [8, 2.5],
      [8, NaN],
    ]) {
      expect(thrown(() => checkRenderSize(w, h, limits)).code).toBe('invalid-scene');
    }
    const e = thrown(() => checkRenderSize(65, 8, limits));
    expect(e.code).toBe('limit-exceeded');
    expect(e.message).toMatch(/maxTextureDimension2D/);
  });
});
