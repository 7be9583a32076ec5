/**
 * Orientation helpers shared by NIfTI, NRRD and DICOM: a 3×3 row-major matrix whose
 * columns are unit world directions of the index axes.
 */

/** Normalize the three columns of a row-major 3×3 (or the 3×3 block of a 4×4 given as rows). Null when a column is zero or not finite. */
export function directionCosines(columns: number[][]): { orientation: number[]; lengths: number[] } | null {
  const lengths = columns.map((c) => Math.hypot(c[0], c[1], c[2]));
  if (lengths.some((l) => !Number.isFinite(l) || l === 0)) return null;
  const o = new Array<number>(9);
  for (let r = 0; r < 3; r++) for (let c = 0; c < 3; c++) o[3 * r + c] = columns[c][r] / lengths[c];
  return { orientation: o, lengths };
}

/**
 * Axis codes ('LAS', 'RAS', 'LPS'…) of an orientation in a RAS+ world: for each index axis
 * the world axis it runs closest to, and which way (nibabel's aff2axcodes convention).
 */
export function axisCodes(orientation: readonly number[], space: 'RAS' | 'LPS' = 'RAS'): string {
  const pos = space === 'RAS' ? ['R', 'A', 'S'] : ['L', 'P', 'S'];
  const neg = space === 'RAS' ? ['L', 'P', 'I'] : ['R', 'A', 'I'];
  let codes = '';
  for (let c = 0; c < 3; c++) {
    let best = 0;
    for (let r = 1; r < 3; r++) if (Math.abs(orientation[3 * r + c]) > Math.abs(orientation[3 * best + c])) best = r;
    codes += orientation[3 * best + c] >= 0 ? pos[best] : neg[best];
  }
  return codes;
}

export function isFiniteVector(v: readonly number[]): boolean {
  return v.every((x) => Number.isFinite(x));
}

// orientationFromAxisCodes lives in core (scene/axis-codes.ts): the viewer's camera fit reads axis codes too.
export { orientationFromAxisCodes } from '@vpt/core';
