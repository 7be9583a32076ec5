import { describe, expect, it } from 'vitest';
import { BACKENDS, usePage } from './helpers/session.js';

const page = usePage();

/**
 * A probe renderer defined in the page exercises the Renderer extension points:
 * its frame is aux0.r + ξ with ξ ~ U(0,1) i.i.d. per pixel and iteration, and it keeps
 * the full, even and odd running means. Its kernels (shader sources) are below; the class
 * is defined in the page (typed code sent with page.evaluate).
 */
const PROBE_KERNELS = {
  generate: {
    glsl: 'void main() { ivec2 p = vptPixel(); uint s = rngInit(p, u.iteration, u.seed); float v = texelFetch(aux0, ivec2(0, 0), 0).r + rngNext(s); vpt_out0 = vec4(v, v, v, 1.0); }',
    wgsl: '@fragment fn fs_main(@builtin(position) fragCoord: vec4f) -> VptOut { let p = vptPixel(fragCoord); var s = rngInit(p, u.iteration, u.seed); let v = textureLoad(aux0, vec2i(0, 0), 0).r + rngNext(&s); var r: VptOut; r.out0 = vec4f(v, v, v, 1.0); return r; }',
  },
  integrate: {
    glsl: `
void main() {
  ivec2 p = vptPixel();
  vec4 f = texelFetch(frame0, p, 0);
  uint n = u.iteration;
  if (n == 0u) { vpt_out0 = f; vpt_out1 = f; vpt_out2 = vec4(0.0); return; }
  vec4 a = texelFetch(accum0, p, 0);
  vec4 e = texelFetch(accum1, p, 0);
  vec4 o = texelFetch(accum2, p, 0);
  vpt_out0 = a + (f - a) * (1.0 / float(n + 1u));
  uint k = n / 2u;
  if (n % 2u == 0u) { vpt_out1 = e + (f - e) * (1.0 / float(k + 1u)); vpt_out2 = o; }
  else { vpt_out1 = e; vpt_out2 = o + (f - o) * (1.0 / float(k + 1u)); }
}`,
    wgsl: `
@fragment fn fs_main(@builtin(position) fragCoord: vec4f) -> VptOut {
  let p = vptPixel(fragCoord);
  let f = textureLoad(frame0, p, 0);
  let n = u.iteration;
  var r: VptOut;
  if (n == 0u) { r.out0 = f; r.out1 = f; r.out2 = vec4f(0.0); return r; }
  let a = textureLoad(accum0, p, 0);
  let e = textureLoad(accum1, p, 0);
  let o = textureLoad(accum2, p, 0);
  r.out0 = a + (f - a) * (1.0 / f32(n + 1u));
  let k = n / 2u;
  if (n % 2u == 0u) { r.out1 = e + (f - e) * (1.0 / f32(k + 1u)); r.out2 = o; }
  else { r.out1 = e; r.out2 = o + (f - o) * (1.0 / f32(k + 1u)); }
  return r;
}`,
  },
};

describe.each(BACKENDS)('renderer extension points on %s', (backend) => {
  it('binds auxiliary textures, rebuilds them only when their key changes, and estimates the error from half accumulations', async () => {
    const r = await page().page.evaluate(async (backend, kernels) => {
      const { core } = (window as any).vpt;
      const t = (window as any).t;
      class Probe extends core.BaseRenderer {
        auxBuilds = 0;
        constructor() {
          super({});
          Object.assign(this, {
            name: 'probe', frameFormats: ['rgba32float'], accumulationFormats: ['rgba32float', 'rgba32float', 'rgba32float'],
            halfAccumulations: [1, 2], paramFields: [],
            kernels: { ...kernels, render: core.COPY_ACCUMULATION_RENDER },
          });
        }
        paramValues() { return {}; }
        auxiliaryTextures(scene: { densityScale: number }) {
          const create = () => {
            this.auxBuilds++;
            return { dimension: '2d', width: 1, height: 1, format: 'rgba32float', data: new Float32Array([scene.densityScale, 0, 0, 0]) };
          };
          return [{ name: 'aux0', dimension: '2d', key: String(scene.densityScale), create }];
        }
      }
      const probe = new Probe();
      const W = 32, H = 32;
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
    }, backend, PROBE_KERNELS);
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
