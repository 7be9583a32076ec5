/**
 * Label volumes are opt-in (scene/labels.ts): `enableLabels()` registers their validation, GPU
 * textures, majorant bounds and shader chunk here, and the scene checks, the context and the
 * majorant grid reach them only through `labelSupport()`. A bundle that never calls it (the
 * viewer's one-file entry) carries none of that code; a scene with `labels` then fails typed.
 */
import { VptError } from '../errors.js';
import type { BackendCapabilities, TextureDescriptor } from '../gpu/backend.js';
import type { SceneLabels } from './labels.js';
import type { Volume } from './volume.js';

export interface LabelSupport {
  validateLabels(labels: unknown, image: Volume, densityScale: number, imageMaxOpacity: number): void;
  labelTextures(
    labels: SceneLabels,
    caps: BackendCapabilities,
  ): { name: string; dimension: '2d' | '3d'; key: string; create: () => TextureDescriptor }[];
  labelScaleOf(volume: Pick<Volume, 'type'>, caps: BackendCapabilities): number;
  labelCellMajorants(labels: SceneLabels, cells: readonly [number, number, number], densityScale: number): Float32Array;
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
