import type { GpuBackend, GpuPass, GpuTexture, RenderTarget, TextureFormat } from '../gpu/backend.js';
import { GUIDE_INTEGRATE } from '../shaders/guides.js';
import { preprocess } from '../shaders/preprocess.js';
import { UniformLayout } from '../uniforms/layout.js';

/** Formats of the two guide frames a renderer's generate pass appends under VPT_GUIDES: (normal, depth), (albedo, hit). */
export const GUIDE_FRAME_FORMATS: readonly TextureFormat[] = ['rgba32float', 'rgba32float'];

/** Names under which post steps with `usesGuides` see the accumulated guides (see PostStep.usesGuides). */
export const GUIDE_TEXTURE_NAMES = ['guideNormalDepth', 'guideAlbedo', 'guideMoments'] as const;

const GUIDE_UNIFORMS = new UniformLayout('GuideParams', [{ name: 'iteration', type: 'u32' }]);
const ACCUMULATION_FORMATS: TextureFormat[] = ['rgba32float', 'rgba32float', 'rgba32float'];

/**
 * The accumulated denoiser guides (docs/architecture.md, "Denoising"): running means of the
 * renderer's guide frames and of the radiance's luminance moments, ping-ponged like the
 * renderer's own accumulation. Exists only while a post step asks for guides, so renders
 * without a denoiser pay nothing.
 */
export class GuideBuffers {
  private pass: GpuPass | null = null;
  private passHasFrames = false;
  private accum: [RenderTarget, RenderTarget];

  constructor(
    private readonly backend: GpuBackend,
    readonly width: number,
    readonly height: number,
  ) {
    this.accum = [
      backend.createRenderTarget(width, height, ACCUMULATION_FORMATS, 'guides A'),
      backend.createRenderTarget(width, height, ACCUMULATION_FORMATS, 'guides B'),
    ];
  }

  /**
   * Folds iteration `iteration` in: `radiance` is the renderer's frame0 (its new sample), `frames`
   * the two guide frames, or null when the renderer writes none (the guides then stay 0).
   */
  integrate(iteration: number, radiance: GpuTexture, frames: readonly [GpuTexture, GpuTexture] | null): void {
    const withFrames = frames !== null;
    if (!this.pass || this.passHasFrames !== withFrames) {
      const flags = { GUIDE_FRAMES: withFrames };
      this.pass = this.backend.createPass({
        label: 'guides.integrate',
        glsl: preprocess(GUIDE_INTEGRATE.glsl, flags),
        wgsl: preprocess(GUIDE_INTEGRATE.wgsl, flags),
        uniforms: GUIDE_UNIFORMS,
        textures: [
          { name: 'radiance', dimension: '2d' },
          ...(withFrames
            ? [
                { name: 'guideFrame0', dimension: '2d' as const },
                { name: 'guideFrame1', dimension: '2d' as const },
              ]
            : []),
          { name: 'guideAccum0', dimension: '2d' },
          { name: 'guideAccum1', dimension: '2d' },
          { name: 'guideAccum2', dimension: '2d' },
        ],
        outputs: ACCUMULATION_FORMATS,
        defines: flags,
      });
      this.passHasFrames = withFrames;
    }
    const [prev, next] = this.accum;
    const textures: Record<string, GpuTexture> = { radiance };
    if (frames) [textures.guideFrame0, textures.guideFrame1] = frames;
    prev.textures.forEach((t, i) => (textures[`guideAccum${i}`] = t));
    this.backend.draw(this.pass, { uniforms: GUIDE_UNIFORMS.pack({ iteration }), textures, target: next });
    this.accum = [next, prev];
  }

  /** The current means, by the names post steps bind (GUIDE_TEXTURE_NAMES). */
  textures(): Record<(typeof GUIDE_TEXTURE_NAMES)[number], GpuTexture> {
    const [t0, t1, t2] = this.accum[0].textures;
    return { guideNormalDepth: t0, guideAlbedo: t1, guideMoments: t2 };
  }

  get targets(): readonly RenderTarget[] {
    return this.accum;
  }

  destroy(): void {
    this.accum.forEach((t) => this.backend.destroyRenderTarget(t));
  }
}
