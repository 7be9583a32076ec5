import { UniformLayout, type PostStep, type UniformValues } from '@vpt/core';
import * as glsl from './srgb.glsl.js';
import * as wgsl from './srgb.wgsl.js';

// No parameters; the pad field exists because WGSL forbids empty structs.
const SRGB_UNIFORMS = /* @__PURE__ */ new UniformLayout('SrgbParams', [{ name: 'pad', type: 'f32' }]);

/** Encodes linear [0, 1] colour with the sRGB OETF (IEC 61966-2-1), clamping first; alpha passes through. */
export class SrgbEncodeStep implements PostStep {
  readonly name = 'srgb';
  readonly glsl = glsl.SRGB_ENCODE;
  readonly wgsl = wgsl.SRGB_ENCODE;
  readonly uniforms = SRGB_UNIFORMS;

  uniformValues(): UniformValues {
    return {};
  }
}
