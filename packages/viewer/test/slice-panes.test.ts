import { describe, expect, it } from 'vitest';
import {
  canvasPlacement,
  dataExtent,
  defaultWindow,
  paneGeometries,
  probeValue,
  screenPoint,
  sliceAspect,
  voxelAt,
  type Voxel,
} from '../src/slice-panes.js';

/** A volume of these dims whose orientation is given by a sidecar's axis codes (RAS+ letters per index axis). */
const coded = (axisCodes: string, dims: [number, number, number] = [4, 5, 6]) => ({
  dims,
  spacing: [1, 1, 1] as [number, number, number],
  meta: { axisCodes },
});

describe('slice pane geometry', () => {
  it('RAS data: axial cuts z, coronal y, sagittal x, in the radiological convention', () => {
    const [axial, coronal, sagittal] = paneGeometries(coded('RAS'));
    // Axial: x (R) across, mirrored so that the patient's right is on the left; y (A) up.
    expect(axial).toMatchObject({ axis: 2, col: 0, row: 1, transpose: false, flipX: true, flipY: true });
    expect(axial.labels).toEqual({ left: 'R', right: 'L', top: 'A', bottom: 'P' });
    expect(coronal).toMatchObject({ axis: 1, col: 0, row: 2, transpose: false, flipX: true, flipY: true });
    expect(coronal.labels).toEqual({ left: 'R', right: 'L', top: 'S', bottom: 'I' });
    // Sagittal: y (A) to the left, z (S) up.
    expect(sagittal).toMatchObject({ axis: 0, col: 1, row: 2, transpose: false, flipX: true, flipY: true });
    expect(sagittal.labels).toEqual({ left: 'A', right: 'P', top: 'S', bottom: 'I' });
  });

  it("the bundled head's PIR: panes are transposed where the image axes do not match the screen's", () => {
    const [axial, coronal, sagittal] = paneGeometries(coded('PIR', [128, 128, 84]));
    expect(axial).toMatchObject({ axis: 1, transpose: true, flipX: true, flipY: false });
    expect(axial.labels).toEqual({ left: 'R', right: 'L', top: 'A', bottom: 'P' });
    expect(coronal).toMatchObject({ axis: 0, transpose: true, flipX: true, flipY: false });
    expect(coronal.labels).toEqual({ left: 'R', right: 'L', top: 'S', bottom: 'I' });
    expect(sagittal).toMatchObject({ axis: 2, transpose: false, flipX: false, flipY: false });
    expect(sagittal.labels).toEqual({ left: 'A', right: 'P', top: 'S', bottom: 'I' });
  });

  it('without an orientation: z, y, x, rows up, no labels', () => {
    const g = paneGeometries({ dims: [4, 5, 6], spacing: [1, 1, 1] });
    expect(g.map((p) => [p.axis, p.transpose, p.flipX, p.flipY, p.labels])).toEqual([
      [2, false, false, true, null],
      [1, false, false, true, null],
      [0, false, false, true, null],
    ]);
  });

  it('voxelAt inverts screenPoint for every voxel of every pane and orientation', () => {
    const dims: [number, number, number] = [3, 4, 5];
    for (const codes of ['RAS', 'PIR', 'LPS', 'SRA']) {
      for (const g of paneGeometries(coded(codes, dims))) {
        for (let k = 0; k < 5; k++)
          for (let j = 0; j < 4; j++)
            for (let i = 0; i < 3; i++) {
              const v: Voxel = [i, j, k];
              const { fx, fy } = screenPoint(g, dims, v);
              const at: Voxel = [0, 0, 0];
              at[g.axis] = v[g.axis];
              expect(voxelAt(g, dims, fx, fy, at), `${codes} ${g.name} ${v}`).toEqual(v);
            }
      }
    }
  });

  it('voxelAt clamps points on and beyond the edges; the cut axis keeps its index', () => {
    const g = paneGeometries({ dims: [4, 5, 6], spacing: [1, 1, 1] })[0]; // axial: x across, y up
    expect(voxelAt(g, [4, 5, 6], 0, 0, [1, 1, 3])).toEqual([0, 4, 3]);
    expect(voxelAt(g, [4, 5, 6], 1, 1, [1, 1, 3])).toEqual([3, 0, 3]);
    expect(voxelAt(g, [4, 5, 6], -0.5, 1.5, [1, 1, 3])).toEqual([0, 0, 3]);
  });

  it('sliceAspect follows the spacing and the transpose; canvasPlacement maps the image onto the stage', () => {
    const v = { dims: [10, 20, 30] as [number, number, number], spacing: [2, 1, 1] as [number, number, number] };
    const [axial] = paneGeometries(v); // z: columns x (10 × 2), rows y (20 × 1)
    expect(sliceAspect(axial, v)).toBe(1);
    const t = { ...axial, transpose: true };
    expect(sliceAspect(t, { dims: [10, 40, 30], spacing: [1, 1, 1] })).toBe(4);
    // Mirrored rows only: the canvas is the stage's box, flipped about its horizontal midline.
    expect(canvasPlacement(axial, { width: 100, height: 50 })).toBe(
      'width:100px;height:50px;transform:matrix(1,0,0,-1,0,50)',
    );
    // Transposed and mirrored left-right: the canvas box is the stage's turned, x' = 100 − y, y' = x.
    expect(canvasPlacement({ ...axial, transpose: true, flipX: true, flipY: false }, { width: 100, height: 50 })).toBe(
      'width:50px;height:100px;transform:matrix(0,1,-1,0,100,0)',
    );
  });

  it('probeValue reads the voxel at x + nx (y + ny z); the starting window spans the data', () => {
    const data = new Int16Array(24).map((_, i) => 3 * i - 1000);
    const v = { dims: [2, 3, 4] as [number, number, number], data };
    expect(probeValue(v, [1, 2, 3])).toBe(3 * (1 + 2 * (2 + 3 * 3)) - 1000);
    expect(dataExtent(v)).toEqual([-1000, -1000 + 3 * 23]);
    expect(defaultWindow([-1000, -931])).toEqual([-965.5, 69]);
    expect(defaultWindow([5, 5])[1]).toBeGreaterThan(0);
  });
});
