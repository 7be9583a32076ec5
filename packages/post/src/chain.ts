import { VptError, type PostStep } from '@vpt/core';
import { DenoiseStep, DENOISE_PARAM_NAMES, checkDenoiseParams, type DenoiseParams } from './denoise.js';
import { ExposureStep, checkExposure } from './exposure.js';
import { SrgbEncodeStep } from './srgb.js';
import { ToneMapStep, checkToneMapOperator, type ToneMapOperator } from './tone-mapping.js';

/** A post step in a scene description. Omitted parameters take the step's defaults. */
export type PostStepJSON =
  | { type: 'exposure'; exposure?: number }
  | { type: 'tonemap'; operator?: ToneMapOperator }
  | { type: 'srgb' }
  | ({ type: 'denoise' } & DenoiseParams);

export interface DefaultPostChainOptions {
  /** Stops; default 0. */
  exposure?: number;
  /** Default 'aces'. */
  toneMapper?: ToneMapOperator;
  /**
   * The HDR image holds display values already (a renderer descriptor's `displayReferred`):
   * exposure → clamp, no tone curve (`toneMapper` does not apply) and no sRGB encoding.
   */
  displayReferred?: boolean;
}

/** Exposure → tone map → sRGB: HDR linear radiance in, display-ready sRGB out (display values: exposure → clamp). */
export function defaultPostChain(options: DefaultPostChainOptions = {}): PostStep[] {
  if (options.displayReferred) return [new ExposureStep(options.exposure ?? 0), new ToneMapStep('clamp')];
  return [new ExposureStep(options.exposure ?? 0), new ToneMapStep(options.toneMapper ?? 'aces'), new SrgbEncodeStep()];
}

// Keys each step type accepts: anything else is most likely a typo and is reported, not ignored.
const KEYS: Readonly<Record<PostStepJSON['type'], readonly string[]>> = {
  exposure: ['type', 'exposure'],
  tonemap: ['type', 'operator'],
  srgb: ['type'],
  denoise: ['type', ...DENOISE_PARAM_NAMES],
};

/** Build a step from its scene-description JSON; throws VptError('invalid-scene') for anything malformed. */
export function postStepFromJSON(json: unknown, where = 'post step'): PostStep {
  if (typeof json !== 'object' || json === null || Array.isArray(json)) {
    throw new VptError(
      'invalid-scene',
      `${where} must be an object like {"type": "srgb"}, got ${json === null ? 'null' : Array.isArray(json) ? 'an array' : typeof json}`,
    );
  }
  const obj = json as Record<string, unknown>;
  const type = obj.type;
  if (typeof type !== 'string' || !Object.hasOwn(KEYS, type)) {
    const got = typeof type === 'string' ? `"${type}"` : type === undefined ? 'no "type"' : typeof type;
    throw new VptError(
      'invalid-scene',
      `${where} has unknown type ${got} (expected one of ${Object.keys(KEYS)
        .map((k) => `"${k}"`)
        .join(', ')})`,
    );
  }
  const allowed = KEYS[type as PostStepJSON['type']];
  for (const key of Object.keys(obj)) {
    if (!allowed.includes(key)) {
      throw new VptError(
        'invalid-scene',
        `${where} of type "${type}" has unknown field "${key}" (allowed: ${allowed.map((k) => `"${k}"`).join(', ')})`,
      );
    }
  }
  switch (type as PostStepJSON['type']) {
    case 'exposure':
      return new ExposureStep(obj.exposure === undefined ? 0 : checkExposure(obj.exposure, `${where}: exposure`));
    case 'tonemap':
      return new ToneMapStep(
        obj.operator === undefined ? 'aces' : checkToneMapOperator(obj.operator, `${where}: tone-mapping operator`),
      );
    case 'srgb':
      return new SrgbEncodeStep();
    case 'denoise': {
      const { type: _type, ...params } = obj;
      return new DenoiseStep(checkDenoiseParams(params, where));
    }
  }
}

/** Build a chain from a JSON array of step descriptions (see postStepFromJSON). */
export function postChainFromJSON(json: unknown): PostStep[] {
  if (!Array.isArray(json)) {
    throw new VptError(
      'invalid-scene',
      `the post chain must be an array of steps, got ${json === null ? 'null' : typeof json}`,
    );
  }
  const steps = json.map((step, i) => postStepFromJSON(step, `post step ${i}`));
  // A step that filters radiance (the denoiser) reads the HDR image and the renderer's guides:
  // after a step that left radiance (exposure, tone mapping, sRGB) it has neither.
  const firstDisplay = steps.findIndex((s) => !s.keepsRadiance);
  steps.forEach((s, i) => {
    if (s.keepsRadiance && firstDisplay >= 0 && i > firstDisplay)
      throw new VptError(
        'invalid-scene',
        `post step ${i} ("${s.name}") must come before post step ${firstDisplay} ("${steps[firstDisplay].name}"): it filters linear HDR radiance, so it goes first in the chain`,
      );
  });
  return steps;
}

/** The scene-description JSON of one of this package's steps. */
export function postStepToJSON(step: PostStep): PostStepJSON {
  if (step instanceof ExposureStep) return { type: 'exposure', exposure: step.exposure };
  if (step instanceof ToneMapStep) return { type: 'tonemap', operator: step.operator };
  if (step instanceof SrgbEncodeStep) return { type: 'srgb' };
  if (step instanceof DenoiseStep) return { type: 'denoise', ...step.getParams() };
  throw new VptError('invalid-scene', `post step "${step.name}" is not one of @vpt/post's steps and has no JSON form`);
}

export function postChainToJSON(steps: readonly PostStep[]): PostStepJSON[] {
  return steps.map(postStepToJSON);
}
