import { describe, expect, it } from 'vitest';
import { expectVptError, testScene } from '../../../tests/helpers/test-scene.js';
import { validateSceneDescription } from '../../headless/src/validate-description.js';
import {
  clipUniformValues,
  hasClip,
  isClippedPoint,
  validateScene,
  volumeBox,
  MAX_CLIP_PLANES,
  type Clip,
} from '../src/index.js';

const plane = (normal: number[], offset: number) => ({ normal, offset });

/** Bad clips, each with the field its error must name (core's path; the headless check names the same path after "clip"). */
const BAD: { what: string; clip: unknown; field: RegExp; headless?: RegExp; code?: 'limit-exceeded' }[] = [
  { what: 'not an object', clip: [1], field: /clip: must be an object/ },
  { what: 'an unknown key', clip: { plane: [] }, field: /clip: unknown key "plane"/ },
  { what: 'planes not an array', clip: { planes: {} }, field: /clip\.planes: must be an array/ },
  {
    what: 'more than MAX_CLIP_PLANES planes',
    clip: { planes: Array.from({ length: MAX_CLIP_PLANES + 1 }, () => plane([1, 0, 0], 0)) },
    field: /clip\.planes: count: 7 is above the limit/,
    code: 'limit-exceeded',
  },
  {
    what: 'a NaN normal',
    clip: { planes: [plane([NaN, 0, 0], 0)] },
    field: /clip\.planes\[0\]\.normal\[0\]/,
    // A scene file's JSON shape check names a non-finite number before the clip rules see it.
    headless: /^Scene description: scene\.clip\.planes\[0\]\.normal\[0\]: NaN is not a finite number/,
  },
  {
    what: 'an infinite normal',
    clip: { planes: [plane([0, Infinity, 0], 0)] },
    field: /clip\.planes\[0\]\.normal\[1\]: must be finite/,
    headless: /^Scene description: scene\.clip\.planes\[0\]\.normal\[1\]: Infinity is not a finite number/,
  },
  {
    what: 'a zero normal',
    clip: { planes: [plane([1, 0, 0], 0), plane([0, 0, 0], 0)] },
    field: /clip\.planes\[1\]\.normal: must have a nonzero length/,
  },
  {
    what: 'a two-component normal',
    clip: { planes: [plane([1, 0], 0)] },
    field: /clip\.planes\[0\]\.normal: must be an array of 3/,
  },
  {
    what: 'a string offset',
    clip: { planes: [{ normal: [1, 0, 0], offset: '0' }] },
    field: /clip\.planes\[0\]\.offset/,
  },
  {
    what: 'an unknown plane key',
    clip: { planes: [{ normal: [1, 0, 0], offset: 0, d: 1 }] },
    field: /clip\.planes\[0\]: unknown key "d"/,
  },
  {
    what: 'box min above max',
    clip: { box: { min: [-0.5, 0.2, -0.5], max: [0.5, 0.1, 0.5] } },
    field: /clip\.box\.min\[1\]: 0\.2 must be <= max\[1\] 0\.1/,
  },
  { what: 'a box without max', clip: { box: { min: [0, 0, 0] } }, field: /clip\.box\.max: must be an array of 3/ },
  {
    what: 'a box corner out of range',
    clip: { box: { min: [-2e4, 0, 0], max: [0, 0, 0] } },
    field: /clip\.box\.min\[0\]/,
  },
];

describe('clip validation', () => {
  for (const b of BAD) {
    it(`core refuses ${b.what}, naming the field`, () =>
      expectVptError(
        () => validateScene(testScene({ clip: b.clip as Clip })),
        b.code ?? 'invalid-scene',
        new RegExp(`^Scene: ${b.field.source}`),
      ));
    it(`the headless scene check refuses ${b.what}, naming the field`, () =>
      expectVptError(
        () => validateSceneDescription({ clip: b.clip }),
        b.code ?? 'invalid-scene',
        b.headless ?? new RegExp(`^Scene description: ${b.field.source}`),
      ));
  }
  it('accepts up to MAX_CLIP_PLANES planes, a flat box and an empty clip', () => {
    const clip: Clip = {
      planes: Array.from({ length: MAX_CLIP_PLANES }, (_, i) => ({ normal: [i + 1, -1, 0.5], offset: i / 10 })),
      box: { min: [0, -0.5, 0.1], max: [0, 0.5, 0.1] },
    };
    expect(() => validateScene(testScene({ clip }))).not.toThrow();
    expect(() => validateSceneDescription({ clip })).not.toThrow();
    expect(hasClip({})).toBe(false);
    expect(hasClip({ planes: [] })).toBe(false);
    expect(hasClip(clip)).toBe(true);
  });
});

describe('clip uniforms', () => {
  it('normalize each plane without moving its half-space, and default the box to the volume box', () => {
    const volume = testScene().volume;
    const clip: Clip = { planes: [{ normal: [0, 3, 4], offset: 1 }] };
    const v = clipUniformValues(clip, volume);
    const p = Array.from(v.clipPlanes as ArrayLike<number>);
    expect(p.slice(0, 4)).toEqual([0, 0.6, 0.8, 0.2].map((x) => Math.fround(x)));
    expect(p.slice(4).every((x) => x === 0)).toBe(true);
    expect(v.clipPlaneCount).toBe(1);
    expect(v.clipBoxMin).toEqual(volumeBox(volume).min);
    expect(v.clipBoxMax).toEqual(volumeBox(volume).max);
    // A point on either side of the plane 3y + 4z = 1 is judged the same by the raw and the unit plane.
    for (const q of [
      [0, 0.1, 0.2],
      [0, 0.1, 0.1],
      [0.3, -0.2, 0.4],
    ]) {
      const raw = 3 * q[1] + 4 * q[2] > 1;
      expect(isClippedPoint(clip, q)).toBe(raw);
      expect(p[0] * q[0] + p[1] * q[1] + p[2] * q[2] > p[3]).toBe(raw);
    }
  });
  it('isClippedPoint removes what lies outside the box', () => {
    const clip: Clip = { box: { min: [-0.1, -0.2, -0.3], max: [0.1, 0.2, 0.3] } };
    expect(isClippedPoint(clip, [0, 0, 0])).toBe(false);
    expect(isClippedPoint(clip, [0.11, 0, 0])).toBe(true);
    expect(isClippedPoint(clip, [0, 0, -0.31])).toBe(true);
  });
});
