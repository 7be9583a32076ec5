/**
 * DICOM files made byte by byte for the tests of issue 25's items and the fuzz suite: a
 * Modality LUT Sequence and an enhanced multi-frame file with two stacks, two time
 * points, shared and per-frame rescale, pixel measures and plane position/orientation
 * (the way pydicom-data's mlut_18.dcm and eCT_Supplemental.dcm and nibabel's
 * 4d_multiframe_test.dcm are made).
 */
import { dicomElement, dicomFile, dicomSequence, dicomText, uints, type DicomMode, type DicomSpec } from './helpers.js';

export const AXIAL = [1, 0, 0, 0, 1, 0];

/** A LUT item: descriptor [entries, first mapped, bits] and the table, as mlut_18.dcm has. */
export const modalityLutSequence = (entries: number, first: number, table: number[]) => (mode: DicomMode) => [
  dicomSequence(
    0x28,
    0x3000,
    [
      [
        dicomElement(0x28, 0x3002, 'US', uints([entries, first, 16], 2, mode.little), mode),
        dicomElement(0x28, 0x3004, 'LO', dicomText('HU'), mode),
        dicomElement(0x28, 0x3006, 'OW', uints(table, 2, mode.little), mode),
      ],
    ],
    mode,
  ),
];

const rows = 2;
const cols = 3;
const plane = rows * cols;
const ds = (x: number[]) => dicomText(x.join('\\'));
interface Frame {
  stack: string;
  pos: number; // in-stack position
  time: number;
  z: number;
  iop?: number[];
  rescale?: [number, number];
}
// Stack 1: three positions × two time points, out of order; stack 2: one sagittal frame.
const frames: Frame[] = [
  { stack: '1', pos: 2, time: 1, z: 12 },
  { stack: '1', pos: 1, time: 2, z: 9.5 },
  { stack: '1', pos: 3, time: 1, z: 14.5 },
  { stack: '2', pos: 1, time: 1, z: 0, iop: [0, 1, 0, 0, 0, -1] },
  { stack: '1', pos: 1, time: 1, z: 9.5, rescale: [2, -10] },
  { stack: '1', pos: 2, time: 2, z: 12 },
  { stack: '1', pos: 3, time: 2, z: 14.5 },
];
const stored = new Uint16Array(frames.length * plane).map((_, i) => 1000 + i);
const SHARED_RESCALE: [number, number] = [1, -1024];

export function enhancedFile(syntax: DicomSpec['syntax'] = 'explicit-le'): Uint8Array {
  return dicomFile({
    syntax,
    rows,
    cols,
    pixels: stored,
    frames: frames.length,
    extra: (mode) => {
      const at = (g: number, e: number) => uints([g, e], 2, mode.little);
      const el = dicomElement;
      const dimension = (g: number, e: number) => [
        el(0x20, 0x9165, 'AT', at(g, e), mode),
        el(0x20, 0x9167, 'AT', at(0x20, 0x9111), mode),
      ];
      const pvt = ([slope, inter]: [number, number]) =>
        dicomSequence(
          0x28,
          0x9145,
          [
            [
              el(0x28, 0x1052, 'DS', dicomText(String(inter)), mode),
              el(0x28, 0x1053, 'DS', dicomText(String(slope)), mode),
            ],
          ],
          mode,
        );
      return [
        // Dimension Index Sequence: StackID, InStackPositionNumber, TemporalPositionIndex.
        dicomSequence(0x20, 0x9222, [dimension(0x20, 0x9056), dimension(0x20, 0x9057), dimension(0x20, 0x9128)], mode),
        dicomSequence(
          0x5200,
          0x9229,
          [
            [
              dicomSequence(0x20, 0x9116, [[el(0x20, 0x37, 'DS', ds(AXIAL), mode)]], mode),
              dicomSequence(
                0x28,
                0x9110,
                [
                  [
                    el(0x18, 0x50, 'DS', dicomText('2.5'), mode),
                    el(0x28, 0x30, 'DS', ds([0.5, 0.25]), mode), // row spacing \ column spacing
                  ],
                ],
                mode,
              ),
              pvt(SHARED_RESCALE),
            ],
          ],
          mode,
        ),
        dicomSequence(
          0x5200,
          0x9230,
          frames.map((f) => [
            dicomSequence(
              0x20,
              0x9111,
              [
                [
                  el(0x20, 0x9056, 'SH', dicomText(f.stack), mode),
                  el(0x20, 0x9057, 'UL', uints([f.pos], 4, mode.little), mode),
                  el(0x20, 0x9128, 'UL', uints([f.time], 4, mode.little), mode),
                  el(0x20, 0x9157, 'UL', uints([Number(f.stack), f.pos, f.time], 4, mode.little), mode),
                ],
              ],
              mode,
            ),
            dicomSequence(0x20, 0x9113, [[el(0x20, 0x32, 'DS', ds([-20, 30, f.z]), mode)]], mode),
            ...(f.iop ? [dicomSequence(0x20, 0x9116, [[el(0x20, 0x37, 'DS', ds(f.iop), mode)]], mode)] : []),
            ...(f.rescale ? [pvt(f.rescale)] : []),
          ]),
          mode,
        ),
      ];
    },
  });
}

/** The enhanced file and what it was made from. */
export const ENHANCED = { bytes: enhancedFile(), frames, stored, plane, rows, cols, SHARED_RESCALE };
