/** Types of renderer-plumbing.mjs, for the unit test that imports it. */
export interface RendererCatalogLine {
  name: string;
  packageName: string;
  exportName: string;
}
export function readCatalog(root: string): Promise<RendererCatalogLine[]>;
export function rendererPlumbing(root: string): Promise<Record<string, string>>;
