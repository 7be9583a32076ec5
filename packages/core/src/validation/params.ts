import { checkBoolean, checkKnownKeys, checkNumber, checkObject, checkOneOf, fail, type NumberRule } from './checks.js';
import { MAX_MARCH_STEPS, MIN_STEP_SIZE, MIN_STEP_VOXELS } from './limits.js';

/**
 * How a renderer declares its parameters, so that one validator checks them all (the
 * constructor, `setParams`, the headless scene files and the viewer's `renderer-params`
 * attribute): unknown keys are refused, numbers are checked against their range and the
 * float32 range. A renderer's own resolver may add rules across parameters.
 */
export type ParamSpec =
  | ({ kind: 'number' } & NumberRule)
  /** A ray-march step in world units: NumberRule plus, per scene, at least MIN_STEP_VOXELS voxels. */
  | { kind: 'step' }
  | { kind: 'enum'; values: readonly string[] }
  | { kind: 'boolean' }
  /** Checked by the renderer itself (e.g. a list of isosurfaces). */
  | { kind: 'custom' };

export type ParamSpecs = Readonly<Record<string, ParamSpec>>;

/** The scene-independent rule of a 'step' parameter. */
export const STEP_RULE: NumberRule = { min: MIN_STEP_SIZE, max: 1, unit: "world units; the box's longest side is 1" };

/** Check parameters against their declared specs; throws VptError('invalid-scene') naming `owner.key`. */
export function validateParams(owner: string, specs: ParamSpecs, params: unknown): void {
  const obj = checkObject(`${owner} parameters`, params);
  checkKnownKeys(`${owner} parameters`, obj, Object.keys(specs));
  for (const [key, spec] of Object.entries(specs)) {
    const v = obj[key];
    if (v === undefined) continue;
    const field = `${owner}.${key}`;
    switch (spec.kind) {
      case 'number':
        checkNumber(field, v, spec);
        break;
      case 'step':
        checkNumber(field, v, STEP_RULE);
        break;
      case 'enum':
        checkOneOf(field, v, spec.values);
        break;
      case 'boolean':
        checkBoolean(field, v);
        break;
      case 'custom':
        break;
    }
  }
}

/** The smallest step accepted for a volume of these dims: MIN_STEP_VOXELS voxels of its largest dimension. */
export function minStepSize(dims: readonly number[]): number {
  return Math.max(MIN_STEP_SIZE, MIN_STEP_VOXELS / Math.max(...dims));
}

/**
 * The scene-dependent part: every 'step' parameter must be at least MIN_STEP_VOXELS voxels,
 * so a march across the box takes at most √3·max(dims)/MIN_STEP_VOXELS samples (below
 * MAX_MARCH_STEPS for dims ≤ 2048; the kernels clamp to MAX_MARCH_STEPS anyway).
 */
export function validateStepParams(
  owner: string,
  specs: ParamSpecs | undefined,
  params: Record<string, unknown> | undefined,
  dims: readonly number[],
): void {
  if (!specs || !params) return;
  const min = minStepSize(dims);
  for (const [key, spec] of Object.entries(specs)) {
    const v = params[key];
    if (spec.kind !== 'step' || v === undefined) continue;
    if (typeof v !== 'number' || !(v >= min)) {
      fail(
        `${owner}.${key}`,
        `${describeStep(v)} is below the smallest step for a volume of dims [${dims.join(', ')}]: ${min} world units (${MIN_STEP_VOXELS} voxel; a march is limited to ${MAX_MARCH_STEPS} steps)`,
      );
    }
  }
}

function describeStep(v: unknown): string {
  return typeof v === 'number' ? String(v) : JSON.stringify(v);
}
