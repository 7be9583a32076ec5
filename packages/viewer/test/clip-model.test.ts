import { describe, expect, it } from 'vitest';
import { isClippedPoint, isVptError, MAX_CLIP_PLANES, type Clip } from '@vpt/core';
import { parseClip } from '../src/attributes.js';
import { canAddPlane, clipControls, clipFromControls, moveBoxBound, type Vec3 } from '../src/clip-model.js';

describe('the clip attribute', () => {
  it('takes the scene file JSON and returns a copy', () => {
    const text = '{"planes":[{"normal":[1,0,0],"offset":0.1}],"box":{"min":[-0.5,-0.4,-0.3],"max":[0.5,0.4,0.3]}}';
    const clip = parseClip(text);
    expect(clip).toEqual(JSON.parse(text));
    const obj: Clip = { planes: [{ normal: [0, 1, 0], offset: 0 }] };
    expect(parseClip(obj)).not.toBe(obj);
  });

  it.each([
    ['{"planes": [', /<vpt-viewer> clip: not valid JSON/],
    ['[1, 2]', /<vpt-viewer> clip: expected JSON like/],
    ['{"planes":[{"normal":[0,0,0],"offset":0}]}', /clip\.planes\[0\]\.normal: must have a nonzero length/],
    ['{"box":{"min":[0,0,0],"max":[-1,0,0]}}', /clip\.box\.min\[0\]/],
    ['{"planes":[],"cut":true}', /clip.*cut/],
    [
      JSON.stringify({ planes: Array.from({ length: 7 }, () => ({ normal: [1, 0, 0], offset: 0 })) }),
      /clip\.planes: count/,
    ],
  ])('refuses %s with a typed error naming the field', (text, message) => {
    let error: unknown;
    try {
      parseClip(text);
    } catch (e) {
      error = e;
    }
    expect(isVptError(error, 'invalid-scene')).toBe(true);
    expect((error as Error).message).toMatch(message);
  });
});

describe('the Clip panel model', () => {
  const VOLUME = { min: [-0.5, -0.5, -0.25] as Vec3, max: [0.5, 0.5, 0.25] as Vec3 };

  it('reads axis planes (either sign, any length), the box and other planes, and writes them back', () => {
    const clip: Clip = {
      planes: [
        { normal: [2, 0, 0], offset: 0.2 }, // x <= 0.1 kept
        { normal: [0, -1, 0], offset: 0.1 }, // y >= -0.1 kept (flipped)
        { normal: [1, 1, 0], offset: 0 }, // oblique: kept as it is
        { normal: [1, 0, 0], offset: 0.3 }, // a second x plane: kept as it is
      ],
      box: { min: [-0.4, -0.5, -0.25], max: [0.5, 0.3, 0.2] },
    };
    const c = clipControls(clip);
    expect(c.axes).toEqual({ x: { position: 0.1, flip: false }, y: { position: -0.1, flip: true }, z: null });
    expect(c.others).toHaveLength(2);
    expect(c.box).toEqual(clip.box);
    const back = clipFromControls(c)!;
    // The same half-spaces and box, so the same points are removed.
    for (let i = 0; i < 2000; i++) {
      const p = [Math.sin(i * 1.3) * 0.5, Math.sin(i * 2.1 + 1) * 0.5, Math.sin(i * 0.7 + 2) * 0.25];
      expect(isClippedPoint(back, p)).toBe(isClippedPoint(clip, p));
    }
  });

  it('a flip keeps the other side; no plane and no box is no clip', () => {
    const keepLow = clipFromControls({
      axes: { x: null, y: null, z: { position: 0.1, flip: false } },
      box: null,
      others: [],
    });
    const keepHigh = clipFromControls({
      axes: { x: null, y: null, z: { position: 0.1, flip: true } },
      box: null,
      others: [],
    });
    expect(keepLow).toEqual({ planes: [{ normal: [0, 0, 1], offset: 0.1 }] });
    expect(keepHigh).toEqual({ planes: [{ normal: [0, 0, -1], offset: -0.1 }] });
    expect(isClippedPoint(keepLow!, [0, 0, 0.2])).toBe(true);
    expect(isClippedPoint(keepHigh!, [0, 0, 0.2])).toBe(false);
    expect(isClippedPoint(keepHigh!, [0, 0, 0])).toBe(true);
    expect(clipFromControls(clipControls(null))).toBeNull();
  });

  it('box bounds stay inside the volume box and ordered', () => {
    const box = { min: [...VOLUME.min] as Vec3, max: [...VOLUME.max] as Vec3 };
    expect(moveBoxBound(box, VOLUME, 'min', 0, -2).min[0]).toBe(-0.5);
    const b = moveBoxBound(box, VOLUME, 'max', 2, 0.1);
    expect(b.max[2]).toBe(0.1);
    expect(moveBoxBound(b, VOLUME, 'min', 2, 0.2).min[2]).toBe(0.1);
    expect(box.max[2]).toBe(0.25); // not modified in place
  });

  it('offers no more axis planes than a scene may have', () => {
    const others = Array.from({ length: MAX_CLIP_PLANES - 1 }, () => ({ normal: [1, 1, 0] as Vec3, offset: 0 }));
    expect(canAddPlane({ axes: { x: null, y: null, z: null }, box: null, others })).toBe(true);
    expect(canAddPlane({ axes: { x: { position: 0, flip: false }, y: null, z: null }, box: null, others })).toBe(false);
  });
});
