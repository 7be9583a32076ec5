import { describe, expect, it } from 'vitest';
import { createVolume } from '@vpt/core';
import { fileLabelTable, gridError, nrrdSegments } from '../src/labels-layer.js';

// The label layer's pure parts: a file's names and colours for the default table, the grid check.
describe('labels layer', () => {
  it("reads 3D Slicer's segment names, values and colours from NRRD key/values", () => {
    expect(
      nrrdSegments({
        Segment0_Name: 'liver',
        Segment0_LabelValue: '3',
        Segment0_Color: '1 0 0.5',
        Segment1_Name: 'tumour',
        Segment1_Color: 'bad',
        Segment2_Name: 'out of range',
        Segment2_LabelValue: '70000',
      }),
    ).toEqual([
      { id: 3, name: 'liver', rgba: [255, 0, 128, 255] },
      { id: 2, name: 'tumour' },
    ]);
    expect(nrrdSegments(undefined)).toEqual([]);
  });

  it("makes the default table from the file's segments (every id present, the file's names and colours), else the palette", () => {
    const v = createVolume([2, 1, 1], 'uint8', Uint8Array.from([1, 3]), [1, 1, 1]);
    const named = fileLabelTable(
      {
        ...v,
        format: 'nrrd',
        meta: { keyValues: { Segment0_Name: 'liver', Segment0_LabelValue: '3', Segment0_Color: '1 0 0' } },
      },
      v,
    );
    expect(named.map((e) => [e.id, e.name ?? null, e.visible])).toEqual([
      [1, null, true],
      [3, 'liver', true],
    ]);
    expect(named[1].color).toEqual([1, 0, 0]);
    const plain = fileLabelTable({ ...v, format: 'raw' }, v);
    expect(plain.map((e) => e.id)).toEqual([1, 3]);
    expect(plain[1].color).not.toEqual([1, 0, 0]);
  });

  it('accepts a label volume on the image grid and refuses another grid with a typed error', () => {
    const image = createVolume([4, 4, 2], 'uint8', new Uint8Array(32), [1, 1, 2]);
    expect(gridError(createVolume([4, 4, 2], 'uint8', new Uint8Array(32), [1, 1, 2]), image)).toBeNull();
    const dims = gridError(createVolume([4, 4, 1], 'uint8', new Uint8Array(16), [1, 1, 2]), image);
    expect(dims?.code).toBe('invalid-scene');
    expect(dims?.message).toMatch(/4×4×1 .*not the image's 4×4×2/);
    // Same dims, another box (spacing).
    expect(gridError(createVolume([4, 4, 2], 'uint8', new Uint8Array(32), [1, 1, 1]), image)?.code).toBe(
      'invalid-scene',
    );
  });
});
