import { describe, expect, it } from 'vitest';
import { BACKENDS, usePage } from './helpers/session.js';

const page = usePage();

describe.each(BACKENDS)('bad scene input on %s', (backend) => {
  // Dims above the device's 3D limit are downsampled with a warning, not refused (tests/compact-volumes.test.ts).
  it('rejects a NaN camera and a zero-size volume with clear typed errors, and stays usable', async () => {
    const r = await page.run(async ({ core, t }, backend) => {
      const ctx = await t.context({ backend, renderer: 'eam', width: 8, height: 8 });
      const good = t.scene({ volume: core.createProceduralVolume('blob', 8), densityScale: 4 });
      ctx.setScene(good);
      await ctx.renderIterations(2);
      const before: Float32Array = await ctx.readHDR();
      const attempt = (s: unknown) => {
        try {
          ctx.setScene(s);
          return { code: 'none', message: '' };
        } catch (e: any) {
          return { code: e.code, message: e.message, isVpt: e instanceof core.VptError };
        }
      };
      const results = {
        nanCamera: attempt({ ...good, camera: { ...good.camera, target: [0, NaN, 0] } }),
        zeroVolume: attempt({
          ...good,
          volume: { dims: [0, 0, 0], spacing: [1, 1, 1], type: 'uint8', data: new Uint8Array(0) },
        }),
      };
      await ctx.renderIterations(2);
      const after: Float32Array = await ctx.readHDR();
      ctx.dispose();
      return { results, unchanged: t.sameBits(before, after) };
    }, backend);
    expect(r.results.nanCamera).toMatchObject({ code: 'invalid-scene', isVpt: true });
    expect(r.results.nanCamera.message).toMatch(/Camera: target must be three finite numbers/);
    expect(r.results.zeroVolume).toMatchObject({ code: 'invalid-scene', isVpt: true });
    expect(r.results.zeroVolume.message).toMatch(/positive integer/);
    expect(r.unchanged).toBe(0); // the previous scene still renders, identically
  });

  it('rejects a render size above the device limit', async () => {
    const r = await page.run(async ({ t }, backend) => {
      try {
        await t.context({ backend, renderer: 'mip', width: 1e6, height: 4 });
        return 'none';
      } catch (e: any) {
        return e.code;
      }
    }, backend);
    expect(r).toBe('limit-exceeded');
  });
});

describe('backend selection', () => {
  it('WebGL 2 without EXT_color_buffer_float gets a missing-extension error', async () => {
    const r = await page.run(async ({ core }) => {
      const proto = WebGL2RenderingContext.prototype as any;
      const original = proto.getExtension;
      proto.getExtension = function (name: string) {
        return name === 'EXT_color_buffer_float' ? null : original.call(this, name);
      };
      try {
        await core.createBackend({ backend: 'webgl2' });
        return { code: 'none' };
      } catch (e: any) {
        return { code: e.code, message: e.message };
      } finally {
        proto.getExtension = original;
      }
    });
    expect(r.code).toBe('missing-extension');
    expect(r.message).toContain('EXT_color_buffer_float');
  });

  it("a browser with neither API gets a no-backend error from 'auto'", async () => {
    const r = await page.run(async ({ core }) => {
      const gpuDesc = Object.getOwnPropertyDescriptor(Navigator.prototype, 'gpu');
      const getContext = HTMLCanvasElement.prototype.getContext;
      Object.defineProperty(Navigator.prototype, 'gpu', { configurable: true, get: () => undefined });
      (HTMLCanvasElement.prototype as any).getContext = () => null;
      try {
        await core.createBackend({ backend: 'auto' });
        return { code: 'none' };
      } catch (e: any) {
        return { code: e.code, message: e.message };
      } finally {
        if (gpuDesc) Object.defineProperty(Navigator.prototype, 'gpu', gpuDesc);
        HTMLCanvasElement.prototype.getContext = getContext;
      }
    });
    expect(r.code).toBe('no-backend');
  });

  it("'auto' picks WebGPU where the browser offers it", async () => {
    const kind = await page.run(async ({ core }) => {
      const b = await core.createBackend({ backend: 'auto' });
      const k = b.kind;
      b.dispose();
      return k;
    });
    expect(kind).toBe('webgpu');
  });
});
