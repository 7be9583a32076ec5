import { VptError } from '../errors.js';
import type { GpuBackend, GpuPass, GpuTexture, PassDescriptor, RenderTarget, TextureFormat } from '../gpu/backend.js';
import type { PostStep } from '../post-step.js';
import { GUIDE_TEXTURE_NAMES, type GuideBuffers } from './guide-buffers.js';

/**
 * The post chain: the HDR image through each PostStep's pass (drawn `repeat` times), the
 * last one writing the rgba8unorm LDR image; its passes, its targets (rgba32float between
 * steps) and the scratch targets of repeated steps, made on first use at the render size.
 */
export class PostChain {
  private passes: GpuPass[] = [];
  private targets: RenderTarget[] = [];
  // Ping-pong targets for the draws of a repeated post step before its last one, by output count.
  private scratch: RenderTarget[][] = [[], []];
  private key = ''; // post-chain parameters the current LDR image was made with

  constructor(
    private readonly backend: GpuBackend,
    private _steps: PostStep[],
  ) {}

  get steps(): readonly PostStep[] {
    return this._steps;
  }

  /** New steps: their passes are made at the next run (the old targets are freed then). */
  setSteps(steps: PostStep[]): void {
    this._steps = steps;
    this.passes = [];
  }

  /** Some post step reads the denoiser guides. */
  wantsGuides(): boolean {
    return this._steps.some((s) => s.usesGuides === true);
  }

  /** The steps' current parameters, as a key of the image they make. */
  parameterKey(): string {
    return JSON.stringify(this._steps.map((s) => [s.name, s.uniformValues(), s.defines?.()]));
  }

  /** Whether the last image was made with these parameters by these steps' passes. */
  madeWith(key: string): boolean {
    return this.key === key && this.passes.length === this._steps.length;
  }

  /** The parameters the image about to be made uses. */
  remember(key: string): void {
    this.key = key;
  }

  /** Draw the chain from `input` (the HDR image), with the denoiser's guides when a step reads them. */
  run(input: GpuTexture, guides: GuideBuffers | null, width: number, height: number): void {
    this.prepare(width, height);
    this._steps.forEach((step, i) => {
      const pass = this.passes[i];
      const guideTextures: Record<string, GpuTexture> = step.usesGuides && guides ? guides.textures() : {};
      const draws = postDraws(step);
      const outputs = step.stateOutput ? 2 : 1;
      // The first draw's state is a placeholder (bound, never read), a texture no draw writes.
      let state: GpuTexture | null = step.stateOutput ? (guideTextures.guideMoments ?? input) : null;
      for (let d = 0; d < draws; d++) {
        // Draws before the last alternate between the two scratch targets; the last writes the step's own.
        const target = d === draws - 1 ? this.targets[i] : this.scratchTarget(d % 2, outputs, width, height);
        this.backend.draw(pass, {
          uniforms: step.uniforms.pack(step.uniformValues(d)),
          textures: { ...guideTextures, inputImage: input, ...(state ? { inputState: state } : {}) },
          target,
        });
        input = target.textures[0];
        if (state) state = target.textures[1];
      }
    });
  }

  /** The last step's LDR image; the chain must not be empty. */
  ldrTexture(): GpuTexture {
    if (this._steps.length === 0) {
      throw new VptError(
        'invalid-scene',
        'The post chain is empty: add at least one step (e.g. sRGB encoding) to get an LDR image',
      );
    }
    return this.targets[this.targets.length - 1].textures[0];
  }

  /**
   * How many leading post steps keep linear radiance (PostStep.keepsRadiance, e.g. the
   * denoiser). The last step writes the LDR image and never counts.
   */
  radianceStepCount(): number {
    let n = 0;
    while (n < this._steps.length - 1 && this._steps[n].keepsRadiance) n++;
    return n;
  }

  /** The output of step `index` (a radiance step's image for readHDR({ afterPost })). */
  output(index: number): RenderTarget {
    return this.targets[index];
  }

  /** Every target the chain holds now (for the context's gpuBytes). */
  allTargets(): RenderTarget[] {
    return [...this.targets, ...this.scratch.flat()];
  }

  /** Free the targets (a new size, dispose); passes and targets are made again at the next run. */
  destroy(): void {
    [...this.targets, ...this.scratch.flat()].forEach((t) => this.backend.destroyRenderTarget(t));
    this.forget();
  }

  /** After a context loss the handles belong to the lost context: drop them without destroying. */
  forget(): void {
    this.targets = [];
    this.scratch = [[], []];
    this.passes = [];
  }

  /** The steps' passes, for RenderContext.precompile: none once they are made. */
  pendingPassDescriptors(): PassDescriptor[] {
    return this.passes.length === this._steps.length ? [] : this.passDescriptors();
  }

  private passDescriptors(): PassDescriptor[] {
    return this._steps.map((step, i) => ({
      label: `post.${step.name}`,
      glsl: step.glsl,
      wgsl: step.wgsl,
      uniforms: step.uniforms,
      textures: [
        { name: 'inputImage', dimension: '2d' },
        ...(step.usesGuides ? GUIDE_TEXTURE_NAMES.map((name) => ({ name, dimension: '2d' as const })) : []),
        ...(step.stateOutput ? [{ name: 'inputState', dimension: '2d' as const }] : []),
      ],
      outputs: outputFormats(step, i === this._steps.length - 1),
      defines: step.defines?.() ?? {},
    }));
  }

  private prepare(width: number, height: number): void {
    if (this.passes.length !== this._steps.length || this.targets.length !== this._steps.length) {
      this.destroy();
      this.passes = this.passDescriptors().map((d) => this.backend.createPass(d));
      this.targets = this._steps.map((step, i) =>
        this.backend.createRenderTarget(width, height, outputFormats(step, i === this._steps.length - 1), `post ${i}`),
      );
    }
  }

  /** Scratch target k (0 or 1) with `outputs` (1 or 2) rgba32float textures for the non-final draws of repeated post steps, made on first use. */
  private scratchTarget(k: number, outputs: number, width: number, height: number): RenderTarget {
    const set = this.scratch[outputs - 1];
    while (set.length <= k)
      set.push(
        this.backend.createRenderTarget(
          width,
          height,
          Array<TextureFormat>(outputs).fill('rgba32float'),
          `post scratch ${outputs}.${set.length}`,
        ),
      );
    return set[k];
  }
}

/** A step's output formats: its image (rgba8unorm for the chain's last step), then its state if it has one. */
function outputFormats(step: PostStep, last: boolean): TextureFormat[] {
  const image: TextureFormat = last ? 'rgba8unorm' : 'rgba32float';
  return step.stateOutput ? [image, 'rgba32float'] : [image];
}

/** Draws of a post step: its `repeat` (a positive integer), else 1. */
function postDraws(step: PostStep): number {
  const r = step.repeat ?? 1;
  if (!Number.isInteger(r) || r < 1)
    throw new VptError('invalid-scene', `post step "${step.name}": repeat must be a positive integer, got ${r}`);
  return r;
}
