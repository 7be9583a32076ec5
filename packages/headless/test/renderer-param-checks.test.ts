import { describe, expect, it } from 'vitest';
import { RENDERER_CATALOG, type Renderer } from '@vpt/core';
import { RENDERER_PARAM_CHECKS } from '../src/validate-description.js';

// Parameter objects good and bad for some renderer: each is refused by the headless check
// exactly when the renderer's own constructor (the reference) refuses it.
const CASES: Record<string, unknown>[] = [
  {},
  { bogus: 1 },
  { stepSize: 0.01 },
  { stepSize: 5e-5 },
  { stepSize: 2 },
  { cutoff: -1 },
  { cutoff: 0.5 },
  { surfaces: [] },
  { surfaces: [{ value: 0.3, color: [1, 0, 0] }] },
  { surfaces: [{ value: 1.5, color: [1, 0, 0] }] },
  { specular: 2 },
  { shininess: 0 },
  { output: 'albedo' },
  { anisotropy: 0.99995 },
  { anisotropy: -0.9 },
  { maxDepth: 0 },
  { maxDepth: 3, scattering: 'single' },
  { lightSamples: 17 },
  { tracking: 'auto', environmentSampling: 'phase' },
  { tracking: 'fast' },
  { emptySpaceSkipping: 'yes' },
];

describe('the headless renderer parameter checks (derived from each descriptor)', () => {
  for (const e of RENDERER_CATALOG) {
    it(`${e.name}: refuses exactly what ${e.exportName} refuses`, async () => {
      const check = RENDERER_PARAM_CHECKS[e.name];
      expect(check, 'a check per catalog renderer').toBeTypeOf('function');
      const Ctor = ((await import(/* @vite-ignore */ e.packageName)) as Record<string, unknown>)[e.exportName] as new (
        p: unknown,
      ) => Renderer;
      const refuses = (f: () => unknown) => {
        try {
          f();
          return false;
        } catch {
          return true;
        }
      };
      let refused = 0;
      for (const params of CASES) {
        const byRenderer = refuses(() => new Ctor(params));
        expect(
          refuses(() => check(params)),
          JSON.stringify(params),
        ).toBe(byRenderer);
        if (byRenderer) refused++;
      }
      // Each renderer refuses some of the cases and accepts some (the comparison is not vacuous).
      expect(refused).toBeGreaterThan(1);
      expect(refused).toBeLessThan(CASES.length);
    });
  }
});
