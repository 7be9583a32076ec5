/**
 * A renderer described by one object: its name, label, parameters (kind, range,
 * default, UI hints, uniform), its viewer look, whether it writes denoiser guides and what
 * it reads from the scene. Each renderer package exports its descriptor from a small,
 * side-effect-free `descriptor.ts` (also the subpath `@vpt/renderer-<name>/descriptor`), so
 * a user interface reads the parameters without loading the kernels. Everything else is
 * derived here: the parameter type (`ParamsOf`), validation (`validateRendererParams`),
 * defaults (`resolveRendererParams`), uniform fields and values, the quality panel's
 * controls (`rendererControls`), the checks the headless CLI runs.
 *
 * After Mitsuba 3's plugin doc tables and `props.get(name, default)`, pbrt-v4's one
 * `Create` switch, and luma.gl's ShaderModule (uniform types and defaults with the code).
 */
import { VptError } from '../errors.js';
import type { ChannelSettings } from '../scene/channels.js';
import type { Scene } from '../scene/scene.js';
import type { TransferFunction } from '../scene/transfer-function.js';
import type { UniformField, UniformValues } from '../uniforms/layout.js';
import type { NumberRule } from '../validation/checks.js';
import { validateParams, type ParamSpec, type ParamSpecs } from '../validation/params.js';

/**
 * A renderer parameter a user interface offers (the viewer's quality panel). `undefined` in
 * the parameter object means the renderer's own default. `read`/`write` reach into nested
 * parameters (the first isosurface's value, say); without them the parameter is `params[name]`.
 */
export interface RendererParamSpec {
  name: string;
  label: string;
  kind?: 'number' | 'select' | 'boolean' | 'color';
  min?: number;
  max?: number;
  step?: number;
  options?: readonly string[];
  /** Shown next to an empty field (the renderer's default, in words). */
  placeholder?: string;
  /** The renderer's default, shown by boolean and select controls when the parameter is unset. */
  defaultValue?: unknown;
  read?(params: Record<string, unknown>): unknown;
  write?(params: Record<string, unknown>, value: unknown): Record<string, unknown>;
}

/** How a user interface offers one parameter; a parameter without `ui` is not offered. */
export interface ParamUi {
  label: string;
  /** Increment of a number field. */
  step?: number;
  /** Number field bounds, where they are narrower than the accepted range (a step's sensible span). */
  min?: number;
  max?: number;
}

/** A parameter that is also a uniform of the renderer's kernels. */
export interface ParamUniform<T> {
  /** The uniform's name, where it differs from the parameter's (`anisotropy` → `phaseG`). */
  name?: string;
  type: 'f32' | 'i32' | 'u32';
  /** The uniform value of the resolved parameter (default: the value itself). */
  pack?(value: T, params: Readonly<Record<string, unknown>>): number;
}

interface ParamBase<T> {
  /** The value when the parameter is unset: a constant, or a function of the scene (a step in voxels). */
  readonly default?: T | ((scene: Scene) => T);
  /** The default in words for user interfaces; required when `default` is a function. */
  readonly defaultText?: string;
  readonly ui?: ParamUi;
  readonly uniform?: ParamUniform<T>;
}

export interface NumberParam extends ParamBase<number>, NumberRule {
  readonly kind: 'number';
}
/** A ray-march step in world units: NumberRule plus, per scene, at least MIN_STEP_VOXELS voxels (core's 'step' spec). */
export interface StepParam extends ParamBase<number> {
  readonly kind: 'step';
}
export interface EnumParam<V extends string = string> extends ParamBase<V> {
  readonly kind: 'enum';
  readonly values: readonly V[];
  /** Values a user interface offers (default: all). */
  readonly uiValues?: readonly V[];
}
export interface BooleanParam extends ParamBase<boolean> {
  readonly kind: 'boolean';
}
/** Checked by the descriptor's `check` hook (a list of isosurfaces); `controls` edit parts of it. Its type is its default's. */
export interface CustomParam<T = unknown> extends ParamBase<T> {
  readonly kind: 'custom';
  readonly controls?: readonly RendererParamSpec[];
}

export type RendererParam = NumberParam | StepParam | EnumParam | BooleanParam | CustomParam<any>;
export type RendererParams = Readonly<Record<string, RendererParam>>;

/** The parameter object type of a descriptor: every parameter optional, typed by its kind. */
export type ParamsOf<D extends { params: RendererParams }> = {
  -readonly [K in keyof D['params']]?: ValueOf<D['params'][K]>;
};
/** A parameter's value type: by kind; an enum's is the union of its values, a custom one's its default's type. */
type ValueOf<P> = P extends { kind: 'number' | 'step' }
  ? number
  : P extends { kind: 'boolean' }
    ? boolean
    : P extends { kind: 'enum'; values: readonly (infer V)[] }
      ? V
      : P extends { kind: 'custom'; default?: infer T }
        ? T
        : never;

/** The viewer's look for a renderer: how its default scene is lit and its automatic transfer function adapted. */
export interface RendererLookDefaults {
  /** Extinction per world unit at opacity 1 that suits the automatic transfer function. */
  densityScale: number;
  /** Radiance of the constant environment. */
  environment: readonly [number, number, number];
  /** Irradiance of one directional key light above the camera's shoulder; absent: no lights. */
  keyLight?: readonly [number, number, number];
  /** The automatic transfer function: as is (default), its colours scaled, or its colours used as albedo. */
  transferFunction?: 'as-is' | 'albedo' | { scaleColors: number };
  /**
   * Parameters that depend on the automatic transfer function, used while the user set none;
   * for a multichannel volume `channels` holds the drawn channels' settings, in order (their
   * own functions and colours).
   */
  params?(tf: TransferFunction | null, channels?: readonly ChannelSettings[]): Record<string, unknown>;
}

/** What a renderer reads from the scene besides the volume (declarative: for documentation and user interfaces). */
export interface RendererInputs {
  transferFunction: boolean;
  lights: boolean;
  environment: boolean;
  /** The gradient-magnitude volume (built by the context when set, see Renderer.needsGradient). */
  gradient?: boolean;
}

export interface RendererDescriptor<P extends RendererParams = RendererParams> {
  /** The name scenes, attributes and configurations use (`renderer: 'mcrt'`); equals the catalog's. */
  readonly name: string;
  /** Shown in user interfaces. */
  readonly label: string;
  /** Prefix of error messages ("MIP.stepSize: …"). */
  readonly owner: string;
  readonly params: P;
  /** Rules across parameters, run after the per-parameter checks; throws VptError('invalid-scene'). */
  check?(params: Readonly<Record<string, unknown>>): void;
  /** The generate kernel writes the denoiser's guides (see Renderer.writesGuides): the viewer denoises it by default. */
  readonly writesGuides: boolean;
  /**
   * false: the viewer's `denoise="auto"` does not filter while the camera moves (it does while the
   * image refines at rest). For a renderer nearly noise-free at a few samples (EAM), whose image in
   * motion the filter blurs more than it cleans and whose per-frame cost lowers adaptive
   * resolution's render size (docs/benchmarks.md, "Orbit"). Default true.
   */
  readonly denoiseWhileMoving?: boolean;
  /**
   * The HDR image holds display values (linear, in [0, 1], a colour map's components) rather
   * than radiance: user interfaces and the CLI show it through exposure and a clamp, with no
   * tone curve and no sRGB encoding, so a PFM and the PNG hold the same values. Default false.
   */
  readonly displayReferred?: boolean;
  readonly needs: RendererInputs;
  /** The viewer's default look (absent: the emission–absorption look). */
  readonly look?: RendererLookDefaults;
}

/** Type the parameter table of a descriptor (keeps each entry's literal kind and values for ParamsOf). */
export function defineRenderer<const P extends RendererParams>(d: RendererDescriptor<P>): RendererDescriptor<P> {
  for (const [key, p] of Object.entries(d.params)) {
    if (typeof p.default === 'function' && p.defaultText === undefined)
      throw new VptError('invalid-scene', `${d.owner}.${key}: a scene-dependent default needs defaultText`);
  }
  return d;
}

/** A step default of `voxels` voxels along the volume's longest side, in world units. */
export function stepInVoxels(voxels: number): Pick<StepParam, 'default' | 'defaultText'> {
  return {
    default: (scene: Scene) => voxels / Math.max(...scene.volume.dims),
    defaultText: `${voxels === 0.5 ? 'half a' : voxels} voxel${voxels > 1 ? 's' : ''}`,
  };
}

/** The validator specs (core's validateParams, validateStepParams) of a descriptor. */
export function paramSpecsOf(d: RendererDescriptor): ParamSpecs {
  return Object.fromEntries(Object.entries(d.params).map(([k, p]) => [k, specOf(p)]));
}

function specOf(p: RendererParam): ParamSpec {
  switch (p.kind) {
    case 'number': {
      const { kind: _k, default: _d, defaultText: _t, ui: _u, uniform: _n, ...rule } = p;
      return { kind: 'number', ...rule };
    }
    case 'enum':
      return { kind: 'enum', values: p.values };
    default:
      return { kind: p.kind };
  }
}

/** Check a parameter object: unknown keys, each declared range, then the descriptor's rules across them. */
export function validateRendererParams(d: RendererDescriptor, params: unknown): void {
  validateParams(d.owner, paramSpecsOf(d), params);
  d.check?.(params as Record<string, unknown>);
}

/**
 * The parameters with every default filled in: set values win; a scene-dependent default
 * is filled only with a scene. `undefined` counts as unset.
 */
export function resolveRendererParams<D extends RendererDescriptor>(
  d: D,
  params: Readonly<Record<string, unknown>>,
  scene?: Scene,
): Record<string, unknown> {
  const out: Record<string, unknown> = {};
  for (const [key, p] of Object.entries(d.params)) {
    const v = params[key];
    if (v !== undefined) out[key] = v;
    else if (typeof p.default === 'function') {
      if (scene) out[key] = (p.default as (s: Scene) => unknown)(scene);
    } else if (p.default !== undefined) out[key] = p.default;
  }
  return out;
}

/** The scene-independent default of a parameter (undefined for a scene-dependent one or none). */
export function constantDefault(d: RendererDescriptor, key: string): unknown {
  const p = d.params[key];
  return typeof p?.default === 'function' ? undefined : p?.default;
}

/** The uniform fields of the parameters that are uniforms, in the table's order. */
export function paramUniformFields(d: RendererDescriptor): UniformField[] {
  return Object.entries(d.params).flatMap(([k, p]) =>
    p.uniform ? [{ name: p.uniform.name ?? k, type: p.uniform.type }] : [],
  );
}

/** The uniform values of resolved parameters (resolveRendererParams with the scene); throws VptError('invalid-scene') for a missing or non-finite one. */
export function paramUniformValues(d: RendererDescriptor, resolved: Readonly<Record<string, unknown>>): UniformValues {
  const out: UniformValues = {};
  for (const [k, p] of Object.entries(d.params)) {
    if (!p.uniform) continue;
    const v = resolved[k];
    const packed = p.uniform.pack ? (p.uniform.pack as (v: unknown, r: typeof resolved) => number)(v, resolved) : v;
    // A uniform is a finite number: NaN or Infinity would reach the accumulation buffers.
    if (typeof packed !== 'number' || !Number.isFinite(packed))
      throw new VptError('invalid-scene', `${d.owner}.${k}: no finite uniform value (got ${String(v)})`);
    out[p.uniform.name ?? k] = packed;
  }
  return out;
}

/** The controls a user interface offers, in the table's order; placeholders and shown defaults come from the defaults. */
export function rendererControls(d: RendererDescriptor): RendererParamSpec[] {
  const out: RendererParamSpec[] = [];
  for (const [name, p] of Object.entries(d.params)) {
    if (p.kind === 'custom') {
      out.push(...(p.controls ?? []));
      continue;
    }
    if (!p.ui) continue;
    const placeholder = p.defaultText ?? (p.default === undefined ? undefined : String(p.default));
    switch (p.kind) {
      case 'number':
      case 'step': {
        const min = p.ui.min ?? (p.kind === 'number' ? p.min : undefined);
        const max = p.ui.max ?? (p.kind === 'number' ? p.max : undefined);
        out.push({
          name,
          label: p.ui.label,
          ...(min !== undefined ? { min } : {}),
          ...(max !== undefined ? { max } : {}),
          ...(p.ui.step !== undefined ? { step: p.ui.step } : {}),
          ...(placeholder !== undefined ? { placeholder } : {}),
        });
        break;
      }
      case 'enum':
        out.push({ name, label: p.ui.label, kind: 'select', options: p.uiValues ?? p.values, defaultValue: p.default });
        break;
      case 'boolean':
        out.push({ name, label: p.ui.label, kind: 'boolean', defaultValue: p.default });
        break;
    }
  }
  return out;
}
