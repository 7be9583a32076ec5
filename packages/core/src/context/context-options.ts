import type { BackendLimits, BackendPreference } from '../gpu/backend.js';
import type { VolumeSampling } from '../gpu/volume-format.js';
import type { PostStep } from '../post-step.js';
import type { Renderer } from '../renderer.js';
import type { TemporalOptions } from './temporal-reuse.js';
import { checkNumber, checkOneOf, fail } from '../validation/checks.js';

/**
 * The RenderContext's options and their checks: each option is checked once, when the
 * context is made, through core's field checks (validation/checks.ts), so a bad value is a
 * VptError naming the option; the render size is checked again on every setSize.
 */
export interface RenderContextOptions {
  backend?: BackendPreference;
  canvas?: HTMLCanvasElement | OffscreenCanvas;
  /**
   * Draw on an existing WebGL 2 context (shared with another renderer, such as three.js's
   * WebGLRenderer) instead of one of vpt's own: the WebGL 2 backend is used, the canvas is
   * never resized, and the owner must reset its GL state cache after vpt drew
   * (BackendOptions.gl). Default: vpt acquires its own context from `canvas`.
   */
  gl?: WebGL2RenderingContext;
  /**
   * Draw on an existing GPUDevice (shared with another renderer, such as three.js's
   * WebGPURenderer: `renderer.backend.device`) instead of requesting one: the WebGPU backend
   * is used and the device is never destroyed by vpt (BackendOptions.device).
   */
  device?: GPUDevice;
  /** Render resolution in pixels (the canvas drawing buffer is resized to it, except on a shared context). */
  width: number;
  height: number;
  renderer: Renderer;
  post?: PostStep[];
  /**
   * Temporal reuse across camera changes (docs/architecture.md, "Temporal reuse"): the image
   * shown is reprojected into the new view and blended with the new samples as a fading
   * history. true or options: on (renderers that write guides); default off.
   */
  temporal?: boolean | TemporalOptions;
  /**
   * Volume sampling when the scene does not say (Scene.sampling): 'fast' (default; compact
   * texture, one hardware-filtered fetch) or 'exact' (r32float, manual trilinear).
   */
  sampling?: VolumeSampling;
  /** float32 volumes may be stored as r16float on the fast path (half the memory, ~3 significant digits). Default false. */
  allowHalfFloatVolumes?: boolean;
  /**
   * GPU memory budget in bytes for everything the context allocates. A volume that does not
   * fit (with its gradient volume, the render targets and the transfer function) is
   * downsampled to the largest resolution that does, with a warning (onWarning). Default:
   * WebGPU's maxBufferSize clamped to [1 GiB, 4 GiB]; 1 GiB where the device reports nothing
   * (WebGL 2).
   */
  maxGpuBytes?: number;
  /**
   * Volumes larger than one texture or the budget: 'off' (default) downsamples them to fit;
   * 'auto' holds them as bricks in an atlas with a page table instead (bricking/; a scene
   * with a 2D transfer function, or a renderer that needs the gradient volume, is still
   * downsampled); 'force' bricks every volume (tests, benchmarks).
   */
  bricking?: 'off' | 'auto' | 'force';
  /** Data voxels per brick side, a power of two (default 32). */
  brickSize?: number;
  /** Bricks uploaded per frame at most (default 16); each upload restarts accumulation. */
  brickUploadsPerFrame?: number;
  /**
   * Level of detail for bricked volumes: load no brick finer than the render's pixels need
   * (a voxel of the next coarser level projects to at most one pixel). Default false: every
   * visible brick at the finest level the atlas holds.
   */
  brickLod?: boolean;
}

export type BrickingMode = NonNullable<RenderContextOptions['bricking']>;

/** How the context holds volumes: the checked options with their defaults filled in. */
export interface VolumeOptions {
  sampling: VolumeSampling;
  allowHalfFloat: boolean;
  bricking: BrickingMode;
  brickSize: number;
  brickUploadsPerFrame: number;
  brickLod: boolean;
}

/** The default budget where the device reports nothing about its memory. */
export const DEFAULT_GPU_BYTES = 1024 ** 3;
const MAX_DEFAULT_GPU_BYTES = 4 * 1024 ** 3;

const SAMPLINGS: readonly VolumeSampling[] = ['fast', 'exact'];
const BRICKING_MODES: readonly BrickingMode[] = ['off', 'auto', 'force'];

/** The volume options, checked, with their defaults (throws VptError 'invalid-scene' naming the option). */
export function checkVolumeOptions(opts: RenderContextOptions): VolumeOptions {
  const sampling = checkOneOf('sampling', opts.sampling ?? 'fast', SAMPLINGS);
  const bricking = checkOneOf('bricking', opts.bricking ?? 'off', BRICKING_MODES);
  const brickSize = checkNumber('brickSize', opts.brickSize ?? 32, { min: 8, max: 256, integer: true });
  if (!Number.isInteger(Math.log2(brickSize)))
    fail('brickSize', `must be a power of two from 8 to 256, got ${brickSize}`);
  const brickUploadsPerFrame = checkNumber('brickUploadsPerFrame', opts.brickUploadsPerFrame ?? 16, {
    min: 1,
    integer: true,
  });
  // Flags keep their documented reading: anything but true is false.
  const allowHalfFloat = opts.allowHalfFloatVolumes === true;
  const brickLod = opts.brickLod === true;
  return { sampling, allowHalfFloat, bricking, brickSize, brickUploadsPerFrame, brickLod };
}

/**
 * maxGpuBytes: the caller's positive number of bytes, else WebGPU's maxBufferSize (one
 * allocation the device admits) within [1 GiB, 4 GiB]; 1 GiB on WebGL 2, which reports no
 * memory figure.
 */
export function checkGpuBudget(maxGpuBytes: number | undefined, limits: Pick<BackendLimits, 'maxBufferSize'>): number {
  if (maxGpuBytes !== undefined)
    return checkNumber('maxGpuBytes', maxGpuBytes, {
      min: 0,
      exclusiveMin: true,
      allowInfinity: true,
      unit: 'bytes',
    });
  const m = limits.maxBufferSize;
  return m ? Math.min(MAX_DEFAULT_GPU_BYTES, Math.max(DEFAULT_GPU_BYTES, m)) : DEFAULT_GPU_BYTES;
}

/** A render size: positive integers within the device's 2D texture limit ('limit-exceeded' above it). */
export function checkRenderSize(
  width: number,
  height: number,
  limits: Pick<BackendLimits, 'maxTextureDimension2D'>,
): void {
  checkNumber('width', width, { min: 1, integer: true, unit: 'pixels' });
  checkNumber('height', height, { min: 1, integer: true, unit: 'pixels' });
  const max = limits.maxTextureDimension2D;
  if (width > max || height > max)
    fail(
      'Render size',
      `${width} x ${height} exceeds this device's 2D texture limit of ${max} (maxTextureDimension2D)`,
      'limit-exceeded',
    );
}
