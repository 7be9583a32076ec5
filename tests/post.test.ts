import { describe, expect, it } from 'vitest';
import { postChainFromJSON, postChainRef } from '../packages/post/src/index.js';
import { BACKENDS, usePage } from './helpers/session.js';

const page = usePage();

// An 8x8 HDR image spanning many orders of magnitude (and exact zeros).
const LEVELS = [0, 1e-4, 0.01, 0.18, 0.5, 1, 4, 1e4];
const W = 8,
  H = 8;
const hdr = new Float32Array(W * H * 4);
for (let i = 0; i < W * H; i++) {
  hdr.set([LEVELS[i % 8], LEVELS[Math.floor(i / 8)], LEVELS[(i * 3) % 8], 0.25 + (i % 4) / 4], 4 * i);
}

const CHAINS = [
  [{ type: 'tonemap', operator: 'reinhard' }],
  [
    { type: 'exposure', exposure: 1.5 },
    { type: 'tonemap', operator: 'aces' },
  ],
  [{ type: 'tonemap', operator: 'pbr-neutral' }],
  [{ type: 'exposure', exposure: -2 }, { type: 'tonemap', operator: 'clamp' }, { type: 'srgb' }],
  [{ type: 'tonemap', operator: 'aces' }, { type: 'srgb' }],
  // Issue 28: chained steps, each within ±64 stops, overflowed f32 (2^192 × 1e4): Reinhard and
  // PBR Neutral gave NaN (black), ACES white. Every operator must now give the reference's white.
  ...['reinhard', 'pbr-neutral', 'aces', 'clamp'].map((operator) => [
    { type: 'exposure', exposure: 64 },
    { type: 'exposure', exposure: 64 },
    { type: 'exposure', exposure: 64 },
    { type: 'tonemap', operator },
  ]),
  // Up and down again: the clamp leaves ordinary values alone.
  [
    { type: 'exposure', exposure: 64 },
    { type: 'exposure', exposure: -64 },
    { type: 'tonemap', operator: 'reinhard' },
  ],
];

/** Run a chain on the GPU: float output after every step but the last, rgba8 after the last. */
async function runChain(backend: string, chain: object[]) {
  return page.run(
    async ({ core, vpt }, backend, chain, hdrIn, W, H) => {
      const { post } = vpt;
      const b = await core.createBackend({ backend });
      const steps = post.postChainFromJSON(chain);
      let input = b.createTexture({
        dimension: '2d',
        width: W,
        height: H,
        format: 'rgba32float',
        data: new Float32Array(hdrIn),
      });
      const floatOut = b.createRenderTarget(W, H, ['rgba32float']);
      const ldrOut = b.createRenderTarget(W, H, ['rgba8unorm']);
      let lastFloat: number[] = [];
      for (let i = 0; i < steps.length; i++) {
        const s = steps[i];
        const passFor = (format: string) =>
          b.createPass({
            label: s.name,
            glsl: s.glsl,
            wgsl: s.wgsl,
            uniforms: s.uniforms,
            textures: [{ name: 'inputImage', dimension: '2d' }],
            outputs: [format],
            defines: s.defines ? s.defines() : {},
          });
        const uniforms = s.uniforms.pack(s.uniformValues());
        b.draw(passFor('rgba32float'), { uniforms, textures: { inputImage: input }, target: floatOut });
        lastFloat = Array.from((await b.readTexture(floatOut.textures[0])) as Float32Array);
        if (i === steps.length - 1)
          b.draw(passFor('rgba8unorm'), { uniforms, textures: { inputImage: input }, target: ldrOut });
        else
          input = b.createTexture({
            dimension: '2d',
            width: W,
            height: H,
            format: 'rgba32float',
            data: new Float32Array(lastFloat),
          });
      }
      const ldr = Array.from((await b.readTexture(ldrOut.textures[0])) as Uint8Array);
      b.dispose();
      return { float: lastFloat, ldr };
    },
    backend,
    chain,
    Array.from(hdr),
    W,
    H,
  );
}

describe.each(BACKENDS)('post chain on %s', (backend) => {
  it.each(CHAINS.map((c) => [JSON.stringify(c), c] as const))('%s equals the CPU reference', async (_name, chain) => {
    const { float, ldr } = await runChain(backend, chain as object[]);
    const steps = postChainFromJSON(chain);
    let maxRel = 0,
      maxCode = 0;
    for (let i = 0; i < W * H; i++) {
      const px = hdr.subarray(4 * i, 4 * i + 3);
      const want = postChainRef(steps, [px[0], px[1], px[2]]);
      for (let c = 0; c < 3; c++) {
        maxRel = Math.max(maxRel, Math.abs(float[4 * i + c] - want[c]) / (Math.abs(want[c]) + 1e-6));
        const code = Math.round(Math.min(1, Math.max(0, want[c])) * 255);
        maxCode = Math.max(maxCode, Math.abs(ldr[4 * i + c] - code));
      }
      expect(float[4 * i + 3]).toBe(hdr[4 * i + 3]); // alpha passes through
      expect(Number.isFinite(float[4 * i])).toBe(true);
    }
    expect(maxRel).toBeLessThan(2e-5);
    expect(maxCode).toBeLessThanOrEqual(1);
  });
});
