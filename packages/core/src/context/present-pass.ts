import type { PassDescriptor } from '../gpu/backend.js';
import { UniformLayout } from '../uniforms/layout.js';

/** Copies the LDR image to the canvas (the backend flips rows for WebGL's bottom-up canvas). */
export const PRESENT_PASS: PassDescriptor = {
  label: 'present',
  uniforms: new UniformLayout('PresentParams', [{ name: 'pad', type: 'f32' }]),
  textures: [{ name: 'inputImage', dimension: '2d' }],
  outputs: ['rgba8unorm'],
  glsl: /* glsl */ `
void main() {
  vpt_out0 = texelFetch(inputImage, vptPixel(), 0);
}
`,
  wgsl: /* wgsl */ `
@fragment fn fs_main(@builtin(position) fragCoord: vec4f) -> VptOut {
  var o: VptOut;
  o.out0 = textureLoad(inputImage, vptPixel(fragCoord), 0);
  return o;
}
`,
};
