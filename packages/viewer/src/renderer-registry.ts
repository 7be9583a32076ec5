/**
 * Renderers by name, each loaded on first use with a dynamic import(), so a page pays
 * only for the renderers it shows and a missing package fails that renderer alone,
 * with a message that says what to install. Applications add their own with
 * `registerRenderer()`.
 */
import {
  RENDERER_CATALOG,
  rendererControls,
  VptError,
  type Renderer,
  type RendererDescriptor,
  type RendererParamSpec,
} from '@vpt/core';
import { DESCRIPTOR_MODULES, PACKAGE_LOADERS } from './renderer-packages.generated.js';

/** A renderer class: constructed with its parameter object (unknown keys are the renderer's business). */
export type RendererConstructor = new (params?: Record<string, unknown>) => Renderer;

export type { RendererParamSpec };

export interface RendererEntry {
  name: string;
  label: string;
  /** npm package that provides it, for the error message when it is missing. */
  packageName: string;
  load(): Promise<RendererConstructor>;
  /** The controls the quality panel offers. */
  params?: readonly RendererParamSpec[];
  /** The renderer's descriptor (its look and whether it writes denoiser guides); absent for an application's own renderer without one. */
  descriptor?: RendererDescriptor;
}

const registry = new Map<string, RendererEntry>();
const loaded = new Map<string, Promise<RendererConstructor>>();

/** Add (or replace) a renderer; without `params`, the quality panel offers its descriptor's controls. */
export function registerRenderer(entry: RendererEntry): void {
  const params = entry.params ?? (entry.descriptor ? rendererControls(entry.descriptor) : undefined);
  registry.set(entry.name, params ? { ...entry, params } : entry);
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

// The catalog's renderers, each loaded on first use: the loaders and descriptor modules are
// generated from core's renderer catalog (renderer-packages.generated.ts, `pnpm run
// gen:renderers`), since bundlers include only what an import names literally. A catalog
// entry without a loader there is imported by its bare name (works with an import map).
export { PACKAGE_LOADERS };
for (const e of RENDERER_CATALOG) {
  const descriptor = DESCRIPTOR_MODULES[e.packageName]?.descriptor;
  registerRenderer({
    name: e.name,
    // An absent optional package has no descriptor: listed by name, it fails when chosen.
    label: descriptor?.label ?? e.name,
    packageName: e.packageName,
    ...(descriptor ? { descriptor } : { params: [] }),
    load: () =>
      (PACKAGE_LOADERS[e.packageName] ?? (() => import(/* @vite-ignore */ e.packageName)))().then((m) =>
        exported<RendererConstructor>(m, e.exportName),
      ),
  });
}
