import { VptError, type VptErrorCode } from '../errors.js';
import { FLOAT32_MAX, MAX_TEXTURE_SIDE_2D } from './limits.js';

/**
 * Field checks shared by every validator (the scene model, renderer parameters, the
 * headless scene files, the viewer's attributes). Each throws a VptError whose message
 * starts with the field's path and names the rule or limit it broke, e.g.
 * `environment.radiance[0]: 1e+39 exceeds the float32 range (3.4028234663852886e+38)`.
 */

/** A readable rendering of any value for messages (numbers as numbers, never "[object Object]"). */
export function describeValue(x: unknown): string {
  if (typeof x === 'number') return String(x);
  if (typeof x === 'string') return JSON.stringify(x.length > 60 ? `${x.slice(0, 57)}...` : x);
  if (x === undefined) return 'nothing';
  if (ArrayBuffer.isView(x)) return `a ${x.constructor.name}`;
  try {
    const s = JSON.stringify(x);
    if (s === undefined) return typeof x;
    return s.length > 80 ? `${s.slice(0, 77)}...` : s;
  } catch {
    return typeof x;
  }
}

export function fail(field: string, message: string, code: VptErrorCode = 'invalid-scene'): never {
  throw new VptError(code, `${field}: ${message}`);
}

export interface NumberRule {
  /** Inclusive bounds unless the exclusive flags say otherwise. */
  min?: number;
  max?: number;
  exclusiveMin?: boolean;
  exclusiveMax?: boolean;
  integer?: boolean;
  /** Accept +Infinity (e.g. "unlimited"); otherwise the value must be a finite float32. */
  allowInfinity?: boolean;
  /** Error code when the value is a number above `max` (a limit rather than a rule). */
  maxCode?: VptErrorCode;
  /** Unit named in messages ("world units", "radians"…). */
  unit?: string;
}

/** An integer from `min` (default 1) to a limit of vpt's: above it is 'limit-exceeded', named with `unit`. */
export function countUpTo(max: number, unit?: string, min = 1): NumberRule {
  return { min, max, integer: true, maxCode: 'limit-exceeded', ...(unit ? { unit } : {}) };
}

/** The rule for a lat-long environment's width and height: one less than the 2D limit, for the CDF tables' extra column. */
export const LATLONG_SIDE_RULE: NumberRule = countUpTo(MAX_TEXTURE_SIDE_2D - 1, 'texels');

function rangeText(r: NumberRule): string {
  const lo = r.min === undefined ? '' : `${r.exclusiveMin ? '>' : '>='} ${r.min}`;
  const hi = r.max === undefined ? '' : `${r.exclusiveMax ? '<' : '<='} ${r.max}`;
  const both = [lo, hi].filter(Boolean).join(' and ');
  return `${r.integer ? 'an integer' : 'a number'}${both ? ` ${both}` : ''}${r.unit ? ` (${r.unit})` : ''}`;
}

/**
 * A number the GPU can hold: a JS number, finite in float32 (|x| ≤ 3.4028e38: a value finite
 * in float64 but not in float32 would become Infinity on upload), within the rule's bounds.
 */
export function checkNumber(field: string, x: unknown, rule: NumberRule = {}): number {
  if (typeof x !== 'number' || Number.isNaN(x)) fail(field, `must be ${rangeText(rule)}, got ${describeValue(x)}`);
  const n = x as number;
  const unlimited = rule.allowInfinity && n === Infinity;
  if (!unlimited) {
    if (!Number.isFinite(n)) fail(field, `must be finite, got ${n}`);
    if (Math.abs(n) > FLOAT32_MAX) fail(field, `${n} exceeds the float32 range (±${FLOAT32_MAX}) the GPU computes in`);
    if (rule.integer && !Number.isInteger(n)) fail(field, `must be ${rangeText(rule)}, got ${n}`);
  }
  if (rule.min !== undefined && (rule.exclusiveMin ? !(n > rule.min) : !(n >= rule.min)))
    fail(field, `must be ${rangeText(rule)}, got ${n}`);
  if (!unlimited && rule.max !== undefined && (rule.exclusiveMax ? !(n < rule.max) : !(n <= rule.max))) {
    fail(field, `${n} is above the limit: must be ${rangeText(rule)}`, rule.maxCode ?? 'invalid-scene');
  }
  return n;
}

/** A fixed-length array of numbers, each checked by `rule`. */
export function checkNumbers(field: string, x: unknown, length: number, rule: NumberRule = {}): number[] {
  if (!Array.isArray(x) || x.length !== length)
    fail(field, `must be an array of ${length} numbers, got ${describeValue(x)}`);
  return (x as unknown[]).map((v, i) => checkNumber(`${field}[${i}]`, v, rule));
}

export function checkOneOf<T extends string>(field: string, x: unknown, allowed: readonly T[]): T {
  if (typeof x !== 'string' || !allowed.includes(x as T))
    fail(field, `must be one of ${allowed.map((a) => JSON.stringify(a)).join(', ')}, got ${describeValue(x)}`);
  return x as T;
}

export function checkBoolean(field: string, x: unknown): boolean {
  if (typeof x !== 'boolean') fail(field, `must be true or false, got ${describeValue(x)}`);
  return x as boolean;
}

export function checkString(field: string, x: unknown): string {
  if (typeof x !== 'string' || x.length === 0) fail(field, `must be a non-empty string, got ${describeValue(x)}`);
  return x as string;
}

/** A plain object (not null, not an array). */
export function checkObject(field: string, x: unknown): Record<string, unknown> {
  if (!x || typeof x !== 'object' || Array.isArray(x) || ArrayBuffer.isView(x))
    fail(field, `must be an object, got ${describeValue(x)}`);
  return x as Record<string, unknown>;
}

/** Refuse keys outside `known`, naming the first unknown one and listing the known ones. */
export function checkKnownKeys(field: string, obj: Record<string, unknown>, known: readonly string[]): void {
  for (const k of Object.keys(obj)) {
    if (!known.includes(k)) fail(field, `unknown key ${JSON.stringify(k)} (known: ${known.join(', ')})`);
  }
}
