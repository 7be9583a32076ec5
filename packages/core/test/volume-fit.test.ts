import { describe, expect, it } from 'vitest';
import { createVolume, type Scene } from '../src/index.js';
import { checkVolumeOptions, type RenderContextOptions } from '../src/context/context-options.js';
import { VolumeFit, type RenderWarning } from '../src/context/volume-fit.js';
import type { VolumeUpload } from '../src/gpu/volume-format.js';
import { testScene } from '../../../tests/helpers/test-scene.js';

// The budget fit without a device: a host whose upload costs one byte a voxel (uint8 on the fast path).
function fitFor(budgetBytes: number, options: Partial<RenderContextOptions> = {}, max3D = 2048) {
  const warnings: RenderWarning[] = [];
  const fit = new VolumeFit(checkVolumeOptions({ width: 8, height: 8, ...options } as RenderContextOptions), {
    resources: {
      planUpload: () => ({ bytesPerVoxel: 1 }) as VolumeUpload,
      wantsGradient: () => false,
    },
    maxGpuBytes: budgetBytes,
    max3D: () => max3D,
    size: () => ({ width: 8, height: 8 }),
    budgetBytes: () => budgetBytes,
    warn: (w) => warnings.push(w),
  });
  return { fit, warnings };
}

const cube = (n: number) => createVolume([n, n, n], 'uint8', new Uint8Array(n * n * n));
const voxels = (s: Scene) => s.volume.dims[0] * s.volume.dims[1] * s.volume.dims[2];

describe('VolumeFit: the GPU budget decides what is uploaded', () => {
  it('a volume within the budget is the scene unchanged, with no warning', () => {
    const { fit, warnings } = fitFor(32 ** 3);
    const scene = testScene({ volume: cube(32) });
    expect(fit.fitScene(scene)).toBe(scene);
    expect(warnings).toEqual([]);
    expect(fit.bricks).toBeNull();
  });

  it('a volume over the budget is downsampled to fit, warned once per volume', () => {
    const budget = 20 ** 3;
    const { fit, warnings } = fitFor(budget);
    const scene = testScene({ volume: cube(40) });
    const fitted = fit.fitScene(scene);
    expect(voxels(fitted)).toBeLessThanOrEqual(budget);
    expect(fitted.volume.dims.every((d) => d < 40)).toBe(true);
    expect(warnings.map((w) => w.code)).toEqual(['volume-downsampled']);
    // The same volume again (a camera change, say): the same copy, no second warning.
    expect(fit.fitScene({ ...scene, seed: 2 }).volume).toBe(fitted.volume);
    expect(warnings.length).toBe(1);
  });

  it('a side beyond the 3D texture limit is downsampled even within the budget', () => {
    const { fit, warnings } = fitFor(2 ** 30, {}, 16);
    const fitted = fit.fitScene(testScene({ volume: cube(40) }));
    expect(Math.max(...fitted.volume.dims)).toBeLessThanOrEqual(16);
    expect(warnings[0].message).toMatch(/maxTextureDimension3D/);
  });

  it("bricking 'auto' keeps an oversized volume whole, as a brick plan within the budget", () => {
    const budget = 20 ** 3;
    const { fit, warnings } = fitFor(budget, { bricking: 'auto', brickSize: 8 });
    const scene = testScene({ volume: cube(40) });
    expect(fit.fitScene(scene)).toBe(scene);
    expect(fit.bricks?.capacityBytes).toBe(budget);
    expect(fit.bricks?.brickSize).toBe(8);
    expect(warnings).toEqual([]);
  });

  it('a budget with no room for one voxel is limit-exceeded', () => {
    const { fit } = fitFor(0);
    expect(() => fit.fitScene(testScene({ volume: cube(4) }))).toThrow(/maxGpuBytes/);
  });
});
