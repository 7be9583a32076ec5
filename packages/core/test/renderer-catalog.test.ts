import { describe, expect, it } from 'vitest';
import { RENDERER_CATALOG, rendererCatalogEntry, rendererNames, type Renderer } from '../src/index.js';

describe('renderer catalog', () => {
  it('names each renderer once', () => {
    expect(new Set(rendererNames()).size).toBe(RENDERER_CATALOG.length);
    expect(rendererCatalogEntry('nope')).toBeUndefined();
  });

  for (const e of RENDERER_CATALOG) {
    it(`${e.name}: ${e.packageName} exports ${e.exportName}, a renderer of that name`, async () => {
      const m = (await import(/* @vite-ignore */ e.packageName)) as Record<string, unknown>;
      const Ctor = m[e.exportName] as new (params?: Record<string, unknown>) => Renderer;
      expect(typeof Ctor).toBe('function');
      expect(new Ctor({}).name).toBe(e.name);
      expect(new Set(e.params.map((p) => p.name)).size).toBe(e.params.length);
    });
  }
});
