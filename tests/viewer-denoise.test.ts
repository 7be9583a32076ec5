import { describe, expect, it } from 'vitest';
import { useViewerPage } from './helpers/viewer-page.js';

/**
 * The viewer's `denoise` attribute (docs/architecture.md, "Denoising"): 'auto' filters while
 * refining and shows the plain estimate once converged, 'on' keeps filtering, 'off' has no
 * denoise step; the HDR export says whether it was denoised; a bad value is a typed error.
 */
const viewer = useViewerPage();

describe('<vpt-viewer denoise>', () => {
  it('auto denoises while refining and not once converged; on keeps it; off removes it; bad values are refused', async () => {
    const r = await viewer().page.evaluate(async () => {
      const vt = window.vt;
      const el = vt.blob('mcrt', 100000);
      await el.whenSettled();
      await vt.next(el, 'progress');
      await vt.frames(2);
      const refining = { denoised: el.denoised, first: el.context.post[0].name, steps: el.context.post.length };

      // A few samples past where refinement is now (a fast machine may already be past a fixed count).
      const maxSamples = Math.max(6, el.samples + 3);
      el.setAttribute('max-samples', String(maxSamples));
      await vt.converged(el);
      await vt.frames(2);
      const plain: Float32Array = await el.context.readHDR();
      const converged = {
        denoised: el.denoised,
        exportIsPlain: sameBytes(await el.exportHDR('pfm'), encodeLikeExport(el, plain)),
      };

      el.setAttribute('denoise', 'on');
      await vt.frames(3);
      const after: Float32Array = await el.context.readHDR({ afterPost: true });
      let changed = 0;
      for (let i = 0; i < after.length; i++) if (after[i] !== plain[i]) changed++;
      const on = {
        denoised: el.denoised,
        samples: el.samples,
        changed,
        exportIsDenoised: sameBytes(await el.exportHDR('pfm'), encodeLikeExport(el, after)),
      };

      el.setAttribute('denoise', 'sometimes');
      await vt.frames(2);
      const bad = el.__events.filter((e: { type: string }) => e.type === 'error').pop();
      const kept = el.denoise;

      el.setAttribute('denoise', 'off');
      await vt.frames(2);
      const off = { denoised: el.denoised, names: el.context.post.map((s: { name: string }) => s.name) };
      el.remove();
      return { refining, converged, on, bad, kept, off, maxSamples };

      // The PFM export of an HDR image, built the way the element's export is (header + bottom-up rows of RGB).
      function encodeLikeExport(el: { context: { size: { width: number; height: number } } }, hdr: Float32Array) {
        const { width, height } = el.context.size;
        const header = new TextEncoder().encode(`PF\n${width} ${height}\n-1.0\n`);
        const body = new Float32Array(width * height * 3);
        for (let y = 0; y < height; y++)
          for (let x = 0; x < width; x++)
            for (let c = 0; c < 3; c++) body[3 * ((height - 1 - y) * width + x) + c] = hdr[4 * (y * width + x) + c];
        const out = new Uint8Array(header.length + body.byteLength);
        out.set(header);
        out.set(new Uint8Array(body.buffer), header.length);
        return out;
      }
      function sameBytes(a: Uint8Array, b: Uint8Array) {
        return a.length === b.length && a.every((v, i) => v === b[i]);
      }
    });
    expect(r.refining).toEqual({ denoised: true, first: 'denoise', steps: 4 });
    expect(r.converged).toEqual({ denoised: false, exportIsPlain: true });
    // Turning it on after convergence keeps the samples (the guides were accumulated all along).
    expect(r.on.samples).toBe(r.maxSamples);
    expect(r.on.denoised).toBe(true);
    expect(r.on.changed).toBeGreaterThan(0);
    expect(r.on.exportIsDenoised).toBe(true);
    expect(r.bad).toMatchObject({ code: 'invalid-scene', source: 'attribute' });
    expect(r.bad.message).toMatch(/denoise: must be one of auto, on, off/);
    expect(r.kept).toBe('on');
    expect(r.off).toEqual({ denoised: false, names: ['exposure', 'tonemap', 'srgb'] });
  });
});
