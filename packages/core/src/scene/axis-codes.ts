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
