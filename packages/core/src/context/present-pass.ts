import type { PassDescriptor } from '../gpu/backend.js';
import { UniformLayout } from '../uniforms/layout.js';

/**
 * Copies the LDR image to the canvas (the backend flips rows for WebGL's bottom-up canvas).
 * The displayed image is opaque: the background radiance is already in rgb, and a
 * coverage alpha would be misread by a premultiplied-alpha canvas.
 */
export const PRESENT_PASS: PassDescriptor = {
  label: 'present',
  uniforms: new UniformLayout('PresentParams', [{ name: 'pad', type: 'f32' }]),
  textures: [{ name: 'inputImage', dimension: '2d' }],
  outputs: ['rgba8unorm'],
  glsl: /* glsl */ `
void main() {
  vpt_out0 = vec4(texelFetch(inputImage, vptPixel(), 0).rgb, 1.0);
}
`,
  wgsl: /* wgsl */ `
@fragment fn fs_main(@builtin(position) fragCoord: vec4f) -> VptOut {
  var o: VptOut;
  o.out0 = vec4f(textureLoad(inputImage, vptPixel(fragCoord), 0).rgb, 1.0);
  return o;
}
`,
};
