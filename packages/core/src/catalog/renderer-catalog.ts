/**
 * The renderers of this repository, named once: one line per renderer package. Everything
 * else about a renderer (label, parameters, defaults, look) is its package's descriptor
 * (`@vpt/renderer-<name>/descriptor`, see renderer-descriptor.ts). Core does not depend on
 * the renderer packages: this table is plain data, the import happens in the caller's
 * module graph (an import map, a bundler, Node), and `pnpm run gen:renderers`
 * (scripts/gen-renderers.mjs) writes the plumbing that must name each package literally
 * (import maps, the viewer's loaders, package lists) from it.
 *
 * This file imports nothing: the generator reads it by transpiling it alone.
 */

export interface RendererCatalogEntry {
  /** The name scenes, attributes and configurations use (`renderer: 'mcrt'`); the descriptor's `name`. */
  readonly name: string;
  /** The npm package that provides it (its main entry exports the class, `./descriptor` the descriptor). */
  readonly packageName: string;
  /** The package's export: a class constructed with the parameter object. */
  readonly exportName: string;
}

export const RENDERER_CATALOG: readonly RendererCatalogEntry[] = [
  { name: 'mip', packageName: '@vpt/renderer-mip', exportName: 'MipRenderer' },
  { name: 'iso', packageName: '@vpt/renderer-iso', exportName: 'IsoRenderer' },
  { name: 'eam', packageName: '@vpt/renderer-eam', exportName: 'EamRenderer' },
  { name: 'mcrt', packageName: '@vpt/renderer-mcrt', exportName: 'McrtRenderer' },
  { name: 'slice', packageName: '@vpt/renderer-slice', exportName: 'SliceRenderer' },
];

/** The renderer a scene, the viewer and the CLI use when none is named. */
export const DEFAULT_RENDERER_NAME = 'eam';

/** The catalog entry of a renderer name, or undefined. */
export function rendererCatalogEntry(name: string): RendererCatalogEntry | undefined {
  return RENDERER_CATALOG.find((e) => e.name === name);
}

/** The renderer names of the catalog, for error messages ("eam, mip, …"). */
export function rendererNames(): string[] {
  return RENDERER_CATALOG.map((e) => e.name);
}
