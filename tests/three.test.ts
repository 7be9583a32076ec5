/**
 * @vpt/three (issue 27): a VptVolume drawn by VptCompositor on three.js's own WebGL 2
 * context. Images are checked against core's own renders of the same scene and camera, a
 * CPU expectation on a homogeneous cube, and three.js-only renders.
 */
import { writeFileSync } from 'node:fs';
import { describe, expect, it } from 'vitest';
import { encodePNG } from '../packages/headless/src/index.js';
import { useThreePage } from './helpers/three-page.js';

const N = 32;
const three = useThreePage();

/** Save an HDR image (top row first) as an 8-bit PNG under /tmp, for looking at. */
function savePng(name: string, rgba: number[], w = N, h = N): void {
  const px = new Uint8Array(w * h * 4);
  for (let i = 0; i < w * h; i++) {
    for (let c = 0; c < 3; c++) px[4 * i + c] = Math.round(255 * Math.min(1, Math.max(0, rgba[4 * i + c])));
    px[4 * i + 3] = 255;
  }
  writeFileSync(`/tmp/vpt-three-${name}.png`, encodePNG(px, w, h));
}

function maxRgbDiff(a: number[], b: number[]): number {
  let m = 0;
  for (let i = 0; i < a.length; i++) if (i % 4 !== 3) m = Math.max(m, Math.abs(a[i] - b[i]));
  return m;
}

function meanRgbDiff(a: number[], b: number[]): number {
  let s = 0;
  for (let i = 0; i < a.length; i++) if (i % 4 !== 3) s += Math.abs(a[i] - b[i]);
  return s / ((a.length * 3) / 4);
}

const BG = [0.2, 0.3, 0.4];

describe('@vpt/three: VptVolume in a three.js scene', () => {
  it('without meshes equals core’s own render of the same scene and camera (EAM and MCRT)', async () => {
    const out = await three().run(
      async (h3, n, bg) => {
        const res: Record<string, number[][]> = {};
        for (const r of ['eam', 'mcrt']) {
          const s = h3.setup(n);
          const { eam, mcrt } = (window as any).ref;
          const vscene = {
            ...h3.vptScene('blob', 16, [1, 0.6, 0.3], 1, 12, bg),
            lights: [{ type: 'directional', direction: [0.48, 0.64, 0.6], irradiance: [3, 3, 3] }],
          };
          const vol = new (window as any).ref.vt3.VptVolume({
            renderer: r === 'eam' ? new eam.EamRenderer() : new mcrt.McrtRenderer(),
            scene: vscene,
            iterationsPerFrame: 8,
          });
          s.scene.add(vol);
          s.renderer.setClearColor(h3.linear(bg), 1);
          await s.compositor.prepare(s.scene);
          h3.frames(s, 2);
          const got = Array.from(h3.readTarget(s));
          const camera = { position: [0, 0, 2], target: [0, 0, 0], up: [0, 1, 0], fovy: (40 * Math.PI) / 180 };
          const want = Array.from(await h3.coreRender(r, { ...vscene, camera }, n, 16));
          res[r] = [got, want];
          vol.dispose();
          s.renderer.dispose();
        }
        return res;
      },
      N,
      BG,
    );
    for (const r of ['eam', 'mcrt']) {
      const [got, want] = out[r];
      savePng(`${r}-three`, got);
      savePng(`${r}-core`, want);
      // The volume is there: the centre differs from the background.
      const c = (N / 2) * N * 4 + (N / 2) * 4;
      expect(Math.abs(want[c + 2] - BG[2])).toBeGreaterThan(0.1);
      expect(meanRgbDiff(got, want)).toBeLessThan(r === 'eam' ? 1e-4 : 2e-3);
      if (r === 'eam') expect(maxRgbDiff(got, want)).toBeLessThan(2e-3);
    }
  });
});
