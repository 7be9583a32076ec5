import { VptError } from '../errors.js';
import type { BackendLimits } from '../gpu/backend.js';
import type { Renderer } from '../renderer.js';
import type { Scene } from '../scene/scene.js';
import { sliceAtlasLayout } from '../shaders/slice-atlas.js';
import { fail } from './checks.js';
import { validateStepParams } from './params.js';

/**
 * The checks that need the device and the renderer, run by RenderContext.setScene after
 * validateScene: texture sizes against this device's limits, and renderer parameters whose
 * range depends on the scene (ray-march steps of at least MIN_STEP_VOXELS voxels, and the
 * renderer's own `validateScene`). The gradient volume's check (validateGradientAtlasForDevice) runs after the budget fit, on
 * the volume as uploaded.
 */
export function validateSceneForDevice(
  scene: Scene,
  renderer: Renderer,
  limits: Pick<BackendLimits, 'maxTextureDimension2D'>,
): void {
  const env = scene.environment;
  if (env.type === 'latlong') {
    // The conditional CDF texture is one texel wider than the map, the marginal one taller.
    const max = limits.maxTextureDimension2D;
    if (env.width + 1 > max || env.height + 1 > max) {
      fail(
        'Environment',
        `a ${env.width} x ${env.height} lat-long map needs ${env.width + 1} x ${env.height + 1} texel tables; this device's 2D texture limit is ${max} (maxTextureDimension2D)`,
        'limit-exceeded',
      );
    }
  }
  validateStepParams(
    renderer.name.toUpperCase(),
    renderer.paramSpecs,
    renderer.getParams?.() as Record<string, unknown> | undefined,
    scene.volume.dims,
  );
  renderer.validateScene?.(scene);
}

/**
 * The gradient-magnitude volume of a volume of `dims` (for a 2D transfer function, or a
 * renderer that needs it) is a 2D slice atlas: its sides must be within the device's 2D
 * texture limit ('limit-exceeded').
 */
export function validateGradientAtlasForDevice(
  dims: readonly [number, number, number],
  limits: Pick<BackendLimits, 'maxTextureDimension2D'>,
): void {
  const [nx, ny, nz] = dims;
  const atlas = sliceAtlasLayout(dims);
  const max2D = limits.maxTextureDimension2D;
  if (atlas.width > max2D || atlas.height > max2D) {
    throw new VptError(
      'limit-exceeded',
      `The gradient volume of a [${nx}, ${ny}, ${nz}] volume (needed by the 2D transfer function or the renderer) needs a ${atlas.width} x ${atlas.height} slice atlas; this device's 2D texture limit is ${max2D} (maxTextureDimension2D)`,
    );
  }
}
