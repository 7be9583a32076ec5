import { describe, expect, it } from 'vitest';
import { usePage } from './helpers/session.js';

const page = usePage();

// docs/design.md: with the same seed both backends produce the same image on SwiftShader, bit for bit.
describe('WebGL 2 / WebGPU parity', () => {
  it.each(['mip', 'eam'])('%s: HDR and LDR images are bit-identical', async (renderer) => {
    const result = await page.run(async ({ core, t }, renderer) => {
      const out: Record<string, { hdr: Float32Array; ldr: Uint8Array }> = {};
      const volume = core.createProceduralVolume('blob', 20);
      for (const backend of ['webgl2', 'webgpu']) {
        const ctx = await t.context({
          backend,
          renderer,
          width: 20,
          height: 16,
          post: [{ type: 'exposure', exposure: 0.5 }, { type: 'tonemap', operator: 'aces' }, { type: 'srgb' }],
        });
        ctx.setScene(
          t.scene({
            volume,
            seed: 11,
            densityScale: 12,
            camera: { position: [0.7, -0.4, 1.5], target: [0, 0.05, 0], up: [0, 1, 0], fovy: 0.8 },
            transferFunction: t.tf1d([0.1, [0.2, 0.4, 1], 0], [0.6, [1, 0.8, 0.3], 0.8], [1, [3, 3, 3], 1]),
            environment: { type: 'constant', radiance: [0.3, 0.2, 0.1] },
          }),
        );
        await ctx.renderIterations(6);
        out[backend] = { hdr: await ctx.readHDR(), ldr: await ctx.readLDR() };
        ctx.dispose();
      }
      const a = out.webgl2,
        b = out.webgpu;
      let ldrDiff = 0;
      for (let i = 0; i < a.ldr.length; i++) if (a.ldr[i] !== b.ldr[i]) ldrDiff++;
      let varied = 0;
      for (let i = 4; i < a.hdr.length; i += 4) if (a.hdr[i] !== a.hdr[0]) varied++;
      return { hdrDiff: t.sameBits(a.hdr, b.hdr), ldrDiff, varied, n: a.hdr.length };
    }, renderer);
    expect(result.varied).toBeGreaterThan(result.n / 4 / 8); // a real image: over 1/8 of the pixels differ from the first
    expect(result.hdrDiff).toBe(0);
    expect(result.ldrDiff).toBe(0);
  });
});
