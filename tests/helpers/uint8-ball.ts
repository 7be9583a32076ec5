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
