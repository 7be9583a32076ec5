/**
 * Compiling ahead (GpuBackend.compileAhead, RenderContext.precompile): every pass the first
 * image needs is handed to the backend's parallel compile before the first iteration, the
 * image is bit for bit the one the synchronous path makes, and a broken shader compiled ahead
 * still fails in createPass / finish with its log.
 */
import { describe, expect, it } from 'vitest';
import { rendererNames, type PassDescriptor } from '../packages/core/src/index.js';
import { usePage } from './helpers/session.js';

const page = usePage();
const BACKENDS = ['webgl2', 'webgpu'] as const;

describe('compile ahead', () => {
  it.each(BACKENDS)(
    '%s: every renderer compiles its passes ahead and renders the same bits as compiling at the draw',
    async (backend) => {
      const out = await page.run(
        async ({ core, t }, backend, names) => {
          const volume = core.createProceduralVolume('blob', 16);
          const result: Record<string, { missed: string[]; ahead: number; diff: number; varied: number }> = {};
          for (const renderer of names) {
            const scene = t.scene({
              volume,
              seed: 5,
              densityScale: 10,
              camera: { position: [0.6, 0.3, 1.4], target: [0, 0, 0], up: [0, 1, 0], fovy: 0.8 },
              transferFunction: t.tf1d([0.1, [0.2, 0.4, 1], 0], [0.6, [1, 0.8, 0.3], 0.8], [1, [3, 3, 3], 1]),
              environment: { type: 'constant', radiance: [0.3, 0.2, 0.1] },
            });
            const opts = {
              backend,
              renderer,
              width: 16,
              height: 12,
              post: [{ type: 'tonemap', operator: 'aces' }, { type: 'srgb' }],
            };
            // A: renderIterations, which precompiles. Record what went ahead and what createPass saw
            // (the canvas's present pass, never drawn here, is left out of precompile on purpose).
            const a = await t.context(opts);
            const ahead = new Set<string>();
            const created: string[] = [];
            const be = a.backend;
            const compileAhead = be.compileAhead.bind(be);
            const createPass = be.createPass.bind(be);
            be.compileAhead = (descs: readonly PassDescriptor[]) => {
              for (const d of descs) ahead.add(`${d.label}\n${d.glsl}\n${d.wgsl}\n${d.outputs.join(',')}`);
              return compileAhead(descs);
            };
            be.createPass = (d: PassDescriptor) => {
              if (d.label !== 'present') created.push(`${d.label}\n${d.glsl}\n${d.wgsl}\n${d.outputs.join(',')}`);
              return createPass(d);
            };
            a.setScene(scene);
            await a.renderIterations(3);
            const hdrA = await a.readHDR();
            // B: iterate() and renderImage() compile at the draw, as before.
            const b = await t.context(opts);
            b.setScene(scene);
            b.iterate(3);
            b.renderImage();
            await b.backend.finish();
            const hdrB = await b.readHDR();
            let varied = 0;
            for (let i = 4; i < hdrB.length; i += 4) if (hdrB[i] !== hdrB[0] || hdrB[i + 3] !== hdrB[3]) varied++;
            result[renderer] = {
              missed: created.filter((k) => !ahead.has(k)).map((k) => k.split('\n')[0]),
              ahead: ahead.size,
              diff: t.sameBits(hdrA, hdrB),
              varied,
            };
            a.dispose();
            b.dispose();
          }
          return result;
        },
        backend,
        rendererNames(),
      );
      for (const name of rendererNames()) {
        const r = out[name];
        // Generate, integrate, render and the two post steps at least.
        expect(r.ahead, name).toBeGreaterThanOrEqual(5);
        expect(r.missed, name).toEqual([]);
        expect(r.diff, name).toBe(0);
        expect(r.varied, `${name}: a real image`).toBeGreaterThan(0);
      }
    },
  );

  it.each(BACKENDS)('%s: a broken shader compiled ahead still fails with its log', async (backend) => {
    const out = await page.run(async ({ core }, backend) => {
      const ctx = await core.RenderContext.create({
        backend,
        width: 4,
        height: 4,
        renderer: window.vpt.createRenderer('eam'),
      });
      const be = ctx.backend;
      const gl = be.kind === 'webgl2';
      const desc = {
        label: 'broken ahead',
        uniforms: new core.UniformLayout('NoParams', []),
        textures: [],
        outputs: ['r32float' as const],
        glsl: gl ? 'void main() {\n  vpt_out0 = vec4(notDeclared);\n}\n' : '',
        wgsl: gl
          ? ''
          : '@fragment fn fs_main(@builtin(position) fragCoord: vec4f) -> VptOut {\n  var o: VptOut;\n  o.out0 = vec4f(notDeclared);\n  return o;\n}',
      };
      let resolved = false;
      await be.compileAhead([desc]).then(() => (resolved = true));
      let message = '';
      let code = '';
      try {
        const target = be.createRenderTarget(4, 4, ['r32float'], 'broken target');
        be.draw(be.createPass(desc), { uniforms: new ArrayBuffer(16), textures: {}, target });
        await be.finish();
      } catch (e) {
        message = String((e as Error).message);
        code = String((e as { code?: string }).code);
      }
      ctx.dispose();
      return { resolved, message, code };
    }, backend);
    expect(out.resolved).toBe(true);
    expect(out.code).toBe('shader-compile');
    expect(out.message).toMatch(/broken ahead/);
    expect(out.message).toMatch(/notDeclared/);
  });
});
