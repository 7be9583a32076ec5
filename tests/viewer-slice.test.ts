import { readFileSync } from 'node:fs';
import { describe, expect, it } from 'vitest';
import { HEAD_SIDECAR, ROOT, useViewerPage } from './helpers/viewer-page.js';

/**
 * `<vpt-viewer renderer="slice">`: the one-file bundle loads the slice renderer (a lazy chunk),
 * passes renderer-params to it, and a fitted axial slice of the bundled head at one pixel per
 * voxel is the windowed voxels, computed here from the raw file.
 */
const viewer = useViewerPage();

describe('<vpt-viewer renderer="slice">', () => {
  it('shows the fitted slice of the head: every pixel is its voxel through the window', async () => {
    const params = { axis: 'y', index: 56, fit: true, window: [90, 180] };
    const r = await viewer().run(
      async (vt, src, params) => {
        const el = vt.create(
          {
            src,
            renderer: 'slice',
            'renderer-params': JSON.stringify(params),
            backend: 'webgl2',
            panels: 'none',
            'max-samples': '2',
          },
          'width:128px;height:84px',
        );
        await vt.converged(el);
        const hdr: Float32Array = await el.context.readHDR();
        const ldr: Uint8Array = await el.context.readLDR();
        const out = {
          ldr: Array.from(ldr),
          post: el.context.post.map((s: { name: string }) => s.name),
          size: el.context.size,
          renderer: el.context.renderer.name,
          errors: el.__events.filter((e: { type: string }) => e.type === 'error'),
          hdr: Array.from(hdr),
        };
        el.remove();
        return out;
      },
      HEAD_SIDECAR,
      params,
    );
    expect(r.errors).toEqual([]);
    expect(r.renderer).toBe('slice');
    expect(r.size).toEqual({ width: 128, height: 84 });
    // The head: x fastest, then y, then z; the y slice's columns run along x, its rows along z.
    const voxels = readFileSync(`${ROOT}${HEAD_SIDECAR.replace(/\.json$/, '.raw')}`);
    let worst = 0;
    for (let z = 0; z < 84; z++)
      for (let x = 0; x < 128; x++) {
        const d = voxels[x + 128 * (56 + 128 * z)];
        const w = Math.min(1, Math.max(0, d / 180)); // window [90, 180]: [0, 180] → [0, 1]
        const i = 4 * (x + 128 * z);
        for (let c = 0; c < 3; c++) worst = Math.max(worst, Math.abs(r.hdr[i + c] - w));
        worst = Math.max(worst, Math.abs(r.hdr[i + 3] - 1));
      }
    expect(worst).toBeLessThan(1e-6);
    // Shown as it is: the windowed value to 8 bits, no tone curve, no sRGB encoding, no denoiser.
    expect(r.post).toEqual(['exposure', 'tonemap']);
    let ldrWorst = 0;
    for (let i = 0; i < r.ldr.length; i += 4)
      for (let c = 0; c < 3; c++) ldrWorst = Math.max(ldrWorst, Math.abs(r.ldr[i + c] - 255 * r.hdr[i + c]));
    expect(ldrWorst).toBeLessThanOrEqual(0.5001);
  });
});
