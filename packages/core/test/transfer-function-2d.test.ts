import { describe, expect, it } from 'vitest';
import {
  createVolume,
  isVptError,
  maxOpacityByValue,
  rasterizeTransferFunction,
  transferFunctionFromJSON,
  transferFunctionPreset,
  transferFunctionSize,
  transferFunctionToJSON,
  TRANSFER_FUNCTION_PRESETS,
  validateTransferFunction,
  TF_2D_HEIGHT,
  TF_RESOLUTION,
  type TransferFunction,
  type TransferFunction2D,
} from '../src/index.js';

function expectError(f: () => unknown, pattern: RegExp): void {
  try {
    f();
  } catch (e) {
    expect(isVptError(e, 'invalid-scene')).toBe(true);
    expect((e as Error).message).toMatch(pattern);
    return;
  }
  throw new Error('expected a VptError');
}

/** A deterministic pseudo-random stream (not the code under test), for generated transfer functions. */
function lcg(seed: number) {
  let s = seed >>> 0;
  return () => (s = (Math.imul(s, 1664525) + 1013904223) >>> 0) / 4294967296;
}

function randomTf(rand: () => number): TransferFunction {
  const color = (): [number, number, number] => [rand() * 3, rand(), rand() / 7];
  if (rand() < 0.3) {
    const values = Array.from({ length: 1 + Math.floor(rand() * 5) }, rand).sort((a, b) => a - b);
    return { dimensions: '1d', points: values.map((value) => ({ value, color: color(), opacity: rand() * 100 })) };
  }
  return {
    dimensions: '2d',
    ...(rand() < 0.5 ? { gradientMax: 1e-3 + rand() * 500 } : {}),
    widgets: Array.from({ length: 1 + Math.floor(rand() * 4) }, () => {
      if (rand() < 0.5)
        return {
          type: 'gaussian' as const,
          center: [rand(), rand()] as [number, number],
          width: [0.01 + rand(), 1e-3 + rand() / 3] as [number, number],
          color: color(),
          opacity: rand() * 10,
        };
      const a = rand(),
        b = rand();
      return {
        type: 'box' as const,
        min: [a / 2, b / 2] as [number, number],
        max: [a, b] as [number, number],
        ...(rand() < 0.5 ? { ramp: [rand() / 10, 0] as [number, number] } : {}),
        color: color(),
        opacity: rand(),
      };
    }),
  };
}

describe('2D transfer function', () => {
  it('rasterizes a box to 256 x 256 texels: inside exactly its colour and opacity, outside zero', () => {
    const tf: TransferFunction2D = {
      dimensions: '2d',
      widgets: [{ type: 'box', min: [0.25, 0.5], max: [0.75, 1], color: [1, 0.5, 0.25], opacity: 3 }],
    };
    expect(transferFunctionSize(tf)).toEqual([TF_RESOLUTION, TF_2D_HEIGHT]);
    const t = rasterizeTransferFunction(tf);
    expect(t.length).toBe(256 * 256 * 4);
    const at = (i: number, j: number) => Array.from(t.subarray(4 * (i + 256 * j), 4 * (i + 256 * j) + 4));
    // texel (i, j) is value i/255, gradient j/255
    expect(at(128, 200)).toEqual([1, 0.5, 0.25, 3]);
    expect(at(128, 127)).toEqual([0, 0, 0, 0]); // gradient 0.498 < 0.5
    expect(at(128, 128)).toEqual([1, 0.5, 0.25, 3]); // 0.502
    expect(at(200, 255)).toEqual([0, 0, 0, 0]); // value 0.784 > 0.75
  });

  it('adds the extinctions of overlapping widgets and weights their colours by extinction', () => {
    const tf: TransferFunction2D = {
      dimensions: '2d',
      widgets: [
        { type: 'box', min: [0, 0], max: [1, 1], color: [1, 0, 0], opacity: 1 },
        { type: 'gaussian', center: [0.2, 0.6], width: [0.1, 0.2], color: [0, 0, 1], opacity: 3 },
      ],
    };
    const t = rasterizeTransferFunction(tf);
    const i = 100,
      j = 30;
    const v = i / 255,
      g = j / 255;
    const w = 3 * Math.exp(-0.5 * (((v - 0.2) / 0.1) ** 2 + ((g - 0.6) / 0.2) ** 2));
    const k = 4 * (i + 256 * j);
    expect(t[k + 3]).toBeCloseTo(1 + w, 6);
    expect(t[k]).toBeCloseTo(1 / (1 + w), 6);
    expect(t[k + 2]).toBeCloseTo(w / (1 + w), 6);
  });

  it('ramps a trapezoid linearly to zero over its ramp width', () => {
    const tf: TransferFunction2D = {
      dimensions: '2d',
      widgets: [{ type: 'box', min: [0.5, 0], max: [0.6, 1], ramp: [0.2, 0], color: [1, 1, 1], opacity: 2 }],
    };
    const t = rasterizeTransferFunction(tf);
    const i = 102; // value 0.4: 0.1 below min with a 0.2 ramp → weight 1 − (0.5 − 0.4)/0.2
    const v = i / 255;
    expect(t[4 * (i + 256 * 10) + 3]).toBeCloseTo(2 * (1 - (0.5 - v) / 0.2), 6);
    expect(t[4 * (51 + 256 * 10) + 3]).toBe(0); // value 0.2: beyond the ramp
  });

  it('bounds the opacity per value over all gradients (for majorants)', () => {
    const tf: TransferFunction2D = {
      dimensions: '2d',
      widgets: [
        { type: 'box', min: [0.2, 0.9], max: [0.4, 1], color: [1, 1, 1], opacity: 5 },
        { type: 'box', min: [0.3, 0], max: [0.6, 0.1], color: [1, 1, 1], opacity: 2 },
      ],
    };
    const m = maxOpacityByValue(tf);
    expect(m.length).toBe(256);
    expect(m[Math.round(0.25 * 255)]).toBe(5); // only at high gradient
    expect(m[Math.round(0.35 * 255)]).toBe(5); // both widgets, never at the same gradient
    expect(m[Math.round(0.5 * 255)]).toBe(2);
    expect(m[Math.round(0.8 * 255)]).toBe(0);
    const tf1: TransferFunction = {
      dimensions: '1d',
      points: [
        { value: 0, color: [1, 1, 1], opacity: 0 },
        { value: 1, color: [1, 1, 1], opacity: 3 },
      ],
    };
    expect(Array.from(maxOpacityByValue(tf1))).toEqual(
      Array.from(rasterizeTransferFunction(tf1)).filter((_, i) => i % 4 === 3),
    );
  });

  it('keeps the 1D rasterization (256 x 1)', () => {
    const tf: TransferFunction = {
      dimensions: '1d',
      points: [
        { value: 0, color: [0, 0, 0], opacity: 0 },
        { value: 1, color: [1, 1, 1], opacity: 2 },
      ],
    };
    expect(transferFunctionSize(tf)).toEqual([256, 1]);
    const t = rasterizeTransferFunction(tf);
    expect(t.length).toBe(256 * 4);
    expect(t[4 * 51 + 3]).toBeCloseTo((2 * 51) / 255, 6);
  });

  it('rejects bad widgets with errors that name the field', () => {
    const box = { type: 'box', min: [0, 0], max: [1, 1], color: [1, 1, 1], opacity: 1 };
    const tf = (w: object) => ({ dimensions: '2d', widgets: [box, w] }) as TransferFunction;
    expectError(
      () => validateTransferFunction(tf({ ...box, opacity: -1 })),
      /widget 1: opacity must be non-negative, got -1/,
    );
    expectError(
      () => validateTransferFunction(tf({ ...box, opacity: NaN })),
      /widget 1: opacity must be a finite number, got NaN/,
    );
    expectError(
      () => validateTransferFunction(tf({ ...box, type: 'triangle' })),
      /widget 1: unknown widget type "triangle" \(supported: gaussian, box\)/,
    );
    expectError(
      () =>
        validateTransferFunction(
          tf({ type: 'gaussian', center: [0.5, 0.5], width: [0, 0.1], color: [1, 1, 1], opacity: 1 }),
        ),
      /widget 1: width must be positive/,
    );
    expectError(
      () => validateTransferFunction(tf({ ...box, min: [0.6, 0], max: [0.5, 1] })),
      /min must not exceed max/,
    );
    expectError(
      () => validateTransferFunction(tf({ ...box, color: [1, Infinity, 0] })),
      /widget 1: color must be three finite non-negative numbers/,
    );
    expectError(() => validateTransferFunction({ dimensions: '2d', widgets: [] }), /at least one widget/);
    expectError(
      () =>
        validateTransferFunction({
          dimensions: '2d',
          widgets: [box as TransferFunction2D['widgets'][0]],
          gradientMax: 0,
        }),
      /gradientMax must be a positive finite number/,
    );
    expectError(
      () => validateTransferFunction({ dimensions: '3d' } as unknown as TransferFunction),
      /unknown dimensions "3d"/,
    );
  });
});

describe('transfer function JSON', () => {
  it('round-trips exactly: fromJSON(toJSON(tf)) equals tf, toJSON(fromJSON(text)) equals text, the raster is identical', () => {
    const rand = lcg(7);
    for (let n = 0; n < 200; n++) {
      const tf = randomTf(rand);
      const text = transferFunctionToJSON(tf);
      const back = transferFunctionFromJSON(text);
      expect(back).toEqual(tf);
      expect(transferFunctionToJSON(back)).toBe(text);
      if (n % 20 === 0) {
        const a = rasterizeTransferFunction(back),
          b = rasterizeTransferFunction(tf);
        let diff = 0;
        for (let i = 0; i < a.length; i++) if (!Object.is(a[i], b[i])) diff++;
        expect(diff).toBe(0);
      }
    }
  });

  it('accepts parsed objects as well as text', () => {
    const tf = transferFunctionPreset('ct-bone');
    expect(transferFunctionFromJSON(JSON.parse(transferFunctionToJSON(tf)))).toEqual(tf);
  });

  it('rejects invalid JSON with clear errors', () => {
    const w = '{"type":"box","min":[0,0],"max":[1,1],"color":[1,1,1],"opacity":%}';
    const doc = (x: string) => `{"dimensions":"2d","widgets":[${x}]}`;
    expectError(
      () => transferFunctionFromJSON(doc(w.replace('%', '-0.5'))),
      /widget 0: opacity must be non-negative, got -0.5/,
    );
    // JSON has no NaN: JSON.stringify writes null, a hand-written file may hold a string.
    expectError(
      () => transferFunctionFromJSON(doc(w.replace('%', 'null'))),
      /widget 0: opacity must be a finite number, got null/,
    );
    expectError(
      () => transferFunctionFromJSON(doc(w.replace('%', '"NaN"'))),
      /widget 0: opacity must be a finite number, got "NaN"/,
    );
    expectError(() => transferFunctionFromJSON(doc(w.replace('%', 'NaN'))), /not valid JSON/);
    expectError(
      () =>
        transferFunctionFromJSON({
          dimensions: '2d',
          widgets: [{ type: 'gaussian', center: [0.5, NaN], width: [0.1, 0.1], color: [1, 1, 1], opacity: 1 }],
        }),
      /widget 0: center must be two finite numbers/,
    );
    expectError(
      () => transferFunctionFromJSON(doc(w.replace('"box"', '"ellipse"').replace('%', '1'))),
      /widget 0: unknown widget type "ellipse" \(supported: gaussian, box\)/,
    );
    expectError(
      () => transferFunctionFromJSON(doc(w.replace('"opacity"', '"opacty"').replace('%', '1'))),
      /widget 0: unknown field "opacty"/,
    );
    expectError(
      () => transferFunctionFromJSON('{"dimensions":"1d","points":[{"value":0.5,"color":[1,1,1],"opacity":-2}]}'),
      /point 0: opacity must be non-negative/,
    );
    expectError(() => transferFunctionFromJSON('{"widgets":[]}'), /unknown dimensions undefined/);
    expectError(() => transferFunctionFromJSON('{"dimensions":"2d","widgets":[]'), /not valid JSON/);
  });
});

describe('transfer function presets', () => {
  it('are valid 2D transfer functions for every preset, with and without a volume', () => {
    const vol = createVolume(
      [4, 4, 4],
      'uint8',
      Uint8Array.from({ length: 64 }, (_, i) => i * 4),
    );
    for (const name of TRANSFER_FUNCTION_PRESETS) {
      for (const tf of [transferFunctionPreset(name), transferFunctionPreset(name, vol)]) {
        expect(tf.dimensions).toBe('2d');
        expect(() => validateTransferFunction(tf)).not.toThrow();
        expect(transferFunctionFromJSON(transferFunctionToJSON(tf))).toEqual(tf);
      }
    }
  });

  it('places CT presets by Hounsfield units through the volume normalization range', () => {
    const ct = (range: [number, number]) => {
      const v = createVolume([2, 2, 2], 'int16');
      v.valueRange = range;
      return v;
    };
    const at = (tf: TransferFunction2D, hu: number, range: [number, number]) => {
      const r = rasterizeTransferFunction(tf);
      const i = Math.round(((hu - range[0]) / (range[1] - range[0])) * 255);
      return r[4 * (i + 256 * 128) + 3];
    };
    for (const range of [
      [-1024, 3071],
      [-1024, 1671],
    ] as [number, number][]) {
      const tf = transferFunctionPreset('ct-bone', ct(range));
      expect(at(tf, 1200, range)).toBeGreaterThan(10); // cortical bone: opaque
      expect(at(tf, -1000, range)).toBe(0); // air: clear
      expect(at(tf, 40, range)).toBeLessThan(1); // soft tissue: at most a faint boundary
    }
  });

  it('names unknown presets', () => {
    expectError(() => transferFunctionPreset('ct-lung' as 'ct-bone'), /Unknown transfer-function preset "ct-lung"/);
  });
});
