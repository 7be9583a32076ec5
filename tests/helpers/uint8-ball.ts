/**
 * A uint8 cube of side `side` (x fastest) holding a cone-profile ball: `peak` at `centre`,
 * falling linearly to 0 at `radius` voxels. The viewer tests write these as files (raw, NIfTI,
 * NRRD) so that each step or channel is a different, known image.
 */
export function uint8Ball(side: number, centre: [number, number, number], radius: number, peak = 255): Uint8Array {
  const v = new Uint8Array(side ** 3);
  for (let z = 0; z < side; z++)
    for (let y = 0; y < side; y++)
      for (let x = 0; x < side; x++) {
        const d = Math.hypot(x - centre[0], y - centre[1], z - centre[2]);
        v[x + side * (y + side * z)] = Math.max(0, Math.round(peak * (1 - d / radius)));
      }
  return v;
}

/**
 * Two uint8 fields on one ball of radius 24 voxels at the centre of a cube of side `side` that is
 * exactly 0 outside it (so whole bricks there are constant): a smooth fall-off and a rippled
 * rise. The 2-channel bricking tests stream these as a store's channels.
 */
export function twoFieldBall(side: number): [Uint8Array, Uint8Array] {
  const a = new Uint8Array(side ** 3),
    b = new Uint8Array(side ** 3);
  const c = (side - 1) / 2;
  for (let z = 0; z < side; z++)
    for (let y = 0; y < side; y++)
      for (let x = 0; x < side; x++) {
        const r = Math.hypot(x - c, y - c, z - c) / 24;
        if (r >= 1) continue;
        const i = x + side * (y + side * z);
        a[i] = Math.round(40 + 215 * (1 - r * r));
        b[i] = Math.round(40 + 215 * r * (1 + 0.3 * Math.sin(x / 3)) * 0.75);
      }
  return [a, b];
}
