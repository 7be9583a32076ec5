import { VptError } from '../errors.js';
import { validateTransferFunction, type TransferFunction, type TransferWidget } from './transfer-function.js';

/**
 * JSON (de)serialization of transfer functions. The JSON form is the object itself with a
 * fixed key order and only the known keys, so `fromJSON(toJSON(tf))` equals `tf` and
 * `toJSON(fromJSON(text)) === text` for any text `toJSON` wrote (JavaScript prints
 * numbers in the shortest form that reads back to the same double).
 */

const KEYS: Record<string, readonly string[]> = {
  '1d': ['dimensions', 'points'],
  '2d': ['dimensions', 'widgets', 'gradientMax'],
  point: ['value', 'color', 'opacity'],
  gaussian: ['type', 'center', 'width', 'color', 'opacity'],
  box: ['type', 'min', 'max', 'ramp', 'color', 'opacity'],
};

function bad(m: string): never {
  throw new VptError('invalid-scene', `TransferFunction JSON: ${m}`);
}

function checkKeys(o: unknown, kind: string, where: string): void {
  if (!o || typeof o !== 'object' || Array.isArray(o)) bad(`${where} must be an object, got ${JSON.stringify(o)}`);
  const known = KEYS[kind];
  for (const k of Object.keys(o as object)) {
    if (!known.includes(k)) bad(`${where}: unknown field "${k}" (expected ${known.join(', ')})`);
  }
}

/** A copy with the known keys in canonical order (what toJSON writes). */
function canonical(tf: TransferFunction): TransferFunction {
  if (tf.dimensions === '1d') {
    return {
      dimensions: '1d',
      points: tf.points.map((p) => ({ value: p.value, color: [...p.color], opacity: p.opacity })),
    };
  }
  return {
    dimensions: '2d',
    ...(tf.gradientMax !== undefined ? { gradientMax: tf.gradientMax } : {}),
    widgets: tf.widgets.map((w): TransferWidget =>
      w.type === 'gaussian'
        ? { type: 'gaussian', center: [...w.center], width: [...w.width], color: [...w.color], opacity: w.opacity }
        : {
            type: 'box',
            min: [...w.min],
            max: [...w.max],
            ...(w.ramp ? { ramp: [...w.ramp] as [number, number] } : {}),
            color: [...w.color],
            opacity: w.opacity,
          },
    ),
  };
}

/** Serialize a (valid) transfer function to JSON text. Throws VptError('invalid-scene') for an invalid one. */
export function transferFunctionToJSON(tf: TransferFunction, space?: number): string {
  validateTransferFunction(tf);
  return JSON.stringify(canonical(tf), null, space);
}

/**
 * Parse and validate a transfer function from JSON text (or an already parsed value).
 * Unknown fields, unknown widget types, non-finite numbers (JSON has no NaN: it arrives
 * as null or a string) and negative opacities are rejected with a VptError('invalid-scene')
 * that names the field.
 */
export function transferFunctionFromJSON(json: string | unknown): TransferFunction {
  let value: unknown = json;
  if (typeof json === 'string') {
    try {
      value = JSON.parse(json);
    } catch (e) {
      bad(`not valid JSON (${(e as Error).message})`);
    }
  }
  const dims = (value as { dimensions?: unknown } | null)?.dimensions;
  if (dims !== '1d' && dims !== '2d') bad(`unknown dimensions ${JSON.stringify(dims)} (supported: "1d", "2d")`);
  checkKeys(value, dims, 'the transfer function');
  const tf = value as TransferFunction;
  if (tf.dimensions === '1d') {
    if (Array.isArray(tf.points)) tf.points.forEach((p, i) => checkKeys(p, 'point', `point ${i}`));
  } else if (Array.isArray(tf.widgets)) {
    tf.widgets.forEach((w, i) => {
      const type = (w as { type?: unknown } | null)?.type;
      if (type !== 'gaussian' && type !== 'box')
        bad(`widget ${i}: unknown widget type ${JSON.stringify(type)} (supported: gaussian, box)`);
      checkKeys(w, type, `widget ${i}`);
    });
  }
  try {
    validateTransferFunction(tf);
  } catch (e) {
    // Same prefix as every JSON error; a limit stays limit-exceeded.
    if (e instanceof VptError)
      throw new VptError(e.code, `TransferFunction JSON: ${e.message.replace(/^TransferFunction: /, '')}`);
    throw e;
  }
  return canonical(tf);
}
