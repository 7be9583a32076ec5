import type { KernelSource } from '../renderer.js';
import * as glsl from './accumulation.glsl.js';
import * as wgsl from './accumulation.wgsl.js';

/** Running mean of a plain-average estimate (accumulation.glsl.ts): one frame/accumulation texture. */
export const RUNNING_MEAN_INTEGRATE: KernelSource = {
  glsl: glsl.RUNNING_MEAN_INTEGRATE,
  wgsl: wgsl.RUNNING_MEAN_INTEGRATE,
};

/** Running means of all, even and odd iterations, for renderers with half accumulations (three rgba32float accumulation textures). */
export const HALF_MEANS_INTEGRATE: KernelSource = {
  glsl: glsl.RUNNING_MEANS_WITH_HALVES_INTEGRATE,
  wgsl: wgsl.RUNNING_MEANS_WITH_HALVES_INTEGRATE,
};

/** Render kernel for renderers whose accumulation already is the HDR image. */
export const COPY_ACCUMULATION_RENDER: KernelSource = {
  glsl: glsl.COPY_ACCUMULATION_RENDER,
  wgsl: wgsl.COPY_ACCUMULATION_RENDER,
};
