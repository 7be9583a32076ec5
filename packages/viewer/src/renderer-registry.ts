/**
 * Renderers by name, each loaded on first use with a dynamic import(), so a page pays
 * only for the renderers it shows and a missing package fails that renderer alone,
 * with a message that says what to install. Applications add their own with
 * `registerRenderer()`.
 */
import { VptError, type Renderer } from '@vpt/core';

/** A renderer class: constructed with its parameter object (unknown keys are the renderer's business). */
export type RendererConstructor = new (params?: Record<string, unknown>) => Renderer;

/**
 * A renderer parameter the quality panel offers. `undefined` in the parameter object
 * means the renderer's own default. `read`/`write` reach into nested parameters (the
 * first isosurface's value, say); without them the parameter is `params[name]`.
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

export interface RendererEntry {
  name: string;
  label: string;
  /** npm package that provides it, for the error message when it is missing. */
  packageName: string;
  load(): Promise<RendererConstructor>;
  params?: readonly RendererParamSpec[];
}

const registry = new Map<string, RendererEntry>();
const loaded = new Map<string, Promise<RendererConstructor>>();

export function registerRenderer(entry: RendererEntry): void {
  registry.set(entry.name, entry);
  loaded.delete(entry.name);
}

export function rendererEntries(): RendererEntry[] {
  return [...registry.values()];
}

export function rendererEntry(name: string): RendererEntry | undefined {
  return registry.get(name);
}

/** The named export of a dynamically imported module; the build's stub for an absent package says so. */
export function exported<T>(m: Record<string, unknown>, name: string): T {
  if (typeof m.__vptMissing === 'string') throw new Error(m.__vptMissing);
  return m[name] as T;
}

/** Load (once) and construct the named renderer; a VptError names the package when it cannot be loaded. */
export async function createRenderer(name: string, params: Record<string, unknown> = {}): Promise<Renderer> {
  const entry = registry.get(name);
  if (!entry) {
    throw new VptError('invalid-scene', `<vpt-viewer> renderer: unknown renderer "${name}" (available: ${[...registry.keys()].join(', ')})`);
  }
  let ctor = loaded.get(name);
  if (!ctor) {
    ctor = entry.load().then((c) => {
      if (typeof c !== 'function') throw new Error(`${entry.packageName} does not export the expected renderer class`);
      return c;
    });
    ctor.catch(() => {}); // reported by the awaiting caller below
    loaded.set(name, ctor);
  }
  let Ctor: RendererConstructor;
  try {
    Ctor = await ctor;
  } catch (e) {
    loaded.delete(name); // a later attempt (after installing or building the package) may succeed
    throw new VptError('load-failed', `The "${name}" renderer is not available: ${entry.packageName} could not be loaded (${(e as Error).message}). Install and build it, or pick another renderer.`, { cause: e });
  }
  return new Ctor(params);
}

const step = (placeholder: string): RendererParamSpec => ({ name: 'stepSize', label: 'Step size', min: 0.0005, max: 0.05, step: 0.0005, placeholder });

/** The first isosurface's fields, edited in place (the iso renderer takes a list of surfaces). */
type Surface = { value: number; color: [number, number, number]; opacity?: number };
const DEFAULT_SURFACE: Surface = { value: 0.5, color: [1, 1, 1], opacity: 1 };
const firstSurface = (p: Record<string, unknown>): Surface => ((p.surfaces as Surface[] | undefined)?.[0] ?? DEFAULT_SURFACE);
const withFirstSurface = (p: Record<string, unknown>, patch: Partial<Surface>) => {
  const surfaces = [...((p.surfaces as Surface[] | undefined) ?? [DEFAULT_SURFACE])];
  surfaces[0] = { ...surfaces[0], ...patch };
  return { ...p, surfaces };
};

// The renderers of this repository. The optional packages are imported by their literal
// names so bundlers include them when installed; the viewer's build replaces an
// uninstalled one with a stub that says so (see rollup.config.mjs).
registerRenderer({
  name: 'mip', label: 'Maximum intensity', packageName: '@vpt/renderer-mip',
  load: () => import('@vpt/renderer-mip').then((m) => m.MipRenderer as unknown as RendererConstructor),
  params: [step('half a voxel')],
});
registerRenderer({
  name: 'iso', label: 'Isosurface', packageName: '@vpt/renderer-iso',
  // @ts-ignore -- optional package, may be absent when this is type-checked
  load: () => import('@vpt/renderer-iso').then((m: Record<string, unknown>) => exported<RendererConstructor>(m, 'IsoRenderer')),
  params: [
    { name: 'isoValue', label: 'Iso value', min: 0, max: 1, step: 0.01, placeholder: '0.5', read: (p) => firstSurface(p).value, write: (p, v) => withFirstSurface(p, { value: v as number }) },
    { name: 'isoColor', label: 'Surface colour', kind: 'color', read: (p) => firstSurface(p).color, write: (p, v) => withFirstSurface(p, { color: v as Surface['color'] }) },
    step('half a voxel'),
    { name: 'specular', label: 'Specular', min: 0, max: 1, step: 0.05, placeholder: '0.1' },
    { name: 'shininess', label: 'Shininess', min: 1, max: 1000, step: 1, placeholder: '40' },
    { name: 'shadows', label: 'Shadows', kind: 'boolean', defaultValue: true },
    { name: 'ambientOcclusion', label: 'Ambient occlusion', kind: 'boolean', defaultValue: true },
  ],
});
registerRenderer({
  name: 'eam', label: 'Emission–absorption', packageName: '@vpt/renderer-eam',
  load: () => import('@vpt/renderer-eam').then((m) => m.EamRenderer as unknown as RendererConstructor),
  params: [step('half a voxel'), { name: 'cutoff', label: 'Early-exit transmittance', min: 0, max: 0.1, step: 0.0001, placeholder: '1e-6' }],
});
registerRenderer({
  name: 'mcrt', label: 'Path tracing (MCRT)', packageName: '@vpt/renderer-mcrt',
  // @ts-ignore -- optional package, may be absent when this is type-checked
  load: () => import('@vpt/renderer-mcrt').then((m: Record<string, unknown>) => exported<RendererConstructor>(m, 'McrtRenderer')),
  params: [
    { name: 'scattering', label: 'Scattering', kind: 'select', options: ['multiple', 'single'], defaultValue: 'multiple' },
    { name: 'anisotropy', label: 'Anisotropy g', min: -0.99, max: 0.99, step: 0.05, placeholder: '0' },
    { name: 'maxDepth', label: 'Max bounces', min: -1, max: 256, step: 1, placeholder: 'unlimited' },
    { name: 'tracking', label: 'Shadow tracking', kind: 'select', options: ['residual', 'ratio', 'delta'], defaultValue: 'residual' },
    { name: 'environmentSampling', label: 'Environment sampling', kind: 'select', options: ['mis', 'light', 'phase'], defaultValue: 'mis' },
    { name: 'majorantGrid', label: 'Majorant grid', kind: 'boolean', defaultValue: true },
  ],
});
