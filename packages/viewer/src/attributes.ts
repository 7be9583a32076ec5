/**
 * Parsing and comparing the element's attribute values. Every parser takes what a
 * person may write (an attribute string: a preset name or JSON; or an object set as a
 * property) and returns the model value, or throws VptError('invalid-scene') with a
 * message that names the attribute. Nothing here touches the GPU.
 */
import {
  MAX_DENSITY_SCALE,
  VptError,
  validateCamera,
  validateClip,
  resolveSlicePlane,
  validateEnvironment,
  validateLights,
  validateTransferFunction,
  TRANSFER_FUNCTION_PRESETS as CORE_TF_PRESETS,
  transferFunctionPreset as coreTransferFunctionPreset,
  type Camera,
  type Clip,
  type SceneSlicePlane,
  type Environment,
  type Light,
  type TransferFunction,
  type TransferFunctionPresetName,
  type Volume,
} from '@vpt/core';
import { TONE_MAP_OPERATORS, type ToneMapOperator } from '@vpt/post';
import { TRANSFER_FUNCTION_PRESETS, transferFunctionPreset } from './presets.js';

export type BackendName = 'auto' | 'webgl2' | 'webgpu';
export const BACKEND_NAMES: readonly BackendName[] = ['auto', 'webgl2', 'webgpu'];

/** An environment given as a URL of a Radiance .hdr (or OpenEXR) lat-long image; loaded asynchronously. */
export interface EnvironmentUrl {
  type: 'url';
  url: string;
  scale?: number;
}
export type EnvironmentValue = Environment | EnvironmentUrl;

const bad = (attribute: string, message: string): never => {
  throw new VptError('invalid-scene', `<vpt-viewer> ${attribute}: ${message}`);
};

/** JSON text → value; a clear message for the typical mistakes. */
function parseJson(attribute: string, text: string): unknown {
  try {
    return JSON.parse(text);
  } catch (e) {
    return bad(attribute, `not valid JSON (${(e as Error).message})`);
  }
}

/** Re-throw core's validation errors with the attribute's name in front. */
function withAttribute<T>(attribute: string, check: () => T): T {
  try {
    return check();
  } catch (e) {
    if (e instanceof VptError) return bad(attribute, e.message);
    throw e;
  }
}

/** Core's 2D presets, fitted to a volume's value range and foreground (core's transferFunctionPreset). */
export function isFittedPreset(name: unknown): name is TransferFunctionPresetName {
  return typeof name === 'string' && (CORE_TF_PRESETS as readonly string[]).includes(name.trim());
}

/**
 * A preset name (the viewer's fixed ones, or core's 2D presets fitted to `volume`) or a
 * transfer-function object / JSON, validated.
 */
export function parseTransferFunction(v: unknown, volume?: Volume): TransferFunction {
  const attribute = 'transfer-function';
  let tf: unknown = v;
  if (typeof v === 'string') {
    const text = v.trim();
    const preset = transferFunctionPreset(text);
    if (preset) return preset;
    if (isFittedPreset(text)) return coreTransferFunctionPreset(text, volume);
    if (!text.startsWith('{'))
      bad(
        attribute,
        `unknown preset "${text}" (presets: ${[...Object.keys(TRANSFER_FUNCTION_PRESETS), ...CORE_TF_PRESETS].join(', ')}; or JSON like {"dimensions":"1d","points":[…]})`,
      );
    tf = parseJson(attribute, text);
  }
  if (!tf || typeof tf !== 'object')
    bad(attribute, `expected a preset name or a transfer-function object, got ${JSON.stringify(tf)}`);
  const copy = structuredClone(tf) as TransferFunction;
  withAttribute(attribute, () => validateTransferFunction(copy));
  return copy;
}

export const DEFAULT_FOVY = 0.7;

export function parseCamera(v: unknown): Camera {
  const attribute = 'camera';
  const c = typeof v === 'string' ? parseJson(attribute, v) : v;
  if (!c || typeof c !== 'object' || Array.isArray(c))
    bad(attribute, 'expected JSON like {"position":[0,0,2],"target":[0,0,0],"up":[0,1,0],"fovy":0.7}');
  const o = c as Partial<Camera>;
  const cam: Camera = {
    position: o.position as Camera['position'],
    target: (o.target ?? [0, 0, 0]) as Camera['target'],
    up: (o.up ?? [0, 1, 0]) as Camera['up'],
    fovy: o.fovy ?? DEFAULT_FOVY,
  };
  withAttribute(attribute, () => validateCamera(cam));
  return { position: [...cam.position], target: [...cam.target], up: [...cam.up], fovy: cam.fovy };
}

export function parseLights(v: unknown): Light[] {
  const attribute = 'lights';
  if (typeof v === 'string' && v.trim() === 'none') return [];
  const l = typeof v === 'string' ? parseJson(attribute, v) : v;
  if (!Array.isArray(l))
    return bad(
      attribute,
      'expected a JSON array like [{"type":"directional","direction":[1,1,1],"irradiance":[3,3,3]}] or "none"',
    );
  const lights = structuredClone(l) as Light[];
  for (const [i, light] of lights.entries()) {
    if (!light || typeof light !== 'object' || !Array.isArray(light.direction) || !Array.isArray(light.irradiance)) {
      bad(attribute, `light ${i} needs "type", "direction" [x,y,z] and "irradiance" [r,g,b]`);
    }
  }
  withAttribute(attribute, () => validateLights(lights));
  return lights;
}

/** A constant radiance as JSON, `{"type":"constant","radiance":[r,g,b]}`, or the URL of a lat-long .hdr image. */
export function parseEnvironment(v: unknown): EnvironmentValue {
  const attribute = 'environment';
  if (typeof v === 'string') {
    const text = v.trim();
    if (!text.startsWith('{')) {
      if (!/\.(hdr|pic|exr)(\?|#|$)/i.test(text))
        bad(
          attribute,
          `expected JSON like {"type":"constant","radiance":[1,1,1]} or the URL of a .hdr/.exr lat-long image, got "${text}"`,
        );
      return { type: 'url', url: text };
    }
    v = parseJson(attribute, text);
  }
  if (!v || typeof v !== 'object') return bad(attribute, 'expected an environment object');
  const env = { ...(v as object) } as EnvironmentValue;
  if (env.type === 'url') {
    if (typeof env.url !== 'string') bad(attribute, '"url" must be a string');
    return { ...env };
  }
  if (env.type === 'constant' && (!Array.isArray(env.radiance) || env.radiance.length !== 3))
    bad(attribute, '"radiance" must be [r, g, b]');
  if (env.type === 'latlong') {
    if (Array.isArray(env.data)) env.data = Float32Array.from(env.data as number[]);
    if (!(env.data instanceof Float32Array))
      bad(attribute, 'a lat-long environment needs "data": width*height*3 floats');
  }
  withAttribute(attribute, () => validateEnvironment(env));
  // Lat-long data (a Float32Array) is kept by identity: copying megabytes per set is waste.
  return env.type === 'constant' ? { type: 'constant', radiance: [...env.radiance] } : env;
}

/**
 * The clip attribute: the scene file's `clip` JSON (`{"planes":[{"normal":[x,y,z],"offset":d}],
 * "box":{"min":[x,y,z],"max":[x,y,z]}}`, world units of the volume box), checked by core's
 * validateClip so the errors name the same fields as a scene file's.
 */
export function parseClip(v: unknown): Clip {
  const attribute = 'clip';
  const c = typeof v === 'string' ? parseJson(attribute, v) : v;
  if (!c || typeof c !== 'object' || Array.isArray(c))
    return bad(attribute, 'expected JSON like {"planes":[{"normal":[1,0,0],"offset":0}],"box":{"min":[…],"max":[…]}}');
  const copy = structuredClone(c) as Clip;
  withAttribute(attribute, () => validateClip(copy, 'clip'));
  return copy;
}

/** The `slice-plane` attribute: the scene file's `slicePlane` JSON (core's scene/slice-plane.ts). */
export function parseSlicePlane(v: unknown): SceneSlicePlane {
  const attribute = 'slice-plane';
  const c = typeof v === 'string' ? parseJson(attribute, v) : v;
  if (!c || typeof c !== 'object' || Array.isArray(c))
    return bad(attribute, 'expected JSON like {"axis":"z","index":40,"window":[40,400],"colormap":"grey"}');
  const copy = structuredClone(c) as SceneSlicePlane;
  withAttribute(attribute, () => resolveSlicePlane(copy, 'slice-plane'));
  return copy;
}

/** Where a crosshair move in the slice panes goes in the 3D view: nowhere, its slice plane, or a clip plane. */
export type Crosshair3D = 'none' | 'slice' | 'clip';
export const CROSSHAIR_3D_MODES: readonly Crosshair3D[] = ['none', 'slice', 'clip'];

export function parseRendererParams(v: unknown): Record<string, unknown> {
  const p = typeof v === 'string' ? (v.trim() === '' ? {} : parseJson('renderer-params', v)) : (v ?? {});
  if (!p || typeof p !== 'object' || Array.isArray(p))
    return bad('renderer-params', 'expected a JSON object like {"stepSize":0.004}');
  return { ...(p as Record<string, unknown>) };
}

export function parseBackend(v: unknown): BackendName {
  if (!BACKEND_NAMES.includes(v as BackendName))
    bad('backend', `must be one of ${BACKEND_NAMES.join(', ')}, got ${JSON.stringify(v)}`);
  return v as BackendName;
}

/** One of a list of names; the error names the attribute and the list. */
export function parseChoice<T extends string>(attribute: string, v: unknown, choices: readonly T[]): T {
  if (!choices.includes(v as T)) bad(attribute, `must be one of ${choices.join(', ')}, got ${JSON.stringify(v)}`);
  return v as T;
}

export function parseToneMapper(v: unknown): ToneMapOperator {
  if (!TONE_MAP_OPERATORS.includes(v as ToneMapOperator))
    bad('tone-mapper', `must be one of ${TONE_MAP_OPERATORS.join(', ')}, got ${JSON.stringify(v)}`);
  return v as ToneMapOperator;
}

/** The denoise attribute: 'auto' denoises while refining (not MIP) and shows the plain estimate once converged. */
export const DENOISE_MODES = ['auto', 'on', 'off'] as const;
export type DenoiseMode = (typeof DENOISE_MODES)[number];

export function parseDenoiseMode(v: unknown): DenoiseMode {
  if (!DENOISE_MODES.includes(v as DenoiseMode))
    bad('denoise', `must be one of ${DENOISE_MODES.join(', ')}, got ${JSON.stringify(v)}`);
  return v as DenoiseMode;
}

/** The temporal attribute: 'on' (default) reuses the image across camera moves, 'off' restarts from nothing. */
export const TEMPORAL_MODES = ['on', 'off'] as const;
export type TemporalMode = (typeof TEMPORAL_MODES)[number];

export function parseNumber(
  attribute: string,
  v: unknown,
  { min = -Infinity, max = Infinity, integer = false } = {},
): number {
  const n = typeof v === 'string' ? Number(v.trim() === '' ? NaN : v) : v;
  if (typeof n !== 'number' || !Number.isFinite(n) || n < min || n > max || (integer && !Number.isInteger(n))) {
    bad(attribute, `must be a${integer ? 'n integer' : ' number'} in [${min}, ${max}], got ${JSON.stringify(v)}`);
  }
  return n as number;
}

/**
 * Objects a parser here made, and so validated: when one comes back as a property's value
 * (from the converter, or the element setting what it parsed) it is not checked again.
 * Parsers return fresh copies, so nothing else holds these objects before the element does.
 */
const parsedValues = new WeakSet<object>();

/** Mark a parser's result as validated (see parsedValues); returns it. */
export function markParsed<T>(value: T): T {
  if (value && typeof value === 'object') parsedValues.add(value);
  return value;
}

/** Whether `value` is an object a parser here made (validated once already). */
export function isParsed(value: unknown): boolean {
  return !!value && typeof value === 'object' && parsedValues.has(value);
}

/** An attribute value that did not parse; the element reports `vpt-error` and keeps the last valid value. */
export class InvalidAttribute {
  constructor(readonly error: unknown) {}
}

/**
 * Converter for object-valued properties: the attribute holds JSON or a preset name, the
 * property the parsed object. Parsing happens here, on the way in, so the attribute keeps
 * what the page wrote (a preset name stays a name) instead of being rewritten as JSON.
 */
export function jsonConverter(parse: (v: unknown) => unknown, keep: (value: string) => boolean = () => false) {
  return {
    fromAttribute: (value: string | null): unknown => {
      if (value === null) return null;
      if (keep(value)) return value; // parsed later, with more context (a preset fitted to the volume)
      try {
        return markParsed(parse(value));
      } catch (e) {
        return new InvalidAttribute(e);
      }
    },
    toAttribute: (value: unknown): string | null =>
      value == null ? null : typeof value === 'string' ? value : JSON.stringify(value, jsonReplacer),
  };
}

/** Typed arrays (lat-long environment data) are not written into attributes. */
function jsonReplacer(_key: string, value: unknown): unknown {
  return ArrayBuffer.isView(value) ? `[${(value as unknown as { length: number }).length} values]` : value;
}

/**
 * Structural equality for attribute values: plain objects and arrays by content,
 * typed arrays by identity (so a lat-long image is not compared element by element).
 */
export function sameValue(a: unknown, b: unknown): boolean {
  if (a === b) return true;
  if (typeof a !== 'object' || typeof b !== 'object' || a === null || b === null)
    return Number.isNaN(a) && Number.isNaN(b);
  if (ArrayBuffer.isView(a) || ArrayBuffer.isView(b)) return false;
  if (Array.isArray(a) !== Array.isArray(b)) return false;
  const ka = Object.keys(a),
    kb = Object.keys(b);
  if (ka.length !== kb.length) return false;
  return ka.every(
    (k) => Object.hasOwn(b, k) && sameValue((a as Record<string, unknown>)[k], (b as Record<string, unknown>)[k]),
  );
}

export const hasChanged = (value: unknown, old: unknown): boolean => !sameValue(value, old);

/** The element's checked properties and the parser each one's value goes through. */
export type CheckedProperty =
  | 'transferFunction'
  | 'camera'
  | 'clip'
  | 'slicePlane'
  | 'crosshair3d'
  | 'crosshairPane'
  | 'lights'
  | 'environment'
  | 'rendererParams'
  | 'backend'
  | 'toneMapper'
  | 'denoise'
  | 'temporal'
  | 'exposure'
  | 'maxSamples'
  | 'targetError'
  | 'densityScale'
  | 'seed'
  | 'resolutionScale'
  | 'renderer';

function propertyParsers(volume: Volume | undefined): Record<CheckedProperty, (v: unknown) => unknown> {
  return {
    transferFunction: (v) => parseTransferFunction(v, volume),
    camera: parseCamera,
    clip: parseClip,
    slicePlane: parseSlicePlane,
    crosshair3d: (v) => parseChoice('crosshair-3d', v, CROSSHAIR_3D_MODES),
    crosshairPane: (v) => parseChoice('crosshair-pane', v, ['axial', 'coronal', 'sagittal'] as const),
    lights: parseLights,
    environment: parseEnvironment,
    rendererParams: parseRendererParams,
    backend: parseBackend,
    toneMapper: parseToneMapper,
    denoise: parseDenoiseMode,
    temporal: (v) => parseChoice('temporal', v, TEMPORAL_MODES),
    exposure: (v) => parseNumber('exposure', v, { min: -64, max: 64 }),
    maxSamples: (v) => parseNumber('max-samples', v, { min: 1, integer: true }),
    targetError: (v) => parseNumber('target-error', v, { min: 0 }),
    densityScale: (v) => parseNumber('density-scale', v, { min: 0, max: MAX_DENSITY_SCALE }),
    seed: (v) => parseNumber('seed', v, { min: 0, max: 0xffffffff, integer: true }),
    resolutionScale: (v) => parseNumber('resolution-scale', v, { min: 0.05, max: 4 }),
    // The name is checked against the registry when it loads; here only its form.
    renderer: (v) =>
      typeof v === 'string' && v.trim() !== ''
        ? v
        : bad('renderer', `must be a renderer name, got ${JSON.stringify(v)}`),
  };
}

export const CHECKED_PROPERTIES = Object.keys(propertyParsers(undefined)) as CheckedProperty[];

/**
 * Validates the element's properties as they change, keeping each one's last valid
 * value: an invalid value (an InvalidAttribute from the converter, or a property set to
 * something that does not parse) is reported and replaced by the last valid one, so the
 * element keeps rendering what it rendered.
 */
export class AttributeValidator {
  private readonly lastValid = new Map<CheckedProperty, unknown>();
  private readonly defaults = new Map<CheckedProperty, unknown>();

  /**
   * Seed each property's "last valid value" with its default, for a first value that is
   * invalid; a removed attribute (null) returns the property to this default.
   */
  constructor(defaults: Record<CheckedProperty, unknown>) {
    for (const key of CHECKED_PROPERTIES) {
      this.lastValid.set(key, defaults[key]);
      this.defaults.set(key, defaults[key]);
    }
  }

  /**
   * Check the properties in `changed` on `target`. Strings set as properties become the
   * parsed objects; objects (from an attribute's converter or a property) are only
   * validated, so an attribute's own text is not rewritten. `volume` fits the 2D presets.
   */
  validate(
    target: Record<CheckedProperty, unknown>,
    changed: { has(key: string): boolean },
    volume: Volume | undefined,
    report: (error: unknown, key: CheckedProperty) => void,
  ): void {
    const parsers = propertyParsers(volume);
    for (const key of CHECKED_PROPERTIES) {
      if (!changed.has(key)) continue;
      const value = target[key];
      if (value === null || value === undefined) {
        // removeAttribute(): back to the default (null itself for camera, lights… whose default is "automatic").
        const fallback = this.defaults.get(key);
        if (fallback !== value && fallback !== null && fallback !== undefined) target[key] = fallback;
        this.lastValid.set(key, fallback);
        continue;
      }
      try {
        if (value instanceof InvalidAttribute) throw value.error;
        if (isParsed(value)) {
          // Parsed (and validated) on its way in: checked once, at that boundary.
          this.lastValid.set(key, value);
          continue;
        }
        const parsed = markParsed(parsers[key](value));
        if (typeof value === 'string' && typeof parsed === 'object') target[key] = parsed;
        this.lastValid.set(key, typeof parsed === 'object' && typeof value !== 'string' ? value : parsed);
      } catch (e) {
        target[key] = this.lastValid.get(key);
        report(e, key);
      }
    }
  }
}
