import { describe, expect, it } from 'vitest';
import {
  DEFAULT_RENDERER_NAME,
  RENDERER_CATALOG,
  rendererCatalogEntry,
  rendererNames,
  type Renderer,
  type RendererDescriptor,
} from '../src/index.js';

describe('renderer catalog', () => {
  it('names each renderer once, the default among them', () => {
    expect(new Set(rendererNames()).size).toBe(RENDERER_CATALOG.length);
    expect(rendererCatalogEntry('nope')).toBeUndefined();
    expect(rendererCatalogEntry(DEFAULT_RENDERER_NAME)).toBeDefined();
  });

  for (const e of RENDERER_CATALOG) {
    it(`${e.name}: ${e.packageName} exports ${e.exportName} and its descriptor, both of that name`, async () => {
      const m = (await import(/* @vite-ignore */ e.packageName)) as Record<string, unknown>;
      const d = (await import(/* @vite-ignore */ `${e.packageName}/descriptor`)) as { descriptor: RendererDescriptor };
      const Ctor = m[e.exportName] as new (params?: Record<string, unknown>) => Renderer;
      expect(typeof Ctor).toBe('function');
      const r = new Ctor({});
      expect(r.name).toBe(e.name);
      expect(d.descriptor.name).toBe(e.name);
      // The main entry re-exports the descriptor module's object, not a copy.
      expect(m.descriptor).toBe(d.descriptor);
      expect(r.writesGuides ?? false).toBe(d.descriptor.writesGuides);
    });
  }
});
