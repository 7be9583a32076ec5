import { beforeEach, describe, expect, it, vi } from 'vitest';

// Count core's validators as the attribute layer calls them: each value is validated once,
// where it enters the element (the attribute converter, or the property check).
const calls = vi.hoisted(() => ({ camera: 0, transferFunction: 0, lights: 0 }));
vi.mock('@vpt/core', async (importOriginal) => {
  const core = await importOriginal<typeof import('@vpt/core')>();
  return {
    ...core,
    validateCamera: (c: Parameters<typeof core.validateCamera>[0]) => {
      calls.camera++;
      return core.validateCamera(c);
    },
    validateTransferFunction: (tf: Parameters<typeof core.validateTransferFunction>[0]) => {
      calls.transferFunction++;
      return core.validateTransferFunction(tf);
    },
    validateLights: (l: Parameters<typeof core.validateLights>[0]) => {
      calls.lights++;
      return core.validateLights(l);
    },
  };
});

const { AttributeValidator, CHECKED_PROPERTIES, jsonConverter, parseCamera, parseLights, parseTransferFunction } =
  await import('../src/attributes.js');
type Target = Parameters<InstanceType<typeof AttributeValidator>['validate']>[0];

/** An element's checked properties at their defaults (what the validator is seeded with). */
function element(): Target {
  const t = Object.fromEntries(CHECKED_PROPERTIES.map((k) => [k, null])) as Target;
  return Object.assign(t, { exposure: 0, seed: 1, maxSamples: 1024, targetError: 0, resolutionScale: 1 });
}

/** The element's willUpdate for one changed property; returns the errors it reported. */
function change(validator: InstanceType<typeof AttributeValidator>, target: Target, key: string): unknown[] {
  const errors: unknown[] = [];
  validator.validate(target, new Set([key]), undefined, (e) => errors.push(e));
  return errors;
}

beforeEach(() => {
  calls.camera = calls.transferFunction = calls.lights = 0;
});

describe('attribute values are validated once', () => {
  it('an attribute parsed by its converter is not validated again by the property check', () => {
    const target = element();
    const validator = new AttributeValidator(target);
    target.camera = jsonConverter(parseCamera).fromAttribute('{"position":[0,0,3]}');
    target.lights = jsonConverter(parseLights).fromAttribute(
      '[{"type":"directional","direction":[1,1,1],"irradiance":[2,2,2]}]',
    );
    expect(calls).toEqual({ camera: 1, transferFunction: 0, lights: 1 });
    expect(change(validator, target, 'camera')).toEqual([]);
    expect(change(validator, target, 'lights')).toEqual([]);
    expect(calls).toEqual({ camera: 1, transferFunction: 0, lights: 1 });
  });

  it('a string set as a property is parsed once, not again when the parsed object comes back', () => {
    const target = element();
    const validator = new AttributeValidator(target);
    target.transferFunction = '{"dimensions":"1d","points":[{"value":0,"color":[1,1,1],"opacity":0}]}';
    expect(change(validator, target, 'transferFunction')).toEqual([]);
    expect(typeof target.transferFunction).toBe('object');
    // Setting the parsed object is a change Lit reports once more.
    expect(change(validator, target, 'transferFunction')).toEqual([]);
    expect(calls.transferFunction).toBe(1);
  });

  it('an object the page made is validated once, and an invalid one is still refused', () => {
    const target = element();
    const validator = new AttributeValidator(target);
    target.camera = { position: [0, 0, 2], target: [0, 0, 0], up: [0, 1, 0], fovy: 0.7 };
    expect(change(validator, target, 'camera')).toEqual([]);
    expect(calls.camera).toBe(1);
    const good = target.camera;
    target.camera = { position: [0, 0, NaN], target: [0, 0, 0], up: [0, 1, 0], fovy: 0.7 };
    expect(change(validator, target, 'camera').length).toBe(1);
    expect(target.camera).toBe(good); // the last valid value is restored
    expect(calls.camera).toBe(2);
  });

  it('a preset the element sets (applyVolume refits one) is validated once, by the property check', () => {
    const target = element();
    const validator = new AttributeValidator(target);
    target.transferFunction = parseTransferFunction('bone');
    // parseTransferFunction of a preset name copies a fixed, valid preset: no validation at all.
    expect(calls.transferFunction).toBe(0);
    expect(change(validator, target, 'transferFunction')).toEqual([]);
    expect(calls.transferFunction).toBe(1);
  });
});
