import { describe, expect, it } from 'vitest';
import { createVolume, type Scene } from '../src/index.js';
import { checkVolumeOptions, type RenderContextOptions } from '../src/context/context-options.js';
import { VolumeFit, type RenderWarning } from '../src/context/volume-fit.js';
import { downsampleLabels } from '../src/scene/label-downsample.js';
import type { VolumeUpload } from '../src/gpu/volume-format.js';
import { testScene } from '../../../tests/helpers/test-scene.js';

// The budget fit without a device: a host whose upload costs one byte a voxel (uint8 on the fast path).
// `labelBytes`: the GPU bytes of a label voxel when the scene's labels are drawn (null: not drawn).
function fitFor(
  budgetBytes: number,
  options: Partial<RenderContextOptions> = {},
  max3D = 2048,
  labelBytes: number | null = 1,
) {
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
    labels: (scene) =>
      scene.labels && labelBytes !== null ? { bytesPerVoxel: labelBytes, downsample: downsampleLabels } : null,
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

  describe('with a label volume on the image grid', () => {
    // Labels: id 1 in the lower half of x, id 2 in the upper half, 0 in a 2-voxel shell.
    const labelCube = (n: number) => {
      const v = createVolume([n, n, n], 'uint8', new Uint8Array(n * n * n));
      for (let z = 2; z < n - 2; z++)
        for (let y = 2; y < n - 2; y++) for (let x = 2; x < n - 2; x++) v.data[x + n * (y + n * z)] = x < n / 2 ? 1 : 2;
      return v;
    };
    const labelScene = (n: number) =>
      testScene({ volume: cube(n), labels: { volume: labelCube(n), table: [{ id: 1 }, { id: 2 }] } });

    it('counts the label bytes: an image that fits alone is downsampled with its labels, by the same factors', () => {
      const n = 32;
      const { fit, warnings } = fitFor(n ** 3 + 100);
      const scene = labelScene(n);
      const fitted = fit.fitScene(scene);
      // Image (1 byte) + labels (1 byte) per voxel within the budget.
      expect(2 * voxels(fitted)).toBeLessThanOrEqual(n ** 3 + 100);
      expect(fitted.labels!.volume.dims).toEqual(fitted.volume.dims);
      expect(fitted.labels!.volume.spacing).toEqual(fitted.volume.spacing);
      expect(fitted.labels!.table).toBe(scene.labels!.table);
      // Only ids of the source: never a blend of 1 and 2.
      expect(new Set(fitted.labels!.volume.data)).toEqual(new Set([0, 1, 2]));
      expect(warnings.length).toBe(1);
      expect(warnings[0].message).toMatch(/label volume/);
      // The scene's own labels are left as given.
      expect(scene.labels!.volume.dims).toEqual([n, n, n]);
    });

    it('a new table on the same label volume reuses the fitted labels, with no second warning', () => {
      const { fit, warnings } = fitFor(32 ** 3);
      const scene = labelScene(32);
      const a = fit.fitScene(scene);
      const b = fit.fitScene({ ...scene, labels: { ...scene.labels!, table: [{ id: 1, visible: false }] } });
      expect(b.labels!.volume).toBe(a.labels!.volume);
      expect(b.labels!.table).toEqual([{ id: 1, visible: false }]);
      expect(b.volume).toBe(a.volume);
      expect(warnings.length).toBe(1);
    });

    it('labels that fit with the image leave the scene unchanged; labels not drawn cost nothing', () => {
      const scene = labelScene(16);
      expect(fitFor(2 * 16 ** 3).fit.fitScene(scene)).toBe(scene);
      // Not drawn by the renderer (the host says null): the image alone against the budget.
      expect(fitFor(16 ** 3, {}, 2048, null).fit.fitScene(scene)).toBe(scene);
    });

    it('beside a brick atlas the labels take their bytes out of its capacity', () => {
      const budget = 20 ** 3;
      const { fit } = fitFor(budget, { bricking: 'auto', brickSize: 8 });
      // 40³ labels exceed budget / 2: downsampled to it, and the atlas has the rest.
      const big = testScene({ volume: cube(40), labels: { volume: labelCube(40), table: [{ id: 1 }] } });
      const fitted = fit.fitScene(big);
      expect(fit.bricks).not.toBeNull();
      const l = fitted.labels!.volume;
      const labelBytes = l.dims[0] * l.dims[1] * l.dims[2];
      expect(labelBytes).toBeLessThanOrEqual(budget / 2);
      expect(fit.bricks!.capacityBytes).toBe(budget - labelBytes);
    });
  });
});
