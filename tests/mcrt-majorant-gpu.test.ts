import { beforeAll, describe, expect, it } from 'vitest';
import { installMcrtHelpers } from './helpers/mcrt-in-page.js';
import { usePage } from './helpers/session.js';

/**
 * The majorant grid is built on the GPU (per-cell value ranges once per volume, then two
 * passes rerun on every transfer-function or density change). Its cells must equal the CPU
 * build (majorant-grid.ts), whose bounds the unit tests prove true, up to float32 rounding
 * (far below the 1e-5 padding both add): for a 1D TF, then on the same context after a
 * density change, a switch to a 2D TF and a new volume that the cells do not divide
 * (13³ voxels in cells of 4), on both backends.
 */
const page = usePage();
beforeAll(async () => { await installMcrtHelpers(page().page); });

describe('MCRT majorant grid built on the GPU', () => {
  for (const backend of ['webgl2', 'webgpu']) {
    it(`equals the CPU build, and follows TF and density changes (${backend})`, async () => {
      const results = await page().page.evaluate(async (backend) => {
        const { core } = (window as any).vpt;
        const ctx = await (window as any).t.context({ backend, renderer: 'mcrt', width: 8, height: 8, params: { majorantCellSize: 4 } });
        const base = {
          volume: core.createProceduralVolume('blob', 22),
          transferFunction: { dimensions: '1d', points: [{ value: 0.1, color: [1, 1, 1], opacity: 0 }, { value: 0.35, color: [1, 1, 1], opacity: 0.9 }, { value: 0.5, color: [1, 1, 1], opacity: 0.05 }, { value: 1, color: [1, 1, 1], opacity: 0.6 }] },
          camera: { position: [0, 0, 2], target: [0, 0, 0], up: [0, 1, 0], fovy: 0.8 },
          lights: [], environment: { type: 'constant', radiance: [1, 1, 1] }, densityScale: 30, seed: 1,
        };
        const tf2d = { dimensions: '2d', widgets: [{ type: 'box', min: [0.2, 0.1], max: [0.6, 0.7], ramp: [0.05, 0.05], color: [1, 1, 1], opacity: 0.7 }, { type: 'gaussian', center: [0.8, 0.3], width: [0.1, 0.2], color: [1, 1, 1], opacity: 1 }] };
        const odd = core.createProceduralVolume('blob', 13);
        const scenes = [base, { ...base, densityScale: 4000 }, { ...base, transferFunction: tf2d }, { ...base, volume: odd }];
        const out = [];
        for (const scene of scenes) {
          ctx.setScene(scene);
          ctx.iterate(1);
          const gpu = await ctx.readAuxiliaryTexture('majorantGrid');
          const cpu = ctx.renderer.majorantGrid(scene);
          const [gx, gy, gz] = cpu.cells;
          const layout = core.sliceAtlasLayout(cpu.cells);
          let worst = 0, cells = 0, nonZero = 0;
          for (let z = 0; z < gz; z++) for (let y = 0; y < gy; y++) for (let x = 0; x < gx; x++) {
            const c = x + gx * (y + gy * z);
            const t = x + (z % layout.columns) * gx + layout.width * (y + Math.floor(z / layout.columns) * gy);
            for (let ch = 0; ch < 2; ch++) {
              const a = cpu.data[4 * c + ch], b = gpu[4 * t + ch];
              worst = Math.max(worst, Math.abs(a - b) / Math.max(Math.abs(a), 1e-30));
              if (a > 0) nonZero++;
            }
            cells++;
          }
          out.push({ worst, cells, nonZero, max: cpu.globalMajorant });
        }
        ctx.dispose();
        return out;
      }, backend);
      expect(results.map((r) => r.cells)).toEqual([6 * 6 * 6, 6 * 6 * 6, 6 * 6 * 6, 4 * 4 * 4]);
      for (const r of results) {
        expect(r.nonZero).toBeGreaterThan(r.cells / 2); // a grid with content, not zeros compared to zeros
        expect(r.worst, JSON.stringify(r)).toBeLessThan(1e-6);
      }
      // The density change and the 2D TF reached the GPU grid (it is not the first one again).
      expect(results[1].max).toBeCloseTo(results[0].max * 4000 / 30, 2);
      expect(results[2].max).not.toBeCloseTo(results[0].max, 3);
    });
  }
});
