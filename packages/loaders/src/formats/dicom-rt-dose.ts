/**
 * RT Dose (PS3.3 C.8.8.3): the stored values times Dose Grid Scaling (3004,000E) are the
 * dose in Dose Units, and a multi-frame grid's frames lie at the Grid Frame Offset Vector
 * (3004,000C) along the slice normal from ImagePositionPatient, when the Frame Increment
 * Pointer (0028,0009) names it.
 */
import { finite, reader, type DataSet } from './dicom-elements.js';

export interface DoseGrid {
  /** Dose Grid Scaling, a factor on the rescaled values. */
  scale?: number;
  /** Offset of each frame along the normal (mm), one per frame. */
  frameOffsets?: number[];
}

export function readDoseGrid(ds: DataSet, frames: number): DoseGrid {
  const r = reader(ds);
  const scale = r.num('x3004000e');
  const out: DoseGrid = {};
  if (finite(scale) && scale > 0) out.scale = scale;
  const pointer = ds.elements.x00280009;
  const pointsAtOffsets = pointer && r.u16('x00280009', 0) === 0x3004 && r.u16('x00280009', 1) === 0x000c;
  if (frames > 1 && pointsAtOffsets) {
    const offsets: number[] = [];
    for (let i = 0; i < frames; i++) {
      const v = r.num('x3004000c', i);
      if (!finite(v)) return out;
      offsets.push(v);
    }
    out.frameOffsets = offsets;
  }
  return out;
}
