import { describe, expect, it } from 'vitest';
import { zSummary } from './helpers/mcrt-stats.js';
import { usePage } from './helpers/session.js';

/**
 * `specialize: false` (one generic kernel for every scene, the baseline of the
 * specialization benchmark) must render the same image as the kernel specialised to the
 * scene. With phase sampling of the environment the two consume the same random numbers
 * (a constant sky looked up in a constant map, lights cut by a runtime count, single
 * scattering as maxDepth = 1), so the images are bit-identical. With MIS the generic kernel
 * importance-samples the constant map where the specialised one samples the sphere
 * uniformly: same expectation, different noise, compared by per-pixel z-scores.
 */
const page = usePage({ mcrt: true });

const W = 16,
  H = 16;

type Run = { mean: number[] | null; se: number[] | null; hdr: number[]; nonFinite: boolean };

async function render(
  backend: string,
  params: Record<string, unknown>,
  lightCount: number,
  seed: number,
  iterations: number,
  frames: boolean,
): Promise<Run> {
  return page.run(
    async ({ core, mt, t }, backend, W, H, params, lightCount, seed, iterations, frames) => {
      const lights = [
        { type: 'directional', direction: [-0.4, 1, 0.3], irradiance: [2, 1.8, 1.5] },
        { type: 'directional', direction: [1, 0.2, -0.5], irradiance: [0.5, 0.7, 1.2] },
      ].slice(0, lightCount);
      const scene = {
        volume: core.createProceduralVolume('blob', 20),
        transferFunction: t.tf1d([0.05, [0.9, 0.9, 0.9], 0], [0.4, [0.95, 0.7, 0.4], 0.7], [1, [0.99, 0.99, 0.99], 1]),
        camera: { position: [0.3, 0.9, 1.8], target: [0, 0, 0], up: [0, 1, 0], fovy: 0.6 },
        lights,
        environment: { type: 'constant', radiance: [0.4, 0.5, 0.7] },
        densityScale: 25,
        seed,
      };
      return mt.run({
        backend,
        width: W,
        height: H,
        iterations,
        frames,
        params: { anisotropy: 0.5, majorantCellSize: 4, ...params },
        scene,
      });
    },
    backend,
    W,
    H,
    params,
    lightCount,
    seed,
    iterations,
    frames,
  );
}

describe('MCRT generic kernel (specialize: false) against the specialised kernels', () => {
  const cases: [string, Record<string, unknown>, number][] = [
    ['single scattering, two lights', { scattering: 'single' }, 2],
    ['multiple scattering, no lights', { scattering: 'multiple' }, 0],
    ['multiple scattering to depth 3, one light', { scattering: 'multiple', maxDepth: 3 }, 1],
  ];
  for (const backend of ['webgl2', 'webgpu']) {
    it(`renders bit-identical images with phase-sampled environment light (${backend})`, async () => {
      for (const [name, params, lights] of cases) {
        if (backend === 'webgpu' && lights !== 2) continue; // one case shows the WGSL variant; parity tests cover the rest
        const p = { ...params, environmentSampling: 'phase' };
        const special = await render(backend, p, lights, 5, 8, false);
        const generic = await render(backend, { ...p, specialize: false }, lights, 5, 8, false);
        expect(special.nonFinite || generic.nonFinite, name).toBe(false);
        expect(Math.max(...special.hdr), name).toBeGreaterThan(0.1);
        let differing = 0;
        for (let i = 0; i < special.hdr.length; i++) if (special.hdr[i] !== generic.hdr[i]) differing++;
        expect(differing, name).toBe(0);
      }
    });
  }

  it('converges to the same image with MIS and without the majorant grid (z-scores, webgl2)', async () => {
    const params = { scattering: 'multiple', majorantGrid: false };
    const special = await render('webgl2', params, 1, 21, 64, true);
    const generic = await render('webgl2', { ...params, specialize: false }, 1, 22, 64, true);
    expect(special.nonFinite || generic.nonFinite).toBe(false);
    const z: number[] = [];
    const a = special.mean!,
      b = generic.mean!,
      sa = special.se!,
      sb = generic.se!;
    for (let i = 0; i < a.length; i += 4) {
      if (sa[i] === 0 && sb[i] === 0 && a[i] === b[i]) continue; // background only: exact in both
      for (let c = 0; c < 3; c++) z.push((a[i + c] - b[i + c]) / Math.hypot(sa[i + c], sb[i + c]));
    }
    const s = zSummary(z, 3);
    expect(z.length).toBeGreaterThan(200);
    expect(Math.abs(s.meanScaled), JSON.stringify(s)).toBeLessThan(4);
    expect(s.maxAbs, JSON.stringify(s)).toBeLessThan(5.5);
  });
});
