import { describe, expect, it } from 'vitest';
import {
  createProceduralVolume,
  createVolume,
  gradientMagnitudes,
  maxGradientMagnitude,
  volumeBox,
  type Volume,
} from '../packages/core/src/index.js';
import { BACKENDS, usePage } from './helpers/session.js';
import { testVolumes, type FieldSpec } from './helpers/test-volumes.js';

/**
 * The gradient-magnitude volume computed on the GPU (RenderContext.readGradientVolume) against
 * analytic answers and the CPU reference, and the shader-side lookup (the chunk behind the 2D
 * transfer function, reached here through a renderer with `needsGradient`) against a CPU
 * trilinear interpolation of the CPU gradients.
 */
type Field = FieldSpec;

/** The field's volume in Node (the page builds the same one with window.tv.field). */
function build(field: Field): Volume {
  return testVolumes({ createVolume, createProceduralVolume }).field(field);
}

const RAMP: Field = { dims: [9, 7, 5], spacing: [1, 2, 0.5], range: [-10, 10], kind: 'ramp' };
const SPHERE: Field = { dims: [33, 33, 33], spacing: [1, 1, 1], range: [0, 30], kind: 'sphere16' };
// Over 64³ (the size above which gradients must not be computed on the main thread) and not cubic.
const LARGE: Field = { dims: [70, 66, 65], spacing: [1, 1, 1.5], range: [-2, 2], kind: 'waves' };

const page = usePage();

// CPU comparisons read the exact path's r32float gradient; the fast path's r16float is tested against its stated bound.
async function gpuGradient(
  backend: string,
  field: Field,
  sampling: 'fast' | 'exact' = 'exact',
): Promise<{ magnitudes: number[]; max: number }> {
  return page.run(
    async ({ t }, backend, field, sampling) => {
      const volume = window.tv.field(field);
      const ctx = await t.context({ backend, renderer: 'eam', width: 4, height: 4, sampling });
      ctx.setScene(
        t.scene({
          volume,
          transferFunction: {
            dimensions: '2d',
            widgets: [{ type: 'box', min: [0, 0.5], max: [1, 1], color: [1, 1, 1], opacity: 1 }],
          },
        }),
      );
      const g = await ctx.readGradientVolume();
      ctx.dispose();
      return { magnitudes: Array.from(g.magnitudes as Float32Array), max: g.max };
    },
    backend,
    field,
    sampling,
  );
}

describe.each(BACKENDS)('gradient magnitude on the GPU (%s)', (backend) => {
  it('equals the slope of a linear ramp (anisotropic spacing), borders included', async () => {
    const g = await gpuGradient(backend, RAMP);
    const slope = Math.sqrt(0.3 ** 2 + 0.2 ** 2 + 0.5 ** 2);
    expect(g.magnitudes.length).toBe(9 * 7 * 5);
    for (const m of g.magnitudes) expect(Math.abs(m - slope)).toBeLessThan(1e-4 * slope);
    expect(Math.abs(g.max - slope)).toBeLessThan(1e-4);
  });

  it('is 1 for a sphere distance field away from the centre, and matches the CPU reference', async () => {
    const g = await gpuGradient(backend, SPHERE);
    const cpu = gradientMagnitudes(build(SPHERE));
    let checked = 0;
    for (let z = 1; z < 32; z++)
      for (let y = 1; y < 32; y++)
        for (let x = 1; x < 32; x++) {
          const i = x + 33 * (y + 33 * z);
          expect(Math.abs(g.magnitudes[i] - cpu[i])).toBeLessThan(1e-5);
          if (Math.hypot(x - 16, y - 16, z - 16) >= 4) {
            expect(Math.abs(g.magnitudes[i] - 1)).toBeLessThan(0.02);
            checked++;
          }
        }
    expect(checked).toBeGreaterThan(20000);
    expect(Math.abs(g.max - maxGradientMagnitude(cpu))).toBeLessThan(1e-5);
  });

  it('handles volumes over 64³ on the GPU (slice atlas and max reduction), matching the CPU reference', async () => {
    const g = await gpuGradient(backend, LARGE);
    const cpu = gradientMagnitudes(build(LARGE));
    let maxErr = 0;
    for (let i = 0; i < cpu.length; i++) maxErr = Math.max(maxErr, Math.abs(g.magnitudes[i] - cpu[i]));
    expect(maxErr).toBeLessThan(1e-5);
    expect(Math.abs(g.max - maxGradientMagnitude(cpu))).toBeLessThan(1e-5);
  });

  it("keeps the fast path's 16-bit gradient within half precision of the CPU reference (relative 2^-11)", async () => {
    const g = await gpuGradient(backend, LARGE, 'fast');
    const cpu = gradientMagnitudes(build(LARGE));
    let worst = 0;
    for (let i = 0; i < cpu.length; i++)
      worst = Math.max(worst, Math.abs(g.magnitudes[i] - cpu[i]) - 2 ** -11 * cpu[i]);
    expect(worst).toBeLessThan(1e-6); // |fast − cpu| ≤ 2^-11·cpu + float32 noise, at every voxel
    expect(Math.abs(g.max - maxGradientMagnitude(cpu))).toBeLessThanOrEqual(2 ** -11 * g.max + 1e-6);
  });

  it('is sampled trilinearly and normalized by the kernels of a renderer that sets needsGradient', async () => {
    // A probe renderer writes sampleGradientMagnitude(p) and normalizedGradientAt(p) at points
    // p spread over the box (through several atlas tiles of a non-cubic volume).
    const field: Field = { dims: [20, 12, 9], spacing: [1, 1, 2], range: [-3, 3], kind: 'probe' };
    const W = 16,
      H = 12,
      Z = 0.37;
    const out: number[] = await page.run(
      async ({ core, t }, backend, field, W, H, Z) => {
        const volume = window.tv.field(field);
        const body = (g: boolean) =>
          g
            ? 'void main() { ivec2 q = vptPixel(); vec3 f = vec3((float(q.x) + 0.5) / ' +
              W +
              '.0, (float(q.y) + 0.5) / ' +
              H +
              '.0, ' +
              Z +
              '); vec3 p = u.boxMin + (u.boxMax - u.boxMin) * f; vpt_out0 = vec4(sampleGradientMagnitude(p), normalizedGradientAt(p), VPT_GRADIENT, VPT_TF_2D); }'
            : '@fragment fn fs_main(@builtin(position) fragCoord: vec4f) -> VptOut { let q = vptPixel(fragCoord); let f = vec3f((f32(q.x) + 0.5) / ' +
              W +
              '.0, (f32(q.y) + 0.5) / ' +
              H +
              '.0, ' +
              Z +
              '); let p = u.boxMin + (u.boxMax - u.boxMin) * f; var r: VptOut; r.out0 = vec4f(sampleGradientMagnitude(p), normalizedGradientAt(p), select(0.0, 1.0, VPT_GRADIENT), select(0.0, 1.0, VPT_TF_2D)); return r; }';
        class Probe extends core.BaseRenderer {
          constructor() {
            super({});
            Object.assign(this, {
              name: 'gradient-probe',
              needsGradient: true,
              frameFormats: ['rgba32float'],
              accumulationFormats: ['rgba32float'],
              paramFields: [],
              kernels: {
                generate: { glsl: body(true), wgsl: body(false) },
                integrate: core.RUNNING_MEAN_INTEGRATE,
                render: core.COPY_ACCUMULATION_RENDER,
              },
            });
          }
          paramValues() {
            return {};
          }
        }
        const ctx = await core.RenderContext.create({
          backend,
          width: W,
          height: H,
          renderer: new Probe(),
          sampling: 'exact',
        });
        ctx.setScene(t.scene({ volume })); // a 1D transfer function: the gradient is there for the renderer alone
        await ctx.renderIterations(1);
        const hdr = Array.from((await ctx.readHDR()) as Float32Array);
        // A 2D transfer function with a fixed gradientMax: the axis is |grad f| / 0.05 (clamped to 1).
        ctx.updateScene({
          transferFunction: {
            dimensions: '2d',
            gradientMax: 0.05,
            widgets: [{ type: 'box', min: [0, 0], max: [1, 1], color: [1, 1, 1], opacity: 1 }],
          },
        });
        await ctx.renderIterations(1);
        const fixed = Array.from((await ctx.readHDR()) as Float32Array);
        ctx.dispose();
        return [...hdr, ...fixed];
      },
      backend,
      field,
      W,
      H,
      Z,
    );
    const vol = build(field);
    const g = gradientMagnitudes(vol);
    const gmax = maxGradientMagnitude(g);
    const box = volumeBox(vol);
    const [nx, ny, nz] = field.dims;
    const trilinear = (p: number[]) => {
      const c = p.map((x, a) => ((x - box.min[a]) / box.size[a]) * field.dims[a] - 0.5);
      const i0 = c.map(Math.floor),
        fr = c.map((x, a) => x - i0[a]);
      const cl = (i: number, n: number) => Math.min(n - 1, Math.max(0, i));
      let s = 0;
      for (const dz of [0, 1])
        for (const dy of [0, 1])
          for (const dx of [0, 1]) {
            const w = (dx ? fr[0] : 1 - fr[0]) * (dy ? fr[1] : 1 - fr[1]) * (dz ? fr[2] : 1 - fr[2]);
            s += w * g[cl(i0[0] + dx, nx) + nx * (cl(i0[1] + dy, ny) + ny * cl(i0[2] + dz, nz))];
          }
      return s;
    };
    for (let j = 0; j < H; j++)
      for (let i = 0; i < W; i++) {
        const f = [(i + 0.5) / W, (j + 0.5) / H, Z];
        const p = f.map((x, a) => box.min[a] + box.size[a] * x);
        const want = trilinear(p);
        const k = 4 * (i + W * j);
        expect(Math.abs(out[k] - want)).toBeLessThan(1e-4 * gmax);
        expect(Math.abs(out[k + 1] - want / gmax)).toBeLessThan(1e-4);
        expect([out[k + 2], out[k + 3]]).toEqual([1, 0]); // VPT_GRADIENT on, VPT_TF_2D off
        const k2 = k + 4 * W * H;
        expect(out[k2]).toBe(out[k]);
        expect(Math.abs(out[k2 + 1] - Math.min(1, want / 0.05))).toBeLessThan(2e-3);
        expect([out[k2 + 2], out[k2 + 3]]).toEqual([1, 1]);
      }
  });
});

describe('gradient magnitude: WebGL 2 / WebGPU parity', () => {
  it('computes bit-identical gradient volumes', async () => {
    const a = await gpuGradient('webgl2', LARGE);
    const b = await gpuGradient('webgpu', LARGE);
    let diff = 0;
    for (let i = 0; i < a.magnitudes.length; i++) if (!Object.is(a.magnitudes[i], b.magnitudes[i])) diff++;
    expect(diff).toBe(0);
    expect(a.max).toBe(b.max);
  });
});
