import { describe, expect, it } from 'vitest';
import { RENDERER_CATALOG } from '@vpt/core';
import { PACKAGE_LOADERS, rendererEntries } from '../src/renderer-registry.js';

describe('renderer registry', () => {
  it('has a literal import() for exactly the packages of the catalog (a bundler sees no others)', () => {
    expect(Object.keys(PACKAGE_LOADERS).sort()).toEqual(
      [...new Set(RENDERER_CATALOG.map((e) => e.packageName))].sort(),
    );
  });
  it('registers every catalog renderer under its name, label and package', () => {
    expect(rendererEntries().map((e) => [e.name, e.label, e.packageName])).toEqual(
      RENDERER_CATALOG.map((e) => [e.name, e.label, e.packageName]),
    );
  });
});
