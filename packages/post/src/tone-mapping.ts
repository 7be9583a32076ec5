import { preprocess, UniformLayout, VptError, type PostStep, type UniformValues } from '@vpt/core';
import {
  TONE_MAP_DEFINE,
  TONE_MAP_OPERATOR_ID,
  TONE_MAP_OPERATORS,
  isToneMapOperator,
  type ToneMapOperator,
} from './tone-mapping-operators.js';
import * as glsl from './tone-mapping.glsl.js';
import * as wgsl from './tone-mapping.wgsl.js';

export { TONE_MAP_OPERATORS, isToneMapOperator, type ToneMapOperator } from './tone-mapping-operators.js';

// The operator is compile-time; the layout only exists because WGSL forbids empty structs.
const TONE_MAP_UNIFORMS = /* @__PURE__ */ new UniformLayout('ToneMapParams', [{ name: 'pad', type: 'f32' }]);

/**
 * Maps linear HDR colour to [0, 1] with one operator, chosen at compile time so each
 * kernel variant holds only that operator's code. Negative input is treated as 0.
 * The operator is fixed per instance: to switch, put a new step in the chain.
 */
export class ToneMapStep implements PostStep {
  readonly name = 'tonemap';
  readonly glsl: string;
  readonly wgsl: string;
  readonly uniforms = TONE_MAP_UNIFORMS;
  readonly operator: ToneMapOperator;

  constructor(operator: ToneMapOperator = 'aces') {
    this.operator = checkToneMapOperator(operator);
    // Both languages keep only this operator's code, cut by the one core preprocessor.
    const flags = this.defines();
    this.glsl = preprocess(glsl.TONE_MAP, flags);
    this.wgsl = preprocess(wgsl.TONE_MAP, flags);
  }

  uniformValues(): UniformValues {
    return {};
  }

  defines(): Record<string, boolean | number> {
    return { [TONE_MAP_DEFINE]: TONE_MAP_OPERATOR_ID[this.operator] };
  }
}

/** Returns `op` if it names a tone-mapping operator, else throws VptError('invalid-scene'). */
export function checkToneMapOperator(op: unknown, where = 'tone-mapping operator'): ToneMapOperator {
  if (!isToneMapOperator(op)) {
    const got = typeof op === 'string' ? `"${op}"` : op === null ? 'null' : typeof op;
    throw new VptError(
      'invalid-scene',
      `unknown ${where} ${got} (expected one of ${TONE_MAP_OPERATORS.map((o) => `"${o}"`).join(', ')})`,
    );
  }
  return op;
}
