/**
 * CPU twin of the denoise step (denoise.glsl.ts), in float64: the same edge-avoiding à-trous
 * levels (Dammertz et al. 2010, Sec. 3) with the same weights and variance filtering (SVGF,
 * Schied et al. 2017, Sec. 4.4) and the same fade, written from the formulas for tests that check
 * the kernels within float tolerance.
 */
import { DENOISE_DEFAULTS, type DenoiseParams } from './denoise.js';

/** RGBA float images, top row first, as the context's guide textures hold them. */
export interface DenoiseInputs {
  width: number;
  height: number;
  image: ArrayLike<number>;
  /** (mean normal, mean depth of hits × hit fraction). */
  normalDepth: ArrayLike<number>;
  /** (mean albedo, hit fraction). */
  albedo: ArrayLike<number>;
  /** (mean luminance, mean squared luminance, sample count, 0). */
  moments: ArrayLike<number>;
}

const B3 = [3 / 8, 1 / 4, 1 / 16];
const luminance = (a: ArrayLike<number>, i: number) =>
  0.2126 * a[4 * i] + 0.7152 * a[4 * i + 1] + 0.0722 * a[4 * i + 2];

/** All levels of the filter; returns the RGBA result. */
export function denoiseRef(inputs: DenoiseInputs, params: DenoiseParams = {}): Float64Array {
  const p = { ...DENOISE_DEFAULTS, ...params };
  let image: ArrayLike<number> = inputs.image;
  let variance: Float64Array | null = null;
  for (let level = 0; level < p.iterations; level++)
    ({ image, variance } = denoiseLevelRef(inputs, image, variance, level, p));
  return image as Float64Array;
}

function denoiseLevelRef(
  g: DenoiseInputs,
  image: ArrayLike<number>,
  prevVariance: Float64Array | null,
  level: number,
  p: Required<DenoiseParams>,
): { image: Float64Array; variance: Float64Array } {
  const { width: W, height: H } = g;
  const out = new Float64Array(W * H * 4);
  const at = (x: number, y: number) => y * W + x;
  const clampX = (x: number) => Math.min(Math.max(x, 0), W - 1);
  const clampY = (y: number) => Math.min(Math.max(y, 0), H - 1);
  const depth = (i: number) => (g.albedo[4 * i + 3] > 0 ? g.normalDepth[4 * i + 3] / g.albedo[4 * i + 3] : 0);
  const momentVariance = (i: number) =>
    Math.max(g.moments[4 * i + 1] - g.moments[4 * i] ** 2, 0) / Math.max(g.moments[4 * i + 2] - 1, 1);
  const step = 2 ** level;
  // The variance each tap filters: the moments' at level 0 (the 3x3 spatial variance of the luminance
  // after one sample), then the previous level's filtered variance.
  const levelVariance = new Float64Array(W * H);
  for (let y = 0; y < H; y++)
    for (let x = 0; x < W; x++) {
      const i = at(x, y);
      if (level > 0 && prevVariance) levelVariance[i] = prevVariance[i];
      else if (g.moments[4 * i + 2] >= 2) levelVariance[i] = momentVariance(i);
      else {
        let s1 = 0,
          s2 = 0;
        for (let dy = -1; dy <= 1; dy++)
          for (let dx = -1; dx <= 1; dx++) {
            const l = luminance(image, at(clampX(x + dx), clampY(y + dy)));
            s1 += l;
            s2 += l * l;
          }
        levelVariance[i] = Math.max(s2 / 9 - (s1 / 9) ** 2, 0);
      }
    }
  const variance = new Float64Array(W * H);
  for (let y = 0; y < H; y++) {
    for (let x = 0; x < W; x++) {
      const ip = at(x, y);
      // σ_l's variance: the level's under a 3x3 binomial filter.
      let v = 0,
        vw = 0;
      for (let dy = -1; dy <= 1; dy++)
        for (let dx = -1; dx <= 1; dx++) {
          const w = (2 - Math.abs(dx)) * (2 - Math.abs(dy));
          v += w * levelVariance[at(clampX(x + dx), clampY(y + dy))];
          vw += w;
        }
      v /= vw;
      const sigmaL = p.colorSigma * p.colorSigmaDecay ** level * Math.sqrt(v) + 1e-10;
      const lp = luminance(image, ip);
      const np = g.normalDepth.length
        ? Math.hypot(g.normalDepth[4 * ip], g.normalDepth[4 * ip + 1], g.normalDepth[4 * ip + 2])
        : 0;
      const zp = depth(ip);
      const dzx = (depth(at(clampX(x + 1), y)) - depth(at(clampX(x - 1), y))) * 0.5;
      const dzy = (depth(at(x, clampY(y + 1))) - depth(at(x, clampY(y - 1)))) * 0.5;
      const sum = [0, 0, 0, 0];
      let weights = 0,
        varSum = 0;
      for (let ky = -2; ky <= 2; ky++)
        for (let kx = -2; kx <= 2; kx++) {
          const qx = x + kx * step,
            qy = y + ky * step;
          if (qx < 0 || qy < 0 || qx >= W || qy >= H) continue;
          const iq = at(qx, qy);
          const h = B3[Math.abs(kx)] * B3[Math.abs(ky)];
          const wl = Math.exp(-Math.abs(luminance(image, iq) - lp) / sigmaL);
          const wz = Math.exp(
            -Math.abs(depth(iq) - zp) / (p.depthSigma * Math.abs(dzx * (qx - x) + dzy * (qy - y)) + p.depthEpsilon),
          );
          const nq = Math.hypot(g.normalDepth[4 * iq], g.normalDepth[4 * iq + 1], g.normalDepth[4 * iq + 2]);
          let wn = 1;
          if (np > 1e-3 && nq > 1e-3) {
            let d = 0;
            for (let c = 0; c < 3; c++) d += g.normalDepth[4 * ip + c] * g.normalDepth[4 * iq + c];
            d /= np * nq;
            wn = d > 0 ? Math.min(d, 1) ** p.normalSigma : 0;
          }
          let da = 0;
          for (let c = 0; c < 4; c++) da += (g.albedo[4 * iq + c] - g.albedo[4 * ip + c]) ** 2;
          const wa = Math.exp(-da / (p.albedoSigma * p.albedoSigma));
          const w = h * wl * wz * wn * wa;
          for (let c = 0; c < 4; c++) sum[c] += w * image[4 * iq + c];
          weights += w;
          varSum += w * w * levelVariance[iq];
        }
      // The fade: the change scaled by min(1, relative standard error of the mean / fadeError).
      const m0 = g.moments[4 * ip];
      const fade =
        g.moments[4 * ip + 2] >= 2
          ? Math.min(Math.sqrt(momentVariance(ip)) / (p.fadeError * Math.max(Math.abs(m0), 1e-6)), 1)
          : 1;
      for (let c = 0; c < 4; c++) out[4 * ip + c] = image[4 * ip + c] + (sum[c] / weights - image[4 * ip + c]) * fade;
      variance[ip] = varSum / (weights * weights);
    }
  }
  return { image: out, variance };
}
