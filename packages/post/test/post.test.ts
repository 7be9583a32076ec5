import { describe, expect, it } from 'vitest';
import { isVptError } from '@vpt/core';
import {
  ExposureStep,
  SrgbEncodeStep,
  TONE_MAP_OPERATORS,
  ToneMapStep,
  acesRef,
  defaultPostChain,
  exposureRef,
  postChainFromJSON,
  postChainRef,
  postChainToJSON,
  postStepFromJSON,
  postStepToJSON,
  srgbEncodeRef,
  srgbOetfRef,
  toneMapRef,
} from '../src/index.js';

const grey = (v: number) => [v, v, v] as const;

describe('CPU references', () => {
  it('exposure scales by 2^stops', () => {
    expect(exposureRef(0, [0.1, 2, 3])).toEqual([0.1, 2, 3]);
    expect(exposureRef(1, [0.25, 1, 4])).toEqual([0.5, 2, 8]);
    expect(exposureRef(-2, [1, 8, 0])).toEqual([0.25, 2, 0]);
  });

  it('sRGB OETF matches IEC 61966-2-1 values', () => {
    expect(srgbOetfRef(0)).toBe(0);
    expect(srgbOetfRef(1)).toBeCloseTo(1, 15);
    // The linear toe: 12.92 x.
    expect(srgbOetfRef(0.001)).toBeCloseTo(0.01292, 15);
    // Both pieces meet at the threshold: 12.92 * 0.0031308 = 0.04044994 ≈ 0.04045.
    expect(srgbOetfRef(0.0031308)).toBeCloseTo(0.04045, 6);
    expect(1.055 * 0.0031308 ** (1 / 2.4) - 0.055).toBeCloseTo(0.04045, 6);
    // Mid grey and 0.5 (values computed independently: 1.055 * 0.5^(1/2.4) - 0.055).
    expect(srgbOetfRef(0.5)).toBeCloseTo(0.7353569830524495, 12);
    expect(srgbOetfRef(0.18)).toBeCloseTo(0.4613561295004, 10);
    // Out-of-range input is clamped first.
    expect(srgbOetfRef(-3)).toBe(0);
    expect(srgbOetfRef(7)).toBeCloseTo(1, 15);
    expect(srgbEncodeRef([0, 0.5, 2])).toEqual([0, srgbOetfRef(0.5), srgbOetfRef(1)]);
  });

  it('sRGB OETF is monotonic across the threshold', () => {
    let prev = -1;
    for (let i = 0; i <= 2000; i++) {
      const y = srgbOetfRef(0.003 + i * 1e-7);
      expect(y).toBeGreaterThan(prev);
      prev = y;
    }
  });

  it('Reinhard is c / (1 + c)', () => {
    expect(toneMapRef('reinhard', [0, 1, 3])).toEqual([0, 0.5, 0.75]);
    expect(toneMapRef('reinhard', grey(1e30))[0]).toBeCloseTo(1, 12);
  });

  it('ACES fit: 0 → 0, 1 → ~0.8, monotonic, saturates at 1', () => {
    expect(acesRef(0)).toBe(0);
    // Narkowicz: "1 on input maps to ~0.8 on output": 2.54 / 3.16.
    expect(acesRef(1)).toBeCloseTo(2.54 / 3.16, 14);
    let prev = -1;
    for (let i = 0; i <= 4000; i++) {
      const y = acesRef(i * 0.005);
      expect(y).toBeGreaterThanOrEqual(prev);
      expect(y).toBeLessThanOrEqual(1);
      prev = y;
    }
    // The curve reaches 1 at x = (0.56 + sqrt(0.56² + 4·0.08·0.14)) / 0.16 ≈ 7.2418.
    expect(acesRef(7.2)).toBeLessThan(1);
    expect(acesRef(7.3)).toBe(1);
    expect(acesRef(1e4)).toBe(1);
    expect(acesRef(1e30)).toBe(1);
  });

  it('PBR Neutral follows the Khronos specification', () => {
    // Below the toe threshold (min < 0.08) the offset is x - x²/(4·0.04); above it, 0.04.
    const x = 0.05;
    expect(toneMapRef('pbr-neutral', grey(x))[0]).toBeCloseTo(x * x * 6.25, 15);
    // Peaks below 0.76 after the offset are only shifted: hue (differences between channels) is kept.
    const c = toneMapRef('pbr-neutral', [0.7, 0.3, 0.1]);
    expect(c[0]).toBeCloseTo(0.66, 15);
    expect(c[1]).toBeCloseTo(0.26, 15);
    expect(c[2]).toBeCloseTo(0.06, 15);
    expect(c[0] - c[1]).toBeCloseTo(0.4, 15);
    // At the compression start the curve is continuous: p = Ks gives p_n = Ks and g = 1 in the spec.
    expect(toneMapRef('pbr-neutral', grey(0.8 - 1e-12))[0]).toBeCloseTo(0.76, 10);
    expect(toneMapRef('pbr-neutral', grey(0.8 + 1e-12))[0]).toBeCloseTo(0.76, 10);
    // Compression: greys map to p_n = 1 - (1 - Ks)² / (p + 1 - 2 Ks) with p = v - 0.04.
    const v = 3;
    const p = v - 0.04;
    const pn = 1 - (0.24 * 0.24) / (p + 1 - 2 * 0.76);
    const out = toneMapRef('pbr-neutral', grey(v));
    out.forEach((o) => expect(o).toBeCloseTo(pn, 14));
    // Bright saturated colours desaturate toward white and stay ≤ 1.
    const hot = toneMapRef('pbr-neutral', [100, 10, 1]);
    hot.forEach((o) => expect(o).toBeLessThanOrEqual(1));
    expect(hot[2] / hot[0]).toBeGreaterThan(1 / 100);
    expect(toneMapRef('pbr-neutral', grey(1e30))[0]).toBeCloseTo(1, 12);
  });

  it('every operator treats negative input as 0 and maps into [0, 1]', () => {
    for (const op of TONE_MAP_OPERATORS) {
      expect(toneMapRef(op, [-1, -1e-3, 0])).toEqual([0, 0, 0]);
      for (const v of [0, 1e-4, 0.18, 1, 4, 1e4, 1e30]) {
        for (const o of toneMapRef(op, [v, v / 2, v / 10])) {
          expect(o).toBeGreaterThanOrEqual(0);
          expect(o).toBeLessThanOrEqual(1 + 1e-12);
        }
      }
    }
    expect(toneMapRef('clamp', [0.25, 1, 5])).toEqual([0.25, 1, 1]);
  });

  it('postChainRef composes the steps', () => {
    const chain = defaultPostChain({ exposure: 1, toneMapper: 'reinhard' });
    expect(postChainRef(chain, [0.5, 0, 1])).toEqual(
      srgbEncodeRef(toneMapRef('reinhard', exposureRef(1, [0.5, 0, 1]))),
    );
    expect(postChainRef(chain, [0.5, 0, 1])[0]).toBeCloseTo(srgbOetfRef(0.5), 15);
  });

  it('a display-referred image is shown as it is: exposure and a clamp, whatever the tone mapper', () => {
    const chain = defaultPostChain({ exposure: 0, toneMapper: 'aces', displayReferred: true });
    expect(postChainToJSON(chain)).toEqual([
      { type: 'exposure', exposure: 0 },
      { type: 'tonemap', operator: 'clamp' },
    ]);
    expect(postChainRef(chain, [0.25, 0.5, 1.5])).toEqual([0.25, 0.5, 1]);
  });
});

describe('steps', () => {
  it('exposure packs 2^stops into its uniform', () => {
    const s = new ExposureStep(3);
    const packed = new Float32Array(s.uniforms.pack(s.uniformValues()));
    expect(packed[0]).toBe(8);
    s.exposure = -1;
    expect(new Float32Array(s.uniforms.pack(s.uniformValues()))[0]).toBe(0.5);
    expect(() => {
      s.exposure = NaN;
    }).toThrow(/finite/);
    expect(() => new ExposureStep(Infinity)).toThrow(/finite/);
    expect(() => new ExposureStep(200)).toThrow(/64/);
  });

  it('exposure keeps any finite input, and so any chain of steps within ±64 stops, within f32 (issue 28)', () => {
    const F32_MAX = 3.4028234663852886e38;
    for (const stops of [64, 17.5, 0, -64]) {
      const [scale, limit] = new Float32Array(
        new ExposureStep(stops).uniforms.pack(new ExposureStep(stops).uniformValues()),
      );
      // What the kernel computes, in f32: clamp(x, -limit, limit) * scale for the largest finite x.
      const out = Math.fround(Math.fround(Math.min(F32_MAX, limit)) * scale);
      expect(Number.isFinite(limit)).toBe(true);
      expect(Number.isFinite(out)).toBe(true);
      // ...and large enough that every tone mapper sees white.
      for (const op of TONE_MAP_OPERATORS) expect(toneMapRef(op, [out, out, out])[0]).toBeCloseTo(1, 6);
    }
  });

  it('every layout has at least one field (WGSL forbids empty structs)', () => {
    for (const s of [new ExposureStep(), new ToneMapStep(), new SrgbEncodeStep()]) {
      expect(s.uniforms.fields.length).toBeGreaterThan(0);
      expect(() => s.uniforms.pack(s.uniformValues())).not.toThrow();
    }
  });

  it('tone map variants differ only by define, and each variant holds only its operator in both languages', () => {
    const ids = new Set<number>();
    for (const op of TONE_MAP_OPERATORS) {
      const s = new ToneMapStep(op);
      const d = s.defines();
      expect(Object.keys(d)).toEqual(['TONEMAP_OPERATOR']);
      ids.add(d.TONEMAP_OPERATOR as number);
      expect(s.wgsl.match(/fn toneMap\(/g)).toHaveLength(1);
      expect(s.glsl.match(/vec3 toneMap\(/g)).toHaveLength(1);
      expect(s.glsl + s.wgsl).not.toMatch(/#(if|elif|else|endif)\b/);
    }
    expect(ids.size).toBe(TONE_MAP_OPERATORS.length);
    expect(new ToneMapStep('aces').wgsl).toContain('2.51');
    expect(new ToneMapStep('reinhard').wgsl).not.toContain('2.51');
    expect(new ToneMapStep('reinhard').glsl).not.toContain('2.51');
    expect(new ToneMapStep().operator).toBe('aces');
    expect(() => new ToneMapStep('filmic' as never)).toThrow(/unknown tone-mapping operator "filmic"/);
  });

  it('kernels keep the structure the backends expect', () => {
    for (const s of [new ExposureStep(), ...TONE_MAP_OPERATORS.map((o) => new ToneMapStep(o)), new SrgbEncodeStep()]) {
      expect(s.glsl).toContain('texelFetch(inputImage, vptPixel(), 0)');
      expect(s.glsl).toContain('vpt_out0 =');
      expect(s.wgsl).toContain('@fragment fn fs_main(@builtin(position) fragCoord: vec4f) -> VptOut');
      expect(s.wgsl).toContain('textureLoad(inputImage, vptPixel(fragCoord), 0)');
    }
  });

  it('the default chain is exposure 0 → ACES → sRGB', () => {
    const chain = defaultPostChain();
    expect(chain.map((s) => s.name)).toEqual(['exposure', 'tonemap', 'srgb']);
    expect(postChainToJSON(chain)).toEqual([
      { type: 'exposure', exposure: 0 },
      { type: 'tonemap', operator: 'aces' },
      { type: 'srgb' },
    ]);
    expect(postChainToJSON(defaultPostChain({ exposure: -1.5, toneMapper: 'pbr-neutral' }))).toEqual([
      { type: 'exposure', exposure: -1.5 },
      { type: 'tonemap', operator: 'pbr-neutral' },
      { type: 'srgb' },
    ]);
  });
});

describe('JSON', () => {
  it('round-trips every step', () => {
    const json = [
      { type: 'exposure', exposure: 0 },
      { type: 'exposure', exposure: -2.25 },
      ...TONE_MAP_OPERATORS.map((operator) => ({ type: 'tonemap', operator })),
      { type: 'srgb' },
    ];
    const chain = postChainFromJSON(JSON.parse(JSON.stringify(json)));
    expect(chain[0]).toBeInstanceOf(ExposureStep);
    expect(chain[2]).toBeInstanceOf(ToneMapStep);
    expect(chain.at(-1)).toBeInstanceOf(SrgbEncodeStep);
    expect(postChainToJSON(chain)).toEqual(json);
    expect(JSON.parse(JSON.stringify(postChainToJSON(chain)))).toEqual(json);
  });

  it('parses the documented example and fills defaults', () => {
    const chain = postChainFromJSON([
      { type: 'exposure', exposure: 0 },
      { type: 'tonemap', operator: 'reinhard' },
      { type: 'srgb' },
    ]);
    expect(chain.map(postStepToJSON)).toEqual([
      { type: 'exposure', exposure: 0 },
      { type: 'tonemap', operator: 'reinhard' },
      { type: 'srgb' },
    ]);
    expect(postStepToJSON(postStepFromJSON({ type: 'exposure' }))).toEqual({ type: 'exposure', exposure: 0 });
    expect(postStepToJSON(postStepFromJSON({ type: 'tonemap' }))).toEqual({ type: 'tonemap', operator: 'aces' });
  });

  const bad: [string, unknown, RegExp][] = [
    ['unknown type', { type: 'bloom' }, /unknown type "bloom"/],
    ['missing type', { exposure: 1 }, /unknown type no "type"/],
    ['non-string type', { type: 3 }, /unknown type number/],
    [
      'unknown operator',
      { type: 'tonemap', operator: 'filmic' },
      /unknown .*tone-mapping operator "filmic".*"reinhard"/,
    ],
    ['non-string operator', { type: 'tonemap', operator: 2 }, /tone-mapping operator number/],
    ['NaN exposure', { type: 'exposure', exposure: NaN }, /finite/],
    ['infinite exposure', { type: 'exposure', exposure: -Infinity }, /finite/],
    ['string exposure', { type: 'exposure', exposure: '2' }, /finite number of stops, got the string "2"/],
    ['null exposure', { type: 'exposure', exposure: null }, /got null/],
    ['huge exposure', { type: 'exposure', exposure: 1000 }, /±64 stops/],
    ['unknown field', { type: 'srgb', gamma: 2.2 }, /unknown field "gamma"/],
    ['not an object', 'srgb', /must be an object/],
    ['null', null, /must be an object.*null/],
    ['array', [], /must be an object.*array/],
  ];
  for (const [what, json, message] of bad) {
    it(`rejects ${what} with VptError('invalid-scene')`, () => {
      let err: unknown;
      try {
        postStepFromJSON(json);
      } catch (e) {
        err = e;
      }
      expect(isVptError(err, 'invalid-scene')).toBe(true);
      expect((err as Error).message).toMatch(message);
    });
  }

  it('names the failing index in a chain, and wants an array', () => {
    expect(() => postChainFromJSON([{ type: 'srgb' }, { type: 'tonemap', operator: 'x' }])).toThrow(/post step 1/);
    expect(() => postChainFromJSON({ type: 'srgb' })).toThrow(/must be an array/);
    try {
      postChainFromJSON('nope');
    } catch (e) {
      expect(isVptError(e, 'invalid-scene')).toBe(true);
    }
  });

  it('refuses to serialise a foreign step', () => {
    const foreign = {
      name: 'custom',
      glsl: '',
      wgsl: '',
      uniforms: new SrgbEncodeStep().uniforms,
      uniformValues: () => ({}),
    };
    expect(() => postStepToJSON(foreign)).toThrow(/no JSON form/);
  });
});
