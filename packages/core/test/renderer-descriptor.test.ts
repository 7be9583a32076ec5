import { describe, expect, it } from 'vitest';
import { expectVptError, testScene } from '../../../tests/helpers/test-scene.js';
import {
  createProceduralVolume,
  defineRenderer,
  paramSpecsOf,
  paramUniformFields,
  paramUniformValues,
  rendererControls,
  resolveRendererParams,
  stepInVoxels,
  validateRendererParams,
  type ParamsOf,
} from '../src/index.js';

// A probe descriptor with one parameter of each kind, a rename, a packed uniform and a rule across parameters.
const PROBE = defineRenderer({
  name: 'probe',
  label: 'Probe',
  owner: 'PROBE',
  params: {
    stepSize: {
      kind: 'step',
      ...stepInVoxels(2),
      ui: { label: 'Step', min: 0.001, max: 0.1 },
      uniform: { type: 'f32' },
    },
    gain: {
      kind: 'number',
      min: 0,
      max: 4,
      default: 0.25,
      ui: { label: 'Gain', step: 0.5 },
      uniform: { name: 'probeGain', type: 'f32' },
    },
    depth: {
      kind: 'number',
      integer: true,
      min: -1,
      max: 8,
      default: -1,
      defaultText: 'unlimited',
      uniform: { type: 'i32', pack: (d, p) => (p.mode === 'one' ? 1 : d) },
    },
    mode: { kind: 'enum', values: ['one', 'many'], uiValues: ['many', 'one'], default: 'many', ui: { label: 'Mode' } },
    fast: { kind: 'boolean', default: false, ui: { label: 'Fast' } },
    hidden: { kind: 'boolean', default: true },
    list: {
      kind: 'custom',
      default: [1, 2] as number[],
      controls: [{ name: 'first', label: 'First', read: (p) => (p.list as number[] | undefined)?.[0] }],
    },
  },
  check: (p) => {
    if (p.fast === true && p.mode === 'one') throw new Error('fast needs many');
  },
  writesGuides: false,
  needs: { transferFunction: true, lights: false, environment: false },
});

describe('renderer descriptor', () => {
  it('types the parameter object from the table', () => {
    const p: ParamsOf<typeof PROBE> = { mode: 'one', gain: 1, list: [3] };
    // @ts-expect-error -- not one of the enum's values
    const bad: ParamsOf<typeof PROBE> = { mode: 'none' };
    expect([p.mode, bad.mode]).toEqual(['one', 'none']);
  });

  it('derives the validator specs: number rules, steps, enums, booleans, custom', () => {
    const specs = paramSpecsOf(PROBE);
    expect(specs.gain).toEqual({ kind: 'number', min: 0, max: 4 });
    expect(specs.depth).toEqual({ kind: 'number', integer: true, min: -1, max: 8 });
    expect(specs.stepSize).toEqual({ kind: 'step' });
    expect(specs.mode).toEqual({ kind: 'enum', values: ['one', 'many'] });
    expect(specs.list).toEqual({ kind: 'custom' });
  });

  it('validates unknown keys, ranges, then the rule across parameters', () => {
    expectVptError(() => validateRendererParams(PROBE, { gian: 1 }), 'invalid-scene', /gian/);
    expectVptError(() => validateRendererParams(PROBE, { gain: 5 }), 'invalid-scene', /PROBE\.gain/);
    expectVptError(() => validateRendererParams(PROBE, { depth: 1.5 }), 'invalid-scene', /PROBE\.depth/);
    expectVptError(() => validateRendererParams(PROBE, { mode: 'all' }), 'invalid-scene', /PROBE\.mode/);
    expect(() => validateRendererParams(PROBE, { fast: true, mode: 'one' })).toThrow(/fast needs many/);
    expect(() => validateRendererParams(PROBE, { fast: true, gain: 4 })).not.toThrow();
  });

  it('fills defaults: constants always, scene-dependent ones with a scene; set values win', () => {
    expect(resolveRendererParams(PROBE, { gain: 2 })).toEqual({
      gain: 2,
      depth: -1,
      mode: 'many',
      fast: false,
      hidden: true,
      list: [1, 2],
    });
    const scene = testScene({ volume: createProceduralVolume('sphere', 16) });
    expect(resolveRendererParams(PROBE, {}, scene).stepSize).toBe(2 / 16);
    expect(resolveRendererParams(PROBE, { stepSize: 0.01 }, scene).stepSize).toBe(0.01);
  });

  it('packs uniforms under their own names, in table order, through pack()', () => {
    expect(paramUniformFields(PROBE)).toEqual([
      { name: 'stepSize', type: 'f32' },
      { name: 'probeGain', type: 'f32' },
      { name: 'depth', type: 'i32' },
    ]);
    const scene = testScene({ volume: createProceduralVolume('sphere', 8) });
    expect(paramUniformValues(PROBE, resolveRendererParams(PROBE, {}, scene))).toEqual({
      stepSize: 0.25,
      probeGain: 0.25,
      depth: -1,
    });
    expect(paramUniformValues(PROBE, resolveRendererParams(PROBE, { mode: 'one' }, scene)).depth).toBe(1);
    // An unlimited gain would be Infinity in the uniform: refused.
    expectVptError(
      () => paramUniformValues(PROBE, resolveRendererParams(PROBE, { gain: Infinity }, scene)),
      'invalid-scene',
      /PROBE\.gain: no finite uniform value \(got Infinity\)/,
    );
    // Without the scene the step has no value: refused rather than NaN in a uniform.
    expectVptError(
      () => paramUniformValues(PROBE, resolveRendererParams(PROBE, {})),
      'invalid-scene',
      /PROBE\.stepSize/,
    );
  });

  it('offers the controls with ui, placeholders written from the defaults', () => {
    const controls = rendererControls(PROBE);
    expect(controls.map((c) => c.name)).toEqual(['stepSize', 'gain', 'mode', 'fast', 'first']);
    expect(controls[0]).toEqual({ name: 'stepSize', label: 'Step', min: 0.001, max: 0.1, placeholder: '2 voxels' });
    expect(controls[1]).toEqual({ name: 'gain', label: 'Gain', min: 0, max: 4, step: 0.5, placeholder: '0.25' });
    expect(controls[2]).toEqual({
      name: 'mode',
      label: 'Mode',
      kind: 'select',
      options: ['many', 'one'],
      defaultValue: 'many',
    });
    expect(controls[3]).toEqual({ name: 'fast', label: 'Fast', kind: 'boolean', defaultValue: false });
  });

  it('writes a step default in words and refuses a scene-dependent default without them', () => {
    expect([0.5, 1, 1.5].map((v) => stepInVoxels(v).defaultText)).toEqual(['half a voxel', '1 voxel', '1.5 voxels']);
    expect(() =>
      defineRenderer({
        ...PROBE,
        params: { stepSize: { kind: 'step', default: () => 1 } },
      }),
    ).toThrow(/PROBE\.stepSize: a scene-dependent default needs defaultText/);
  });
});
