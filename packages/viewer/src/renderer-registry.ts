/**
 * Renderers by name, each loaded on first use with a dynamic import(), so a page pays
 * only for the renderers it shows and a missing package fails that renderer alone,
 * with a message that says what to install. Applications add their own with
 * `registerRenderer()`.
 */
import { RENDERER_CATALOG, VptError, type Renderer, type RendererParamSpec } from '@vpt/core';

/** A renderer class: constructed with its parameter object (unknown keys are the renderer's business). */
export type RendererConstructor = new (params?: Record<string, unknown>) => Renderer;

export type { RendererParamSpec };

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
    throw new VptError(
      'invalid-scene',
      `<vpt-viewer> renderer: unknown renderer "${name}" (available: ${[...registry.keys()].join(', ')})`,
    );
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
    throw new VptError(
      'load-failed',
      `The "${name}" renderer is not available: ${entry.packageName} could not be loaded (${(e as Error).message}). Install and build it, or pick another renderer.`,
      { cause: e },
    );
  }
  return new Ctor(params);
}

// Bundlers include only what a literal import() names, so the viewer keeps one loader per
// package of the catalog (the viewer's build replaces an uninstalled optional one with a
// stub that says so: see rollup.config.mjs). A catalog entry without a loader here is
// imported by its bare name, which works in a page with an import map.
export const PACKAGE_LOADERS: Readonly<Record<string, () => Promise<Record<string, unknown>>>> = {
  '@vpt/renderer-mip': () => import('@vpt/renderer-mip'),
  // @ts-ignore -- optional package, may be absent when this is type-checked
  '@vpt/renderer-iso': () => import('@vpt/renderer-iso'),
  '@vpt/renderer-eam': () => import('@vpt/renderer-eam'),
  // @ts-ignore -- optional package, may be absent when this is type-checked
  '@vpt/renderer-mcrt': () => import('@vpt/renderer-mcrt'),
  // @ts-ignore -- optional package, may be absent when this is type-checked
  '@vpt/renderer-slice': () => import('@vpt/renderer-slice'),
};

// The renderers of the catalog (core's renderer-catalog.ts), each loaded on first use.
for (const e of RENDERER_CATALOG) {
  registerRenderer({
    name: e.name,
    label: e.label,
    packageName: e.packageName,
    params: e.params,
    load: () =>
      (PACKAGE_LOADERS[e.packageName] ?? (() => import(/* @vite-ignore */ e.packageName)))().then((m) =>
        exported<RendererConstructor>(m, e.exportName),
      ),
  });
}
