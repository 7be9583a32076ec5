import { describe, expect, it } from 'vitest';
import { expectVptError, testScene } from '../../../tests/helpers/test-scene.js';
import { defaultCamera, validateScene, volumeBox, normalizedData, createVolume, type Scene } from '../src/index.js';

const scene = testScene;

function expectInvalid(s: Scene, pattern: RegExp): void {
  expectVptError(() => validateScene(s), 'invalid-scene', pattern);
}

describe('scene validation', () => {
  it('accepts a valid scene', () => expect(() => validateScene(scene())).not.toThrow());
  it('rejects a NaN camera', () =>
    expectInvalid(scene({ camera: { ...defaultCamera(), position: [NaN, 0, 2] } }), /position must be three finite/));
  it('rejects a camera whose up is parallel to the view', () =>
    expectInvalid(scene({ camera: { ...defaultCamera(), up: [0, 0, 1] } }), /parallel/));
  it('rejects fovy outside (0, π)', () => expectInvalid(scene({ camera: { ...defaultCamera(), fovy: 0 } }), /fovy/));
  it('rejects a zero-size volume', () =>
    expectInvalid(
      scene({ volume: { dims: [0, 4, 4], spacing: [1, 1, 1], type: 'uint8', data: new Uint8Array(0) } }),
      /positive integer/,
    ));
  it('rejects data shorter than the dims', () =>
    expectInvalid(
      scene({ volume: { dims: [4, 4, 4], spacing: [1, 1, 1], type: 'uint8', data: new Uint8Array(10) } }),
      /need 64 voxels/,
    ));
  it('rejects data of the wrong array type', () =>
    expectInvalid(
      scene({ volume: { dims: [2, 2, 2], spacing: [1, 1, 1], type: 'uint16', data: new Uint8Array(8) } }),
      /Uint16Array/,
    ));
  it('rejects non-positive spacing', () =>
    expectInvalid(
      scene({ volume: { dims: [2, 2, 2], spacing: [1, 0, 1], type: 'uint8', data: new Uint8Array(8) } }),
      /spacing/,
    ));
  it('rejects an unsorted transfer function', () =>
    expectInvalid(
      scene({
        transferFunction: {
          dimensions: '1d',
          points: [
            { value: 0.5, color: [1, 1, 1], opacity: 1 },
            { value: 0.2, color: [1, 1, 1], opacity: 1 },
          ],
        },
      }),
      /sorted/,
    ));
  it('rejects negative opacity', () =>
    expectInvalid(
      scene({ transferFunction: { dimensions: '1d', points: [{ value: 0, color: [1, 1, 1], opacity: -1 }] } }),
      /opacity/,
    ));
  it('rejects a negative density scale', () => expectInvalid(scene({ densityScale: -1 }), /densityScale/));
  it('rejects a non-integer seed', () => expectInvalid(scene({ seed: 1.5 }), /seed/));
  it('rejects NaN environment radiance', () =>
    expectInvalid(scene({ environment: { type: 'constant', radiance: [1, NaN, 1] } }), /radiance/));
});

describe('volume conventions', () => {
  it('scales the box so its longest side is 1, centred', () => {
    const box = volumeBox({ dims: [100, 50, 20], spacing: [1, 1, 2] });
    expect(box.size).toEqual([1, 0.5, 0.4]);
    expect(box.min).toEqual([-0.5, -0.25, -0.2]);
  });
  it('normalizes uint8 by 255 and uint16 by 65535', () => {
    expect(Array.from(normalizedData(createVolume([2, 1, 1], 'uint8', new Uint8Array([0, 255]))))).toEqual([0, 1]);
    expect(normalizedData(createVolume([2, 1, 1], 'uint16', new Uint16Array([65535, 32768])))[1]).toBeCloseTo(
      32768 / 65535,
      7,
    );
  });
  it('maps int16 and float32 by their range and turns NaN/Inf into 0', () => {
    const v = createVolume([4, 1, 1], 'float32', new Float32Array([NaN, -2, 2, Infinity]));
    expect(Array.from(normalizedData(v))).toEqual([0, 0, 1, 0]);
    const s = createVolume([3, 1, 1], 'int16', new Int16Array([-1024, 0, 1024]));
    expect(Array.from(normalizedData(s))).toEqual([0, 0.5, 1]);
  });
});
