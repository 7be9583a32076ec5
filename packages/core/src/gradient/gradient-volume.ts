import { VptError } from '../errors.js';
import type { GpuBackend, GpuTexture, RenderTarget } from '../gpu/backend.js';
import type { Volume } from '../scene/volume.js';
import { normalizationRange } from '../scene/volume.js';
import { UniformLayout } from '../uniforms/layout.js';
import { sliceAtlasLayout, type SliceAtlasLayout } from '../shaders/slice-atlas.js';
import * as glslAtlas from '../shaders/slice-atlas.glsl.js';
import * as wgslAtlas from '../shaders/slice-atlas.wgsl.js';
import * as glsl from './gradient.glsl.js';
import * as wgsl from './gradient.wgsl.js';
import { REDUCTION } from './reduction.js';

/**
 * The gradient-magnitude volume of one scalar volume, on the GPU: `atlas` holds |∇f| per
 * voxel (shaders/slice-atlas.ts layout), `max` (1 × 1) the largest value. Bound to renderer kernels as
 * `gradientMagnitude` and `gradientMax` (see the gradient chunk in shaders/common.glsl.ts).
 */
export interface GradientVolume {
  readonly layout: SliceAtlasLayout;
  readonly atlas: RenderTarget;
  readonly max: RenderTarget;
}

const GRADIENT_UNIFORMS = new UniformLayout('GradientParams', [
  { name: 'gradDims', type: 'ivec4' },
  { name: 'gradScale', type: 'vec3' },
  // Texel → normalized value, as the scene uniforms of the same names (gpu/volume-format.ts).
  { name: 'valueScale', type: 'f32' },
  { name: 'valueOffset', type: 'f32' },
]);

/** How the volume texture's texels map to normalized values, and the atlas's precision. */
export interface GradientBuildOptions {
  valueScale: number;
  valueOffset: number;
  /** r16float (the fast path: 2 bytes per voxel, relative error ≤ 2^-11) or r32float (exact). */
  format: 'r16float' | 'r32float';
}
const REDUCE_UNIFORMS = new UniformLayout('ReduceParams', [{ name: 'srcSize', type: 'ivec4' }]);

/**
 * Build the gradient volume from the uploaded volume texture: one pass over
 * the atlas, then ⌈log₈⌉ max reductions. Everything stays on the GPU (no read-back, no
 * main-thread work), so setScene() stays synchronous for volumes of any size.
 * Throws VptError('limit-exceeded') when the atlas would exceed the 2D texture limit.
 */
export function buildGradientVolume(
  backend: GpuBackend,
  volumeTexture: GpuTexture,
  volume: Volume,
  opts: GradientBuildOptions = { valueScale: 1, valueOffset: 0, format: 'r32float' },
): GradientVolume {
  const layout = sliceAtlasLayout(volume.dims);
  const max2D = backend.limits.maxTextureDimension2D;
  if (layout.width > max2D || layout.height > max2D) {
    throw new VptError(
      'limit-exceeded',
      `The gradient volume of a [${volume.dims.join(', ')}] volume needs a ${layout.width} x ${layout.height} slice atlas; this device's 2D texture limit is ${max2D} (maxTextureDimension2D)`,
    );
  }
  const [lo, hi] = normalizationRange(volume);
  const gradientPass = backend.createPass({
    label: 'gradient magnitude',
    glsl: glslAtlas.SLICE_ATLAS + glsl.GRADIENT_MAGNITUDE,
    wgsl: wgslAtlas.SLICE_ATLAS + wgsl.GRADIENT_MAGNITUDE,
    uniforms: GRADIENT_UNIFORMS,
    textures: [{ name: 'volume', dimension: '3d' }],
    outputs: [opts.format],
  });
  const reducePass = backend.createPass({
    label: 'gradient max',
    glsl: glsl.MAX_REDUCE,
    wgsl: wgsl.MAX_REDUCE,
    uniforms: REDUCE_UNIFORMS,
    textures: [{ name: 'src', dimension: '2d' }],
    outputs: ['r32float'],
  });
  const atlas = backend.createRenderTarget(layout.width, layout.height, [opts.format], 'gradient magnitude atlas');
  backend.draw(gradientPass, {
    uniforms: GRADIENT_UNIFORMS.pack({
      gradDims: [...volume.dims, layout.columns],
      // |hi − lo|: an inverted range flips the sign of every derivative, not the magnitude.
      gradScale: volume.spacing.map((s) => Math.abs(hi - lo) / s),
      valueScale: opts.valueScale,
      valueOffset: opts.valueOffset,
    }),
    textures: { volume: volumeTexture },
    target: atlas,
  });
  // Reduce until 1 x 1; intermediate targets are freed as soon as the next one is drawn.
  let src: RenderTarget = atlas;
  do {
    const w = Math.ceil(src.width / REDUCTION),
      h = Math.ceil(src.height / REDUCTION);
    const dst = backend.createRenderTarget(w, h, ['r32float'], 'gradient max');
    backend.draw(reducePass, {
      uniforms: REDUCE_UNIFORMS.pack({ srcSize: [src.width, src.height, 0, 0] }),
      textures: { src: src.textures[0] },
      target: dst,
    });
    if (src !== atlas) backend.destroyRenderTarget(src);
    src = dst;
  } while (src.width > 1 || src.height > 1);
  return { layout, atlas, max: src };
}

export function destroyGradientVolume(backend: GpuBackend, g: GradientVolume): void {
  backend.destroyRenderTarget(g.atlas);
  backend.destroyRenderTarget(g.max);
}
