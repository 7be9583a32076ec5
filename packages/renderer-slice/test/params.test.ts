import { describe, expect, it } from 'vitest';
import { createVolume, rendererControls, validateRendererParams, VptError, type Scene } from '@vpt/core';
import { SLICE_DESCRIPTOR, SliceRenderer, type SliceParams } from '../src/index.js';

/** The error a call throws (the test fails when it throws none or not a VptError). */
function thrown(f: () => unknown): VptError {
  try {
    f();
  } catch (e) {
    expect(e).toBeInstanceOf(VptError);
    return e as VptError;
  }
  throw new Error('expected a VptError, nothing was thrown');
}

function scene(
  dims: [number, number, number],
  tf: Scene['transferFunction'] = { dimensions: '1d', points: [] },
): Scene {
  return {
    volume: createVolume(dims, 'uint8'),
    transferFunction: tf,
    camera: { position: [0, 0, 2], target: [0, 0, 0], up: [0, 1, 0], fovy: 0.8 },
    lights: [],
    environment: { type: 'constant', radiance: [0, 0, 0] },
    densityScale: 1,
    seed: 1,
  };
}

describe('slice renderer parameters', () => {
  it('defaults: the middle z layer, nearest, grey, the value range, in 3D', () => {
    const r = new SliceRenderer();
    expect(r.resolvedParams).toEqual({
      plane: { kind: 'axis', axis: 'z', index: null, position: null },
      sampling: 'nearest',
      window: null,
      colormap: 'grey',
      fit: false,
    });
    expect(r.features(scene([4, 4, 4]))).toEqual({ FIT: false, NEAREST: true, COLOR_TF: false, COLOR_TABLE: false });
  });

  // Each bad value, the field its error must name, and the rule.
  const bad: [string, unknown, RegExp][] = [
    ['unknown key', { foo: 1 }, /SLICE parameters.*unknown key "foo"/],
    ['axis', { axis: 'w' }, /SLICE\.axis: must be one of "x", "y", "z"/],
    ['negative index', { index: -1 }, /SLICE\.index: must be an integer >= 0/],
    ['fractional index', { index: 1.5 }, /SLICE\.index: must be an integer/],
    ['position beyond the coordinate bound', { position: 1e5 }, /SLICE\.position: 100000 is above the limit/],
    ['sampling', { sampling: 'cubic' }, /SLICE\.sampling: must be one of "nearest", "linear"/],
    ['colormap', { colormap: 'jet' }, /SLICE\.colormap: must be one of/],
    ['fit', { fit: 1 }, /SLICE\.fit: must be true or false/],
    ['window not a pair', { window: 40 }, /SLICE\.window: must be an array of 2 numbers/],
    ['window width 0', { window: [40, 0] }, /SLICE\.window\[1\]: must be a number > 0/],
    ['window NaN', { window: [Number.NaN, 10] }, /SLICE\.window\[0\]/],
    ['window beyond float32', { window: [1e39, 10] }, /SLICE\.window\[0\]: 1e\+39 exceeds the float32 range/],
    ['zero normal', { normal: [0, 0, 0] }, /SLICE\.normal: must have a length above 1e-6/],
    ['normal of two', { normal: [1, 0] }, /SLICE\.normal: must be an array of 3 numbers/],
    ['point without normal', { point: [0, 0, 0] }, /SLICE\.point: needs "normal"/],
    ['index and position', { index: 1, position: 0 }, /SLICE\.position: give "index" or "position", not both/],
    ['normal with axis', { normal: [0, 0, 1], axis: 'z' }, /SLICE\.axis: is for an axis-aligned plane/],
    ['normal with index', { normal: [0, 0, 1], index: 2 }, /SLICE\.index: is for an axis-aligned plane/],
  ];
  for (const [what, params, message] of bad) {
    it(`refuses ${what} with an invalid-scene error naming the field`, () => {
      const e = thrown(() => new SliceRenderer(params as SliceParams));
      expect(e.code).toBe('invalid-scene');
      expect(e.message).toMatch(message);
    });
  }

  it('setParams refuses a bad value and keeps the previous parameters and version', () => {
    const r = new SliceRenderer({ index: 1 });
    const v = r.version;
    expect(thrown(() => r.setParams({ window: [0, -1] })).message).toMatch(/SLICE\.window\[1\]/);
    expect(r.getParams()).toEqual({ index: 1 });
    expect(r.version).toBe(v);
    r.setParams({ colormap: 'viridis' });
    expect(r.version).toBe(v + 1);
    expect(r.features(scene([4, 4, 4])).COLOR_TABLE).toBe(true);
  });

  it('checks the plane against the scene: index, position, an oblique plane that misses the box', () => {
    const s = scene([8, 6, 4]); // box [-0.5, 0.5] x [-0.375, 0.375] x [-0.25, 0.25]
    expect(() => new SliceRenderer({ index: 3 }).validateScene(s)).not.toThrow();
    expect(thrown(() => new SliceRenderer({ index: 4 }).validateScene(s)).message).toMatch(
      /SLICE\.index: 4 is past the last of the volume's 4 layers along z \(0 to 3\)/,
    );
    expect(thrown(() => new SliceRenderer({ axis: 'x', index: 8 }).validateScene(s)).message).toMatch(/SLICE\.index/);
    expect(() => new SliceRenderer({ axis: 'y', position: 0.375 }).validateScene(s)).not.toThrow();
    expect(thrown(() => new SliceRenderer({ axis: 'y', position: 0.4 }).validateScene(s)).message).toMatch(
      /SLICE\.position: 0\.4 is outside the volume's box along y: \[-0\.375, 0\.375\]/,
    );
    expect(thrown(() => new SliceRenderer({ normal: [1, 1, 1], point: [1, 1, 1] }).validateScene(s)).message).toMatch(
      /SLICE\.point: the plane .* does not cut the volume's box/,
    );
    // Touching the box along one edge only is no slice either.
    const edge = new SliceRenderer({ normal: [1, 1, 0], point: [0.5, 0.375, 0] });
    expect(thrown(() => edge.validateScene(s)).message).toMatch(/SLICE\.point/);
  });

  it('setParams checks a new plane against the last scene validated', () => {
    const r = new SliceRenderer();
    r.validateScene(scene([8, 6, 4]));
    expect(thrown(() => r.setParams({ index: 9 })).message).toMatch(/SLICE\.index: 9 is past the last/);
    expect(r.getParams()).toEqual({});
    r.setParams({ index: 2 });
    expect(r.getParams()).toEqual({ index: 2 });
  });

  it('refuses a window whose mapping would overflow float32 against the value range', () => {
    const s = scene([4, 4, 4]); // uint8: value range [0, 255]
    expect(() => new SliceRenderer({ window: [100, 1e-30] }).validateScene(s)).not.toThrow(); // scale 2.55e32
    expect(thrown(() => new SliceRenderer({ window: [100, 1e-37] }).validateScene(s)).message).toMatch(
      /SLICE\.window: \[100,1e-37\] against the volume's value range \[0, 255\] .* outside the float32 range/,
    );
    const r = new SliceRenderer();
    r.validateScene(s);
    expect(thrown(() => r.setParams({ window: [1e38, 1e-3] })).message).toMatch(/SLICE\.window: .*float32/);
    // Far wider than the range: a scale below float32's normal range would reach the kernel as 0.
    const narrow = scene([4, 4, 4]);
    narrow.volume.valueRange = [0, 1e-3];
    expect(thrown(() => new SliceRenderer({ window: [0, 1e36] }).validateScene(narrow)).message).toMatch(
      /SLICE\.window: .*scale of 1e-39/,
    );
  });

  it('a scene never validated against the parameters: nothing drawn, and stats() says why', () => {
    const r = new SliceRenderer({ index: 5 });
    const fits = r.paramValues(scene([4, 4, 8]));
    expect(r.stats()).toEqual({});
    expect(fits.planeNormal).toEqual([0, 0, 1]);
    const none = r.paramValues(scene([4, 4, 4]));
    expect(none.planeNormal).toEqual([0, 0, 0]);
    expect(none.planeU).toEqual([0, 0, 0]);
    expect(r.stats().slice).toMatch(/^nothing drawn: SLICE\.index: 5 is past the last of the volume's 4 layers/);
    r.paramValues(scene([4, 4, 8]));
    expect(r.stats()).toEqual({});
  });

  it('"transfer-function" needs a 1D transfer function', () => {
    const tf2d: Scene['transferFunction'] = { dimensions: '2d', widgets: [] };
    const r = new SliceRenderer({ colormap: 'transfer-function' });
    expect(thrown(() => r.validateScene(scene([4, 4, 4], tf2d))).message).toMatch(
      /SLICE\.colormap: "transfer-function" reads a 1D transfer function; the scene's is 2d/,
    );
    expect(() => new SliceRenderer({ colormap: 'viridis' }).validateScene(scene([4, 4, 4], tf2d))).not.toThrow();
  });
});

describe('slice renderer descriptor', () => {
  it('checks scene files as the constructor does (specs, then the vectors and combinations)', () => {
    for (const p of [{ window: [40, 0] }, { axis: 'w' }, { normal: [0, 0, 1], index: 2 }, { point: [0, 0, 0] }]) {
      const direct = thrown(() => new SliceRenderer(p as SliceParams));
      expect(thrown(() => validateRendererParams(SLICE_DESCRIPTOR, p)).message).toBe(direct.message);
    }
    expect(() => validateRendererParams(SLICE_DESCRIPTOR, { axis: 'y', index: 2, window: [40, 400] })).not.toThrow();
  });

  it('says its output is display values without guides, so nothing tone-maps or auto-denoises it', () => {
    expect(SLICE_DESCRIPTOR.displayReferred).toBe(true);
    expect(SLICE_DESCRIPTOR.writesGuides).toBe(false);
    expect(new SliceRenderer().writesGuides).toBe(false);
  });

  it('offers index, sampling, colour map and fit in the quality panel, with the defaults it uses', () => {
    expect(rendererControls(SLICE_DESCRIPTOR).map((c) => [c.name, c.defaultValue ?? c.placeholder])).toEqual([
      ['index', undefined],
      ['sampling', 'nearest'],
      ['colormap', 'grey'],
      ['fit', false],
    ]);
  });
});
