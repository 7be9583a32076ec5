import { describe, expect, it } from 'vitest';
import { isVptError } from '@vpt/core';
import {
  jsonConverter,
  InvalidAttribute,
  parseCamera,
  parseEnvironment,
  parseLights,
  parseNumber,
  parseTransferFunction,
  sameValue,
} from '../src/attributes.js';
import { TRANSFER_FUNCTION_PRESETS } from '../src/presets.js';

const expectError = (f: () => unknown, pattern: RegExp) => {
  let err: unknown;
  try {
    f();
  } catch (e) {
    err = e;
  }
  expect(isVptError(err, 'invalid-scene'), String(err)).toBe(true);
  expect((err as Error).message).toMatch(pattern);
};

describe('attribute parsing', () => {
  it('transfer-function: a preset name gives a copy of the preset, JSON is validated by core, junk names the presets', () => {
    const tf = parseTransferFunction('bone');
    expect(tf).toEqual(TRANSFER_FUNCTION_PRESETS.bone);
    expect(tf).not.toBe(TRANSFER_FUNCTION_PRESETS.bone);
    expect(
      parseTransferFunction('{"dimensions":"1d","points":[{"value":0,"color":[1,1,1],"opacity":0}]}').dimensions,
    ).toBe('1d');
    expectError(
      () => parseTransferFunction('bones'),
      /transfer-function: unknown preset "bones" \(presets: ramp, tissue, bone/,
    );
    expectError(() => parseTransferFunction('{"dimensions":"1d"'), /transfer-function: not valid JSON/);
    expectError(
      () => parseTransferFunction({ dimensions: '1d', points: [{ value: 2, color: [1, 1, 1], opacity: 0 }] }),
      /transfer-function: .*point 0: value must be in \[0, 1\]/,
    );
    expectError(
      () => parseTransferFunction({ dimensions: '2d', widgets: [] }),
      /transfer-function: .*at least one widget/,
    );
  });

  it('every preset is a valid transfer function', () => {
    for (const [name, tf] of Object.entries(TRANSFER_FUNCTION_PRESETS))
      expect(() => parseTransferFunction(tf), name).not.toThrow();
  });

  it('camera: target, up and fovy default; a degenerate camera is refused with the attribute name', () => {
    expect(parseCamera('{"position":[0,0,3]}')).toEqual({
      position: [0, 0, 3],
      target: [0, 0, 0],
      up: [0, 1, 0],
      fovy: 0.7,
    });
    expectError(() => parseCamera({ position: [0, 0, 0] }), /camera: Camera: position and target coincide/);
    expectError(() => parseCamera({ position: [0, 2, 0], up: [0, 1, 0] }), /camera: .*up is parallel/);
    expectError(() => parseCamera('[1,2,3]'), /camera: expected JSON like/);
  });

  it('lights and environment', () => {
    expect(parseLights('none')).toEqual([]);
    expect(parseLights([{ type: 'directional', direction: [0, 1, 0], irradiance: [1, 1, 1] }])).toHaveLength(1);
    expectError(() => parseLights('{"type":"directional"}'), /lights: expected a JSON array/);
    expectError(
      () => parseLights([{ type: 'directional', direction: [0, 0, 0], irradiance: [1, 1, 1] }]),
      /lights: Light 0: direction must be finite and non-zero/,
    );
    expect(parseEnvironment('{"type":"constant","radiance":[1,2,3]}')).toEqual({
      type: 'constant',
      radiance: [1, 2, 3],
    });
    expect(parseEnvironment('sky.hdr')).toEqual({ type: 'url', url: 'sky.hdr' });
    expectError(() => parseEnvironment('sky.png'), /environment: expected JSON like/);
    const latlong = parseEnvironment({ type: 'latlong', width: 2, height: 1, data: [0, 0, 0, 1, 1, 1] });
    expect(latlong.type === 'latlong' && latlong.data instanceof Float32Array).toBe(true);
  });

  it('numbers are checked against their range', () => {
    expect(parseNumber('max-samples', '16', { min: 1, integer: true })).toBe(16);
    expectError(
      () => parseNumber('max-samples', '1.5', { min: 1, integer: true }),
      /max-samples: must be an integer in \[1, Infinity\], got "1.5"/,
    );
    expectError(() => parseNumber('exposure', NaN), /exposure: must be a number/);
  });

  it('numbers above their maximum are refused (seed > 2^32 − 1, exposure 100, resolution-scale 5), the maximum itself is not', () => {
    // The ranges <vpt-viewer> gives these attributes (tests/viewer-element.test.ts sets them on the element).
    const seed = { min: 0, max: 0xffffffff, integer: true };
    expect(parseNumber('seed', '4294967295', seed)).toBe(0xffffffff);
    expectError(
      () => parseNumber('seed', '4294967296', seed),
      /seed: must be an integer in \[0, 4294967295\], got "4294967296"/,
    );
    expect(parseNumber('exposure', 64, { min: -64, max: 64 })).toBe(64);
    expectError(
      () => parseNumber('exposure', '100', { min: -64, max: 64 }),
      /exposure: must be a number in \[-64, 64\]/,
    );
    expectError(() => parseNumber('exposure', Infinity, { min: -64, max: 64 }), /exposure: must be a number/);
    expect(parseNumber('resolution-scale', '4', { min: 0.05, max: 4 })).toBe(4);
    expectError(
      () => parseNumber('resolution-scale', '5', { min: 0.05, max: 4 }),
      /resolution-scale: must be a number in \[0.05, 4\]/,
    );
    expectError(
      () => parseNumber('resolution-scale', '0.01', { min: 0.05, max: 4 }),
      /resolution-scale: must be a number in \[0.05, 4\]/,
    );
  });

  it('the attribute converter parses on the way in and marks what does not parse', () => {
    const c = jsonConverter(parseTransferFunction);
    expect(c.fromAttribute('hot')).toEqual(TRANSFER_FUNCTION_PRESETS.hot);
    expect(c.fromAttribute('nope')).toBeInstanceOf(InvalidAttribute);
    expect(c.fromAttribute(null)).toBeNull();
    expect(JSON.parse(c.toAttribute({ a: new Float32Array(3) })!)).toEqual({ a: '[3 values]' });
  });

  it('sameValue compares by content, typed arrays by identity', () => {
    expect(sameValue({ a: [1, 2, { b: 3 }] }, { a: [1, 2, { b: 3 }] })).toBe(true);
    expect(sameValue({ a: [1, 2] }, { a: [1, 2, 3] })).toBe(false);
    expect(sameValue({ a: 1 }, { b: 1 })).toBe(false);
    const d = new Float32Array(3);
    expect(sameValue({ d }, { d })).toBe(true);
    expect(sameValue({ d }, { d: new Float32Array(3) })).toBe(false);
    expect(sameValue(NaN, NaN)).toBe(true);
  });
});
