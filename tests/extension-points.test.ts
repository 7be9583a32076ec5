import { describe, expect, it } from 'vitest';
import { BACKENDS, usePage } from './helpers/session.js';

const page = usePage();

/**
 * A probe renderer defined in the page exercises the Renderer extension points:
 * its frame is aux0.r + ξ with ξ ~ U(0,1) i.i.d. per pixel and iteration, and it keeps
 * the full, even and odd running means (core's HALF_MEANS_INTEGRATE). Its generate kernel
 * (shader source) is below; the class is defined in the page (typed code sent with page.evaluate).
 */
const PROBE_KERNELS = {
  generate: {
    glsl: 'void main() { ivec2 p = vptPixel(); uint s = rngInit(p, u.iteration, u.seed); float v = texelFetch(aux0, ivec2(0, 0), 0).r + rngNext(s); vpt_out0 = vec4(v, v, v, 1.0); }',
    wgsl: '@fragment fn fs_main(@builtin(position) fragCoord: vec4f) -> VptOut { let p = vptPixel(fragCoord); var s = rngInit(p, u.iteration, u.seed); let v = textureLoad(aux0, vec2i(0, 0), 0).r + rngNext(&s); var r: VptOut; r.out0 = vec4f(v, v, v, 1.0); return r; }',
  },
};

describe.each(BACKENDS)('renderer extension points on %s', (backend) => {
  it('binds auxiliary textures, rebuilds them only when their key changes, and estimates the error from half accumulations', async () => {
    const r = await page.run(
      async ({ core, t }, backend, kernels) => {
        class Probe extends core.BaseRenderer {
          auxBuilds = 0;
          constructor() {
            super({});
            Object.assign(this, {
              name: 'probe',
              frameFormats: ['rgba32float'],
              accumulationFormats: ['rgba32float', 'rgba32float', 'rgba32float'],
              halfAccumulations: [1, 2],
              paramFields: [],
              kernels: { ...kernels, integrate: core.HALF_MEANS_INTEGRATE, render: core.COPY_ACCUMULATION_RENDER },
            });
          }
          paramValues() {
            return {};
          }
          auxiliaryTextures(scene: { densityScale: number }) {
            const create = () => {
              this.auxBuilds++;
              return {
                dimension: '2d',
                width: 1,
                height: 1,
                format: 'rgba32float',
                data: new Float32Array([scene.densityScale, 0, 0, 0]),
              };
            };
            return [{ name: 'aux0', dimension: '2d', key: String(scene.densityScale), create }];
          }
        }
        const probe = new Probe();
        const W = 32,
          H = 32;
        const ctx = await core.RenderContext.create({ backend, width: W, height: H, renderer: probe });
        const scene = t.scene({ volume: core.createProceduralVolume('blob', 4), densityScale: 3 });
        ctx.setScene(scene);
        const N = 64;
        await ctx.renderIterations(N);
        const hdr: Float32Array = await ctx.readHDR();
        let mean = 0;
        for (let i = 0; i < hdr.length; i += 4) mean += hdr[i];
        mean /= W * H;
        // True error of each pixel's N-sample mean of U(0,1) noise: sqrt(1/(12 N)).
        const est = await ctx.estimateError();
        const buildsAfterFirst = probe.auxBuilds;
        ctx.updateScene({ camera: { ...scene.camera, position: [0.3, 0.2, 2] } });
        await ctx.renderIterations(2);
        const buildsAfterCamera = probe.auxBuilds;
        ctx.updateScene({ densityScale: 5 });
        await ctx.renderIterations(4);
        const hdr2: Float32Array = await ctx.readHDR();
        let mean2 = 0;
        for (let i = 0; i < hdr2.length; i += 4) mean2 += hdr2[i];
        mean2 /= W * H;
        const buildsAfterDensity = probe.auxBuilds;
        ctx.dispose();
        return { mean, mean2, est, buildsAfterFirst, buildsAfterCamera, buildsAfterDensity, N };
      },
      backend,
      PROBE_KERNELS,
    );
    expect(r.mean).toBeCloseTo(3.5, 2); // aux value 3 + E[ξ] = 0.5, averaged over 1024·64 samples
    expect(r.mean2).toBeGreaterThan(5.2); // the rebuilt texture (5) is bound
    expect(r.mean2).toBeLessThan(5.8);
    expect(r.buildsAfterFirst).toBe(1);
    expect(r.buildsAfterCamera).toBe(1);
    expect(r.buildsAfterDensity).toBe(2);
    const truth = Math.sqrt(1 / (12 * r.N));
    expect(r.est).not.toBeNull();
    expect(r.est!.rmse / truth).toBeGreaterThan(0.9);
    expect(r.est!.rmse / truth).toBeLessThan(1.1);
    expect(r.est!.relativeRmse).toBeCloseTo(r.est!.rmse / 3.5, 3);
  });
});
