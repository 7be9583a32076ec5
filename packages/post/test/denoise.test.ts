import { describe, expect, it } from 'vitest';
import { isVptError } from '@vpt/core';
import { DENOISE_DEFAULTS, DenoiseStep, denoiseRef, postStepFromJSON, postStepToJSON } from '../src/index.js';

function expectInvalid(f: () => unknown, pattern: RegExp) {
  try {
    f();
  } catch (e) {
    expect(isVptError(e) && e.code === 'invalid-scene').toBe(true);
    expect((e as Error).message).toMatch(pattern);
    return;
  }
  throw new Error('expected a VptError');
}

describe('denoise step parameters', () => {
  it('refuses bad values with a typed error naming the field and the rule', () => {
    expectInvalid(() => new DenoiseStep({ iterations: 0 }), /iterations must lie in \[1, 10\]/);
    expectInvalid(() => new DenoiseStep({ iterations: 2.5 }), /iterations must be an integer/);
    expectInvalid(() => new DenoiseStep({ colorSigma: NaN }), /colorSigma must be a finite number/);
    expectInvalid(() => new DenoiseStep({ albedoSigma: 0 }), /albedoSigma must lie in/);
    expectInvalid(() => new DenoiseStep({ depthEpsilon: -1 }), /depthEpsilon must lie in/);
    expectInvalid(() => new DenoiseStep({ colorSigmaDecay: 2 }), /colorSigmaDecay must lie in/);
    expectInvalid(() => postStepFromJSON({ type: 'denoise', sigma: 1 }), /unknown field "sigma"/);
    expectInvalid(() => postStepFromJSON({ type: 'denoise', iterations: '5' }), /iterations must be a finite number/);
  });

  it('round-trips through JSON with the defaults filled in', () => {
    const step = postStepFromJSON({ type: 'denoise', iterations: 3 });
    expect(step).toBeInstanceOf(DenoiseStep);
    expect(postStepToJSON(step)).toEqual({ type: 'denoise', ...DENOISE_DEFAULTS, iterations: 3 });
    expect(step.repeat).toBe(3);
    expect(step.usesGuides).toBe(true);
  });

  it('draw i steps 2^i pixels; disabled, it is one pass-through draw', () => {
    const step = new DenoiseStep();
    expect([0, 1, 4].map((i) => step.uniformValues(i).stepWidth)).toEqual([1, 2, 16]);
    step.enabled = false;
    expect(step.repeat).toBe(1);
    expect(step.uniformValues(0).passThrough).toBe(1);
  });
});

describe('denoiseRef (CPU twin)', () => {
  const W = 9,
    H = 7;
  const flat = (f: (x: number, y: number) => number[]) => {
    const a = new Float64Array(W * H * 4);
    for (let y = 0; y < H; y++) for (let x = 0; x < W; x++) a.set(f(x, y), 4 * (y * W + x));
    return a;
  };
  const noGuides = { normalDepth: flat(() => [0, 0, 0, 0]), albedo: flat(() => [0, 0, 0, 0]) };

  it('leaves an image whose variance is 0 unchanged and finite, also without guides', () => {
    const image = flat((x, y) => [x / W, y / H, 0.5, 1]);
    const l = (x: number, y: number) => 0.2126 * (x / W) + 0.7152 * (y / H) + 0.0722 * 0.5;
    const moments = flat((x, y) => [l(x, y), l(x, y) ** 2, 16, 0]);
    const out = denoiseRef({ width: W, height: H, image, moments, ...noGuides });
    for (let i = 0; i < out.length; i++) expect(out[i]).toBeCloseTo(image[i], 9);
  });

  it('averages pure noise towards its mean where the variance says it is noise', () => {
    let s = 1;
    const rnd = () => ((s = (s * 16807) % 2147483647) / 2147483647) * 2 - 1;
    const image = flat(() => {
      const v = 0.5 + 0.1 * rnd();
      return [v, v, v, 1];
    });
    // Moments of 4 samples with standard deviation 0.2 each: variance of the mean 0.01.
    const moments = flat(() => [0.5, 0.25 + 0.04 * (3 / 4), 4, 0]);
    const out = denoiseRef({ width: W, height: H, image, moments, ...noGuides });
    const dev = (a: ArrayLike<number>) => {
      let sq = 0;
      for (let i = 0; i < W * H; i++) sq += (a[4 * i] - 0.5) ** 2;
      return Math.sqrt(sq / (W * H));
    };
    expect(dev(out)).toBeLessThan(0.5 * dev(image));
  });

  it('fades as the error of the mean falls: each level moves a pixel by at most min(1, error / fadeError) of the range', () => {
    let s = 3;
    const rnd = () => ((s = (s * 16807) % 2147483647) / 2147483647) * 2 - 1;
    const image = flat(() => {
      const v = 0.5 + 0.1 * rnd();
      return [v, v, v, 1];
    });
    // 10 000 samples with standard deviation 0.2: the mean's standard error 0.002, 0.4 % of 0.5.
    const n = 10000;
    const moments = flat(() => [0.5, 0.25 + 0.04 * ((n - 1) / n), n, 0]);
    const fadeError = DENOISE_DEFAULTS.fadeError;
    const fade = Math.min(Math.sqrt((0.04 * ((n - 1) / n)) / (n - 1)) / (fadeError * 0.5), 1);
    const out = denoiseRef({ width: W, height: H, image, moments, ...noGuides });
    let lo = Infinity,
      hi = -Infinity,
      moved = 0;
    for (let i = 0; i < W * H; i++) {
      lo = Math.min(lo, image[4 * i]);
      hi = Math.max(hi, image[4 * i]);
    }
    for (let i = 0; i < W * H; i++) moved = Math.max(moved, Math.abs(out[4 * i] - image[4 * i]));
    // Every level's filtered value is a convex combination of the image's, so it moves by at most the range.
    expect(moved).toBeGreaterThan(0);
    expect(moved).toBeLessThanOrEqual(DENOISE_DEFAULTS.iterations * fade * (hi - lo) + 1e-12);
    expect(moved).toBeLessThan(0.25 * (hi - lo));
  });
});
