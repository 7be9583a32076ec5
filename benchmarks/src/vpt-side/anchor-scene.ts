/**
 * The anchor scene of the side-by-side comparison with the original VPT (Lesar, Bohak,
 * Marolt 2018; a build of terier/vpt given by path, never stored here): a procedural 8-bit
 * volume in the unit cube, a TF whose opacity is the normalized value and whose albedo is
 * warm, a perspective camera at z = 1.5 looking down −z with fovy 1 rad, and a lat-long sky
 * whose radiance depends on the direction's height only. docs/benchmarks.md ("Side by side
 * with VPT") describes the method. Node side: the voxels are made here and served to the
 * page, so both renderers read the same bytes. The benchmark page (page-code.ts) imports
 * the same functions for its `kind: 'anchor'` scene, so this module must run in a browser too.
 */

/** An integer hash of a lattice point to [0, 1) (three odd multipliers, then two xor-shift-multiply rounds). */
function latticeHash(i: number, j: number, k: number): number {
  let h = (Math.imul(i, 0x8da6b343) ^ Math.imul(j, 0xd8163841) ^ Math.imul(k, 0xcb1ab31f)) >>> 0;
  h = Math.imul(h ^ (h >>> 16), 0x7feb352d) >>> 0;
  h = Math.imul(h ^ (h >>> 15), 0x846ca68b) >>> 0;
  return ((h ^ (h >>> 16)) >>> 0) / 4294967296;
}

const fade = (t: number) => t * t * (3 - 2 * t);

/** Value noise: the lattice hashes blended trilinearly with smoothstep weights. */
function valueNoise(x: number, y: number, z: number): number {
  const x0 = Math.floor(x),
    y0 = Math.floor(y),
    z0 = Math.floor(z);
  const fx = fade(x - x0),
    fy = fade(y - y0),
    fz = fade(z - z0);
  let sum = 0;
  for (let corner = 0; corner < 8; corner++) {
    const dx = corner & 1,
      dy = (corner >> 1) & 1,
      dz = (corner >> 2) & 1;
    const w = (dx ? fx : 1 - fx) * (dy ? fy : 1 - fy) * (dz ? fz : 1 - fz);
    sum += w * latticeHash(x0 + dx, y0 + dy, z0 + dz);
  }
  return sum;
}

/** Four octaves of value noise, normalized to [0, 1]. */
function fractalNoise(x: number, y: number, z: number): number {
  let sum = 0,
    amplitude = 0.5,
    frequency = 1,
    norm = 0;
  for (let octave = 0; octave < 4; octave++) {
    sum += amplitude * valueNoise(x * frequency, y * frequency, z * frequency);
    norm += amplitude;
    amplitude *= 0.5;
    frequency *= 2;
  }
  return sum / norm;
}

function smoothstep(e0: number, e1: number, x: number): number {
  const t = Math.min(Math.max((x - e0) / (e1 - e0), 0), 1);
  return t * t * (3 - 2 * t);
}

/**
 * Density in [0, 1] at a point of the unit cube [0, 1]³: a noisy torus (radii 0.27, 0.085)
 * tilted 60° about x, a Gaussian core, the lower half of a thin noisy spherical shell and a
 * faint haze inside the bounding sphere. Mean over a 128³ grid ≈ 11.5/255.
 */
export function anchorDensity(px: number, py: number, pz: number): number {
  const qx = px - 0.5,
    qy = py - 0.5,
    qz = pz - 0.5;
  const c = Math.cos(Math.PI / 3),
    s = Math.sin(Math.PI / 3);
  const ty = c * qy - s * qz,
    tz = s * qy + c * qz;
  const torusDistance = Math.hypot(Math.hypot(qx, tz) - 0.27, ty) - 0.085;
  const n = fractalNoise(px * 5 + 11.3, py * 5 + 7.1, pz * 5 + 3.7);
  const torus = smoothstep(0.02, -0.02, torusDistance) * (0.55 + 0.45 * n);
  const gx = qx - 0.05,
    gy = qy + 0.04,
    gz = qz - 0.02;
  const core = 0.9 * Math.exp(-(gx * gx + gy * gy + gz * gz) / (2 * 0.07 * 0.07));
  const r = Math.hypot(qx, qy, qz);
  const bowl = 0.12 * smoothstep(0.015, -0.015, Math.abs(r - 0.42) - 0.02) * smoothstep(0.1, -0.05, qy) * (0.4 + n);
  const haze = 0.015 * (0.5 + n) * smoothstep(0.48, 0.4, r);
  return Math.min(Math.max(Math.max(torus, core, bowl) + haze, 0), 1);
}

/** N³ uint8 voxels, x fastest: round(255 · density at the voxel centre). */
export function anchorVolume(n: number): Uint8Array {
  const data = new Uint8Array(n * n * n);
  let i = 0;
  for (let z = 0; z < n; z++)
    for (let y = 0; y < n; y++)
      for (let x = 0; x < n; x++)
        data[i++] = Math.round(255 * anchorDensity((x + 0.5) / n, (y + 0.5) / n, (z + 0.5) / n));
  return data;
}

/** Sky radiance for a direction of height `up` (= d.y): dim at the nadir, 1 at the zenith. */
export const skyRadiance = (up: number) => 0.05 + 0.95 * ((1 + up) / 2) ** 2;

/** Rows of VPT's sky texture (RGBA8, 128 rows, row 0 = zenith; v = acos(d.y)/π on both renderers). */
export const VPT_SKY_ROWS = 128;
/** The linear albedo of the TF; VPT stores it as sRGB bytes. */
export const ANCHOR_ALBEDO: readonly [number, number, number] = [1, 0.85, 0.7];
/** VPT's extinction and vpt's densityScale in the unit box. */
export const ANCHOR_EXTINCTION = 100;
export const ANCHOR_CAMERA_Z = 1.5;
export const ANCHOR_FOVY = 1;
