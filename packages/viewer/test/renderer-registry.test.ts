import { describe, expect, it } from 'vitest';
import {
  createProceduralVolume,
  defineRenderer,
  RENDERER_CATALOG,
  type Renderer,
  type RendererParamSpec,
} from '@vpt/core';
import { testScene } from '../../../tests/helpers/test-scene.js';
import {
  createRenderer,
  PACKAGE_LOADERS,
  registerRenderer,
  rendererEntries,
  rendererEntry,
} from '../src/renderer-registry.js';

/** A renderer's effective value of one control's parameter, read from the renderer itself (not its descriptor). */
function effectiveValue(r: Renderer, spec: RendererParamSpec, dims: number): unknown {
  const resolved = (r as unknown as { resolvedParams?: Record<string, unknown> }).resolvedParams;
  if (spec.read) return spec.read(resolved ?? {});
  const uniforms = r.paramValues(testScene({ volume: createProceduralVolume('sphere', dims) }));
  // A step is a uniform of the scene; other values as resolved (ISO keeps an unset step as null).
  if (spec.name === 'stepSize') return (uniforms.stepSize as number) * dims;
  return resolved?.[spec.name] ?? uniforms[spec.name];
}

/** The number a placeholder states ("0.1", "half a voxel", "1.5 voxels", "unlimited" = -1 or Infinity). */
function stated(placeholder: string): number[] {
  if (placeholder === 'unlimited') return [-1, Infinity];
  if (placeholder === 'half a voxel') return [0.5];
  const voxels = /^([\d.]+) voxels?$/.exec(placeholder);
  return [Number(voxels ? voxels[1] : placeholder)];
}

describe('renderer registry', () => {
  it('has a literal import() for exactly the packages of the catalog (a bundler sees no others)', () => {
    expect(Object.keys(PACKAGE_LOADERS).sort()).toEqual(
      [...new Set(RENDERER_CATALOG.map((e) => e.packageName))].sort(),
    );
  });

  it('registers every catalog renderer under its name and package, labelled and described by its descriptor', () => {
    const entries = rendererEntries();
    expect(entries.map((e) => [e.name, e.packageName])).toEqual(RENDERER_CATALOG.map((e) => [e.name, e.packageName]));
    for (const e of entries) {
      expect(e.descriptor?.name).toBe(e.name);
      expect(e.label).toBe(e.descriptor?.label);
    }
  });

  it("offers an application renderer's descriptor controls when it registers without params", () => {
    const descriptor = defineRenderer({
      name: 'app-probe',
      label: 'App probe',
      owner: 'APP',
      params: { gain: { kind: 'number', min: 0, max: 2, default: 0.5, ui: { label: 'Gain' } } },
      writesGuides: false,
      needs: { transferFunction: true, lights: false, environment: false },
    });
    registerRenderer({
      name: 'app-probe',
      label: 'App probe',
      packageName: 'app',
      load: async () => null!,
      descriptor,
    });
    expect(rendererEntry('app-probe')?.params).toEqual([
      { name: 'gain', label: 'Gain', min: 0, max: 2, placeholder: '0.5' },
    ]);
  });

  // The quality panel's placeholders and shown defaults against what each renderer does when the parameter is unset.
  for (const entry of rendererEntries()) {
    it(`${entry.name}: every placeholder and shown default is the renderer's own default`, async () => {
      const r = await createRenderer(entry.name, {});
      const dims = 40;
      let checked = 0;
      for (const spec of entry.params ?? []) {
        const actual = effectiveValue(r, spec, dims);
        if (spec.placeholder !== undefined) {
          expect(stated(spec.placeholder), `${spec.name}: "${spec.placeholder}"`).toContain(actual);
          checked++;
        } else if (spec.defaultValue !== undefined && spec.defaultValue !== 'auto') {
          // 'auto' is chosen per scene (MCRT's estimator choice), so there is no one value to compare.
          expect(actual, spec.name).toBe(spec.defaultValue);
          checked++;
        }
      }
      expect(checked).toBeGreaterThan(0);
    });
  }
});
