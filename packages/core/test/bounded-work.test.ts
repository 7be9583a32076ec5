// Issue 28 item 5: setup work that one scene could make unbounded (a 2D transfer function of
// 4,096 Gaussian widgets took 31 s to rasterize, a procedural volume of 512³ over 25 s) is now
// refused with limit-exceeded naming the bound, and the largest accepted case stays quick.
import { describe, expect, it } from 'vitest';
import {
  createProceduralVolume,
  MAX_PROCEDURAL_SIZE,
  MAX_TF_POINTS,
  MAX_TF_WIDGETS,
  rasterizeTransferFunction,
  transferFunctionFromJSON,
  validateTransferFunction,
  type TransferFunction,
} from '@vpt/core';
import { thrownVptError as thrown } from '../../../tests/helpers/test-scene.js';

const gaussians = (n: number): TransferFunction => ({
  dimensions: '2d',
  widgets: Array.from({ length: n }, (_, i) => ({
    type: 'gaussian' as const,
    center: [i / n, 0.5] as [number, number],
    width: [0.05, 0.2] as [number, number],
    color: [1, 0.5, 0.25] as [number, number, number],
    opacity: 0.5,
  })),
});

describe('bounded setup work', () => {
  it('a 2D transfer function with more than MAX_TF_WIDGETS widgets is refused at once, from code and from JSON', () => {
    const t0 = performance.now();
    const e = thrown(() => validateTransferFunction(gaussians(4096)));
    expect(e.code).toBe('limit-exceeded');
    expect(e.message).toMatch(/4096 widgets exceed the limit of 256 \(MAX_TF_WIDGETS/);
    expect(thrown(() => transferFunctionFromJSON(JSON.parse(JSON.stringify(gaussians(MAX_TF_WIDGETS + 1))))).code).toBe(
      'limit-exceeded',
    );
    expect(performance.now() - t0).toBeLessThan(1000);
  });

  it('the largest accepted 2D transfer function rasterizes in seconds, not tens of seconds', () => {
    const t0 = performance.now();
    const texels = rasterizeTransferFunction(gaussians(MAX_TF_WIDGETS));
    expect(texels.every(Number.isFinite)).toBe(true);
    expect(performance.now() - t0).toBeLessThan(10_000);
  }, 30_000); // the bound is the assertion's, not vitest's 5 s default (loaded cores)

  it('1D control points beyond MAX_TF_POINTS are limit-exceeded too', () => {
    const points = Array.from({ length: MAX_TF_POINTS + 1 }, (_, i) => ({
      value: i / MAX_TF_POINTS,
      color: [1, 1, 1] as [number, number, number],
      opacity: 1,
    }));
    expect(thrown(() => validateTransferFunction({ dimensions: '1d', points })).code).toBe('limit-exceeded');
  });

  it('a procedural volume beyond MAX_PROCEDURAL_SIZE (256) is refused; the largest builds in seconds', () => {
    expect(MAX_PROCEDURAL_SIZE).toBe(256);
    const e = thrown(() => createProceduralVolume('blob', 512));
    expect(e.code).toBe('limit-exceeded');
    expect(e.message).toMatch(/512 exceeds the limit of 256 voxels per side \(MAX_PROCEDURAL_SIZE\)/);
    const t0 = performance.now();
    expect(createProceduralVolume('blob', MAX_PROCEDURAL_SIZE).dims).toEqual([256, 256, 256]);
    expect(performance.now() - t0).toBeLessThan(20_000);
  }, 30_000);
});
