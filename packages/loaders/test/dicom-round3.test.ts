/**
 * Issue 25's DICOM items, each on a file made the way the one that showed it was (written
 * byte by byte here): 8-bit pixels in OW under Explicit VR Big Endian (pydicom-data's
 * OBXXXX1A_expb.dcm), the Modality LUT Sequence (mlut_18.dcm), enhanced multi-frame
 * functional groups (eCT_Supplemental.dcm, nibabel's 4d_multiframe_test.dcm), a localizer
 * series, PALETTE COLOR and a malformed NumberOfFrames (badVR.dcm). The real files are in
 * the corpus test (corpus.test.ts). Expected values come from the spec written into each
 * file, not from the loader.
 */
import { describe, expect, it } from 'vitest';
import { loadVolume } from '../src/index.js';
import { dicomElement, dicomFile, dicomText, expectLoaderError, fileOf, uints, type DicomSpec } from './helpers.js';
import { AXIAL, ENHANCED, enhancedFile, modalityLutSequence as lutSequence } from './dicom-fixtures.js';

describe('DICOM: 8-bit pixels in OW, Explicit VR Big Endian', () => {
  it('reads the pixels in order, an odd count included (the last one sits in the padding word)', async () => {
    const pixels = new Uint8Array(15).map((_, i) => (i * 37 + 11) & 0xff); // 5 × 3, odd
    const spec: DicomSpec = { rows: 3, cols: 5, pixels, bitsAllocated: 8, pixelVR: 'OW', pixelSpacing: [1, 1] };
    const be = await loadVolume(fileOf(dicomFile({ ...spec, syntax: 'explicit-be' }), 'be.dcm'));
    const le = await loadVolume(fileOf(dicomFile({ ...spec, syntax: 'explicit-le' }), 'le.dcm'));
    const ob = await loadVolume(fileOf(dicomFile({ ...spec, pixelVR: 'OB', syntax: 'explicit-be' }), 'ob.dcm'));
    for (const v of [be, le, ob]) {
      expect(v.type).toBe('uint8');
      expect(Array.from(v.data)).toEqual(Array.from(pixels));
    }
  });
});

describe('DICOM: Modality LUT Sequence', () => {
  for (const syntax of ['explicit-le', 'explicit-be', 'implicit-le'] as const) {
    it(`maps stored values through the table, clamped at both ends (${syntax})`, async () => {
      const first = 10;
      const table = Array.from({ length: 8 }, (_, i) => 1000 + 7 * i * i);
      const stored = new Uint16Array([0, 9, 10, 11, 13, 17, 18, 500]);
      // PS3.3 C.11.1.1: below the first mapped value → entry 0, past the table → the last entry.
      const expected = Array.from(stored, (x) => table[Math.min(Math.max(x - first, 0), table.length - 1)]);
      const file = dicomFile({
        rows: 2,
        cols: 4,
        pixels: stored,
        syntax,
        extra: lutSequence(table.length, first, table),
      });
      const v = await loadVolume(fileOf(file, 'mlut.dcm'));
      expect(Array.from(v.data)).toEqual(expected);
      expect(v.meta?.rescale).toBe('Modality LUT Sequence');
    });
  }

  it('a LUT whose data is shorter than its descriptor says is a typed error', async () => {
    const file = dicomFile({ rows: 1, cols: 2, pixels: new Uint16Array([1, 2]), extra: lutSequence(64, 0, [1, 2, 3]) });
    const e = await expectLoaderError(loadVolume(fileOf(file, 'short-lut.dcm')), 'truncated');
    expect(e.message).toMatch(/Modality LUT/);
  });
});

describe('DICOM: enhanced multi-frame functional groups', () => {
  const { frames, stored, plane, rows, cols, SHARED_RESCALE } = ENHANCED;

  for (const syntax of ['explicit-le', 'explicit-be', 'implicit-le'] as const)
    it(`loads the first volume of the largest stack, sorted along the normal, each frame with its own rescale (${syntax})`, async () => {
      const v = await loadVolume(fileOf(enhancedFile(syntax), 'enhanced.dcm'));
      // Expected: stack 1 at time 1, by z (frames 4, 0, 2); each frame's rescale is its own
      // Pixel Value Transformation, else the shared one.
      const order = [4, 0, 2];
      const expected = order.flatMap((k) => {
        const [slope, inter] = frames[k].rescale ?? SHARED_RESCALE;
        return Array.from(stored.subarray(k * plane, (k + 1) * plane), (x) => x * slope + inter);
      });
      expect(v.dims).toEqual([cols, rows, 3]);
      expect(Array.from(v.data)).toEqual(expected);
      expect(v.meta?.rescale).toBe('per slice');
    });

  it('spacing from the Pixel Measures group and the positions, origin and orientation from the plane groups', async () => {
    const v = await loadVolume(fileOf(enhancedFile(), 'enhanced.dcm'));
    expect(v.spacing[0]).toBeCloseTo(0.25, 12); // column spacing
    expect(v.spacing[1]).toBeCloseTo(0.5, 12); // row spacing
    expect(v.spacing[2]).toBeCloseTo((14.5 - 9.5) / 2, 12); // from the positions, not SliceThickness 2.5
    expect(v.origin).toEqual([-20, 30, 9.5]);
    expect(v.orientation).toEqual([1, 0, 0, 0, 1, 0, 0, 0, 1]);
    const warnings = (v.meta?.warnings as string[]).join('\n');
    expect(warnings).toMatch(/2 stacks/);
    expect(warnings).toMatch(/2 volumes/);
    expect(warnings).not.toMatch(/PixelSpacing|1 used/);
  });
});

describe('DICOM: a localizer series (slices in several orientations)', () => {
  it('loads the largest group of one orientation and says why, not "no usable ImagePositionPatient"', async () => {
    const SAGITTAL = [0, 1, 0, 0, 0, -1];
    const slices: DicomSpec[] = [
      ...[0, 1, 2].map((k) => ({ iop: AXIAL, ipp: [0, 0, 3 * k], instance: k + 1 })),
      ...[0, 1].map((k) => ({ iop: SAGITTAL, ipp: [5 * k, 0, 0], instance: k + 4 })),
    ].map((s, k) => ({
      rows: 2,
      cols: 2,
      pixels: new Uint16Array(4).fill(10 * k),
      pixelSpacing: [1, 1] as [number, number],
      ...s,
    }));
    const v = await loadVolume(slices.map((s, k) => fileOf(dicomFile(s), `loc${k}.dcm`)));
    expect(v.dims).toEqual([2, 2, 3]);
    expect(Array.from(v.data)).toEqual([0, 0, 0, 0, 10, 10, 10, 10, 20, 20, 20, 20]);
    expect(v.spacing[2]).toBeCloseTo(3, 12);
    const warnings = (v.meta?.warnings as string[]).join('\n');
    expect(warnings).toMatch(/2 different orientations/);
    expect(warnings).not.toMatch(/no usable ImagePositionPatient/);
  });
});

describe('DICOM: a radial or tri-planar localizer (every slice its own orientation)', () => {
  it('is refused: there is no stack to make a volume of', async () => {
    const iops = [AXIAL, [0, 1, 0, 0, 0, -1], [1, 0, 0, 0, 0, -1]];
    const files = iops.map((iop, k) =>
      fileOf(
        dicomFile({ rows: 2, cols: 2, pixels: new Uint16Array(4), iop, ipp: [0, 0, k], instance: k + 1 }),
        `tri${k}.dcm`,
      ),
    );
    const e = await expectLoaderError(loadVolume(files), 'invalid-data');
    expect(e.message).toMatch(/own orientation/);
  });
});

describe('DICOM: RT Dose grids (pydicom’s rtdose.dcm: 15 frames, Dose Grid Scaling 1e-6)', () => {
  const doseFile = (offsets: number[], scale: string) =>
    dicomFile({
      rows: 1,
      cols: 2,
      pixels: new Uint16Array(2 * offsets.length).map((_, i) => 100 * i + 7),
      frames: offsets.length,
      ipp: [-4, 6, 20],
      iop: AXIAL,
      pixelSpacing: [3, 2],
      extra: (mode) => [
        // Frame Increment Pointer → Grid Frame Offset Vector (an AT: group, element).
        dicomElement(0x28, 0x09, 'AT', uints([0x3004, 0x000c], 2, mode.little), mode),
        dicomElement(0x3004, 0x0c, 'DS', dicomText(offsets.join('\\')), mode),
        dicomElement(0x3004, 0x0e, 'DS', dicomText(scale), mode),
      ],
    });

  it('values are stored × Dose Grid Scaling; z spacing and direction from the Grid Frame Offset Vector', async () => {
    const v = await loadVolume(fileOf(doseFile([0, -2.5, -5], '0.001'), 'dose.dcm'));
    expect(v.type).toBe('float32');
    expect(Array.from(v.data)).toEqual(Array.from({ length: 6 }, (_, i) => Math.fround((100 * i + 7) * 0.001)));
    expect(v.spacing).toEqual([2, 3, 2.5]);
    // Decreasing offsets: frame k lies at z = 20 − 2.5k, so the third axis points along −z.
    expect(v.orientation).toEqual([1, 0, 0, 0, 1, 0, 0, 0, -1]);
    expect(v.origin).toEqual([-4, 6, 20]);
    expect(((v.meta?.warnings as string[] | undefined) ?? []).join()).not.toMatch(/multi-frame spacing/);
  });

  it('offsets that do not run one way are refused', async () => {
    const e = await expectLoaderError(loadVolume(fileOf(doseFile([0, 5, 2], '1'), 'dose.dcm')), 'invalid-data');
    expect(e.message).toMatch(/Grid Frame Offset Vector/);
  });
});

describe('DICOM: refused features name themselves', () => {
  it('PALETTE COLOR is unsupported, naming it', async () => {
    const file = dicomFile({
      rows: 1,
      cols: 2,
      pixels: new Uint8Array([3, 4]),
      bitsAllocated: 8,
      photometric: 'PALETTE COLOR',
    });
    const e = await expectLoaderError(loadVolume(fileOf(file, 'pal.dcm')), 'unsupported');
    expect(e.message).toMatch(/PALETTE COLOR/);
  });

  it('a NumberOfFrames that is not a whole number is a bad header, not 1 frame', async () => {
    const file = dicomFile({ rows: 1, cols: 2, pixels: new Uint16Array(30), frames: '1A' });
    const e = await expectLoaderError(loadVolume(fileOf(file, 'frames.dcm')), 'bad-header');
    expect(e.message).toMatch(/NumberOfFrames "1A"/);
  });
});
