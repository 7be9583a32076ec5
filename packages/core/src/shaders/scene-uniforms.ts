import { sliceAtlasLayout } from './slice-atlas.js';
import { volumeValueMapping } from '../gpu/volume-format.js';
import { cameraBasis } from '../scene/camera.js';
import type { Scene } from '../scene/scene.js';
import { transferFunctionSize } from '../scene/transfer-function.js';
import { volumeBox } from '../scene/volume.js';
import type { UniformField, UniformValues } from '../uniforms/layout.js';

/**
 * Uniforms every renderer kernel sees, declared once. A renderer's layout is these
 * fields followed by its own, so shared shader chunks can read `u.cameraPosition` etc.
 * in both languages.
 */
export const SCENE_UNIFORM_FIELDS: readonly UniformField[] = [
  { name: 'cameraPosition', type: 'vec3' },
  { name: 'tanHalfFovy', type: 'f32' },
  { name: 'cameraForward', type: 'vec3' },
  { name: 'aspect', type: 'f32' },
  { name: 'cameraRight', type: 'vec3' },
  { name: 'densityScale', type: 'f32' },
  { name: 'cameraUp', type: 'vec3' },
  { name: 'iteration', type: 'u32' },
  { name: 'boxMin', type: 'vec3' },
  { name: 'seed', type: 'u32' },
  { name: 'boxMax', type: 'vec3' },
  { name: 'tfSize', type: 'i32' },
  { name: 'volumeDims', type: 'ivec4' },
  { name: 'background', type: 'vec4' },
  // Rows of the transfer-function texture: 1 for a 1D TF, the gradient axis of a 2D one.
  { name: 'tfHeight', type: 'i32' },
  // Slice-atlas columns of the gradient-magnitude texture (slice-atlas.ts).
  { name: 'gradientAtlasColumns', type: 'i32' },
  // A 2D TF's gradientMax (> 0), or 0: normalize by the volume's largest magnitude.
  { name: 'tfGradientMax', type: 'f32' },
  // Texel → normalized value: v = clamp(texel · valueScale + valueOffset, 0, 1) (gpu/volume-format.ts;
  // the value range, its inversion and the texture format's decoding).
  { name: 'valueScale', type: 'f32' },
  { name: 'valueOffset', type: 'f32' },
  // Where this estimate's samples start in the sample sequence: a kernel draws sample
  // u.iteration + u.sampleBase (rngInit, blueNoiseDim). 0 but under temporal reuse, where each
  // view continues the sequence its history ended at (TemporalReuse.sampleBase).
  { name: 'sampleBase', type: 'u32' },
];

/**
 * The channel variant's uniforms (VPT_CHANNELS; scene/channels.ts), appended after the
 * renderer's and the clip fields only for a channel scene: per drawn channel (component k of
 * the volume texture) its texel → normalized value map, as valueScale / valueOffset for one
 * channel; unused components 0 (they read as value 0).
 */
export const CHANNEL_UNIFORM_FIELDS: readonly UniformField[] = [
  { name: 'channelScale', type: 'vec4' },
  { name: 'channelOffset', type: 'vec4' },
];

/**
 * Values of SCENE_UNIFORM_FIELDS for one iteration at a given image size. `mapping` is the
 * uploaded volume's texel → value map (volumeValueMapping); without it, texels are taken to
 * hold the data values (the exact path's r32float).
 */
export function sceneUniformValues(
  scene: Scene,
  width: number,
  height: number,
  iteration: number,
  tfSize: number,
  mapping?: { valueScale: number; valueOffset: number },
  sampleBase = 0,
): UniformValues {
  const map = mapping ?? volumeValueMapping(scene.volume, { decodeScale: 1, decodeOffset: 0 });
  const basis = cameraBasis(scene.camera);
  const box = volumeBox(scene.volume);
  const env = scene.environment;
  const bg = env.type === 'constant' ? env.radiance : [0, 0, 0];
  return {
    cameraPosition: scene.camera.position,
    tanHalfFovy: Math.tan(scene.camera.fovy / 2),
    cameraForward: basis.forward,
    aspect: width / height,
    cameraRight: basis.right,
    densityScale: scene.densityScale,
    cameraUp: basis.up,
    iteration: iteration >>> 0,
    boxMin: box.min,
    seed: scene.seed >>> 0,
    boxMax: box.max,
    tfSize,
    volumeDims: [...scene.volume.dims, 0],
    background: [bg[0], bg[1], bg[2], 1],
    tfHeight: scene.channels
      ? scene.channels.filter((c) => c.enabled !== false).length
      : transferFunctionSize(scene.transferFunction, tfSize)[1],
    gradientAtlasColumns: sliceAtlasLayout(scene.volume.dims).columns,
    tfGradientMax:
      !scene.channels && scene.transferFunction.dimensions === '2d' ? (scene.transferFunction.gradientMax ?? 0) : 0,
    valueScale: map.valueScale,
    valueOffset: map.valueOffset,
    sampleBase: sampleBase >>> 0,
  };
}

/**
 * A label scene's uniform (scene/labels.ts), after the channels' and only in variants that draw
 * labels: the label texture's texel → id factor (255 for r8unorm, 65535 for r16unorm, 1 for r32float).
 */
export const LABEL_UNIFORM_FIELDS: readonly UniformField[] = [{ name: 'labelScale', type: 'f32' }];
