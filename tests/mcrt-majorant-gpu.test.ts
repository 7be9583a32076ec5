import { describe, expect, it } from 'vitest';
import { tf1d } from './helpers/test-scene.js';
import { createVolume, sliceAtlasLayout, reference, type Vec3 } from '../packages/core/src/index.js';
import { gridCells } from '../packages/renderer-mcrt/src/index.js';
import { opacityLookup } from './helpers/mcrt-reference.js';
import { usePage } from './helpers/session.js';

/**
 * The majorant grid is built on the GPU (per-cell value ranges once per volume, then two
 * passes rerun on every transfer-function or density change). Its cells must equal the CPU
 * build (majorant-grid.ts), whose bounds the unit tests prove true, up to float32 rounding
 * (far below the 1e-5 padding both add): for a 1D TF, then on the same context after a
 * density change, a switch to a 2D TF and a new volume that the cells do not divide
 * (13³ voxels in cells of 4), on both backends. And, independently of the CPU build, the
 * GPU grid must itself be a true bound: σ_t sampled at random points of each cell (by the
 * CPU twin of the kernel's trilinear + TF lookup) never exceeds the cell's GPU majorant, on
 * smooth data whose cells have narrow value ranges (so a dropped cell border shows).
 */
const page = usePage({ mcrt: true });

describe('MCRT majorant grid built on the GPU', () => {
  for (const backend of ['webgl2', 'webgpu']) {
    it(`equals the CPU build, and follows TF and density changes (${backend})`, async () => {
      const results = await page.run(async ({ core, t }, backend) => {
        const ctx = await t.context({
          backend,
          renderer: 'mcrt',
          width: 8,
          height: 8,
          params: { majorantCellSize: 4, majorantGrid: true }, // set: 'auto' may take the global bound
        });
        const base = {
          volume: core.createProceduralVolume('blob', 22),
          transferFunction: t.tf1d(
            [0.1, [1, 1, 1], 0],
            [0.35, [1, 1, 1], 0.9],
            [0.5, [1, 1, 1], 0.05],
            [1, [1, 1, 1], 0.6],
          ),
          camera: { position: [0, 0, 2], target: [0, 0, 0], up: [0, 1, 0], fovy: 0.8 },
          lights: [],
          environment: { type: 'constant', radiance: [1, 1, 1] },
          densityScale: 30,
          seed: 1,
        };
        const tf2d = {
          dimensions: '2d',
          widgets: [
            { type: 'box', min: [0.2, 0.1], max: [0.6, 0.7], ramp: [0.05, 0.05], color: [1, 1, 1], opacity: 0.7 },
            { type: 'gaussian', center: [0.8, 0.3], width: [0.1, 0.2], color: [1, 1, 1], opacity: 1 },
          ],
        };
        const odd = core.createProceduralVolume('blob', 13);
        const scenes = [
          base,
          { ...base, densityScale: 4000 },
          { ...base, transferFunction: tf2d },
          { ...base, volume: odd },
        ];
        const out = [];
        for (const scene of scenes) {
          ctx.setScene(scene);
          ctx.iterate(1);
          const gpu = await ctx.readAuxiliaryTexture('majorantGrid');
          const cpu = ctx.renderer.majorantGrid(scene);
          const [gx, gy, gz] = cpu.cells;
          const layout = core.sliceAtlasLayout(cpu.cells);
          let worst = 0,
            cells = 0,
            nonZero = 0;
          for (let z = 0; z < gz; z++)
            for (let y = 0; y < gy; y++)
              for (let x = 0; x < gx; x++) {
                const c = x + gx * (y + gy * z);
                const t = x + (z % layout.columns) * gx + layout.width * (y + Math.floor(z / layout.columns) * gy);
                for (let ch = 0; ch < 2; ch++) {
                  const a = cpu.data[4 * c + ch],
                    b = gpu[4 * t + ch];
                  worst = Math.max(worst, Math.abs(a - b) / Math.max(Math.abs(a), 1e-30));
                  if (a > 0) nonZero++;
                }
                cells++;
              }
          // The GPU grid's own largest majorant (not the CPU build's).
          let gpuMax = 0;
          for (let i = 0; i < gpu.length; i += 4) gpuMax = Math.max(gpuMax, gpu[i]);
          out.push({ worst, cells, nonZero, max: gpuMax });
        }
        ctx.dispose();
        return out;
      }, backend);
      expect(results.map((r) => r.cells)).toEqual([6 * 6 * 6, 6 * 6 * 6, 6 * 6 * 6, 4 * 4 * 4]);
      for (const r of results) {
        expect(r.nonZero).toBeGreaterThan(r.cells / 2); // a grid with content, not zeros compared to zeros
        expect(r.worst, JSON.stringify(r)).toBeLessThan(1e-6);
      }
      // The density change and the 2D TF reached the GPU grid (it is not the first one again): GPU maxima.
      expect(results[1].max).toBeCloseTo((results[0].max * 4000) / 30, 2);
      expect(results[2].max).not.toBeCloseTo(results[0].max, 3);
    });
  }

  // A smooth field, rising along every axis plus a gentle wave: each 2-voxel cell spans a
  // narrow value range, and its points near the upper faces blend in larger values.
  const dims: [number, number, number] = [19, 14, 17];
  const smooth = Array.from({ length: dims[0] * dims[1] * dims[2] }, (_, n) => {
    const x = n % dims[0],
      y = Math.floor(n / dims[0]) % dims[1],
      z = Math.floor(n / (dims[0] * dims[1]));
    return 0.05 + (0.9 * (x / dims[0] + y / dims[1] + z / dims[2])) / 3 + 0.04 * Math.sin(0.7 * x + 0.3 * y);
  });
  const linearTf = tf1d([0, [1, 1, 1], 0], [1, [1, 1, 1], 1]);
  const DENSITY = 20,
    CELL = 2;

  for (const backend of ['webgl2', 'webgpu']) {
    it(`is itself a true upper bound of σ_t at random points of every cell, on smooth data (${backend})`, async () => {
      const gpu = await page.run(
        async ({ core, t }, backend, dims, smooth, tf, density, cell) => {
          const ctx = await t.context({
            backend,
            renderer: 'mcrt',
            width: 4,
            height: 4,
            params: { majorantCellSize: cell, majorantGrid: true },
          });
          const volume = core.createVolume(dims, 'float32', new Float32Array(smooth));
          volume.valueRange = [0, 1];
          ctx.setScene({
            volume,
            transferFunction: tf,
            camera: { position: [0, 0, 2], target: [0, 0, 0], up: [0, 1, 0], fovy: 0.8 },
            lights: [],
            environment: { type: 'constant', radiance: [1, 1, 1] },
            densityScale: density,
            seed: 1,
          });
          ctx.iterate(1);
          const gpu = Array.from((await ctx.readAuxiliaryTexture('majorantGrid')) as Float32Array);
          ctx.dispose();
          return gpu;
        },
        backend,
        dims,
        smooth,
        linearTf,
        DENSITY,
        CELL,
      );
      const volume = createVolume(dims, 'float32', new Float32Array(smooth));
      volume.valueRange = [0, 1];
      const sampler = new reference.CpuVolumeSampler({ volume });
      const opacity = opacityLookup(linearTf);
      const cells = gridCells(dims, CELL);
      const { columns, width } = sliceAtlasLayout(cells); // the grid's slice-atlas texture
      let state = 12345;
      const rand = () => (state = (Math.imul(state, 1664525) + 1013904223) >>> 0) / 4294967296;
      let checked = 0,
        violations = 0,
        tightest = Infinity;
      for (let cz = 0; cz < cells[2]; cz++)
        for (let cy = 0; cy < cells[1]; cy++)
          for (let cx = 0; cx < cells[0]; cx++) {
            const t = cx + (cz % columns) * cells[0] + width * (cy + Math.floor(cz / columns) * cells[1]);
            const majorant = gpu[4 * t];
            for (let k = 0; k < 24; k++) {
              // Uniform points, and every third on the cell's upper face along one axis.
              const f = [rand(), rand(), rand()];
              if (k % 3 === 0) f[k % 9 === 0 ? 0 : k % 9 === 3 ? 1 : 2] = 1;
              const p = [0, 1, 2].map(
                (a) => sampler.box.min[a] + (sampler.box.size[a] * ([cx, cy, cz][a] + f[a])) / cells[a],
              ) as Vec3;
              const sigma = DENSITY * opacity(sampler.sample(p));
              checked++;
              if (sigma > majorant) violations++;
              tightest = Math.min(tightest, majorant - sigma);
            }
          }
      expect(checked).toBe(cells[0] * cells[1] * cells[2] * 24);
      expect(violations, `${violations} of ${checked} points above their cell's GPU majorant`).toBe(0);
      expect(tightest).toBeLessThan(0.5); // a tight bound, not a huge constant
    });
  }
});
