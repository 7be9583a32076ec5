/**
 * Label volumes are opt-in (scene/labels.ts): `enableLabels()` registers their validation, GPU
 * textures, majorant bounds and shader chunk here, and the scene checks, the context and the
 * majorant grid reach them only through `labelSupport()`. A bundle that never calls it (the
 * viewer's one-file entry) carries none of that code; a scene with `labels` then fails typed.
 */
import { VptError } from '../errors.js';
import type { BackendCapabilities, TextureDescriptor } from '../gpu/backend.js';
import type { AuxiliaryTexture, VolumeBinding } from '../renderer.js';
import type { SceneLabels } from './labels.js';
import type { Scene } from './scene.js';
import type { Volume } from './volume.js';

export interface LabelSupport {
  /** Scene.labels against the scene (validateScene). */
  validateSceneLabels(scene: Scene): void;
  labelTextures(
    labels: SceneLabels,
    caps: BackendCapabilities,
  ): { name: string; dimension: '2d' | '3d'; key: string; create: () => TextureDescriptor }[];
  labelScaleOf(volume: Pick<Volume, 'type'>, caps: BackendCapabilities): number;
  /** The `'majorants'` grid of a label scene (majorant/grid-textures.ts): the image's plus the labels'. */
  majorantGridTexture(scene: Scene, volume: VolumeBinding, cellSize: number): AuxiliaryTexture;
  /** The label volume by majority vote, for the budget's fit (scene/label-downsample.ts). */
  downsampleLabels(volume: Volume, factors: readonly [number, number, number]): Volume;
  /** GPU bytes per label voxel (uint8: 1; uint16: 2 with 16-bit norm formats, else 4). */
  labelBytesPerVoxel(type: Volume['type'], norm16: boolean): number;
  /** The shared LABELS shader chunk (shaders/labels.*.ts). */
  chunks: { glsl: string; wgsl: string };
}

let support: LabelSupport | null = null;

/** Register (or, with null, remove) the label support. */
export function registerLabelSupport(s: LabelSupport | null): void {
  support = s;
}

/** The registered label support; a scene with labels without it fails with VptError('invalid-scene'). */
export function labelSupport(): LabelSupport {
  if (!support)
    throw new VptError(
      'invalid-scene',
      'Scene: labels: label volumes are not enabled here; call enableLabels() from @vpt/core/labels once before setting such a scene',
    );
  return support;
}
