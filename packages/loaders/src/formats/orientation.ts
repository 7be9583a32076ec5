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

/**
 * The orientation (3×3 row-major, RAS+ world) of axis codes like 'PIR': for each index
 * axis the world direction it runs toward (R/L, A/P, S/I). Null unless the three letters
 * name three different world axes.
 */
export function orientationFromAxisCodes(codes: string): number[] | null {
  const DIRS: Record<string, [number, number]> = {
    R: [0, 1],
    L: [0, -1],
    A: [1, 1],
    P: [1, -1],
    S: [2, 1],
    I: [2, -1],
  };
  if (typeof codes !== 'string' || codes.length !== 3) return null;
  const o = new Array<number>(9).fill(0);
  const used = new Set<number>();
  for (let c = 0; c < 3; c++) {
    const d = DIRS[codes[c].toUpperCase()];
    if (!d || used.has(d[0])) return null;
    used.add(d[0]);
    o[3 * d[0] + c] = d[1];
  }
  return o;
}
