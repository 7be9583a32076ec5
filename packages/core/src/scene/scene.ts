import { VptError } from '../errors.js';
import { validateCamera, type Camera } from './camera.js';
import { validateChannels, type ChannelSettings } from './channels.js';
import { validateClip, type Clip } from './clip.js';
import type { SceneLabels } from './labels.js';
import { labelSupport } from './label-support.js';
import { validateSlicePlane, type SceneSlicePlane } from './slice-plane.js';
import { validateEnvironment, validateLights, type Environment, type Light } from './lights.js';
import { validateTransferFunction, type TransferFunction } from './transfer-function.js';
import { channelCount, validateVolume, type Volume } from './volume.js';
import { checkNumber, checkObject } from '../validation/checks.js';
import { MAX_DENSITY_SCALE, MAX_EXTINCTION } from '../validation/limits.js';

/** Everything that determines the image. Changing any part resets accumulation. */
export interface Scene {
  volume: Volume;
  transferFunction: TransferFunction;
  camera: Camera;
  lights: Light[];
  environment: Environment;
  /** Extinction per world unit at opacity 1: sigma_t(x) = densityScale * opacity(x). */
  densityScale: number;
  /** User seed mixed into the RNG, so runs are reproducible and independent runs differ. */
  seed: number;
  /**
   * How kernels sample the volume (gpu/volume-format.ts): 'fast' (compact texture, one
   * hardware-filtered fetch) or 'exact' (r32float, manual trilinear in full float: the
   * reference for CPU twins and bit parity). Default: the context's `sampling` option ('fast').
   */
  sampling?: 'fast' | 'exact';
  /**
   * Clip planes and a crop box (scene/clip.ts) that cut the volume away; absent: nothing is
   * cut and the kernels compile no clipping code. Changing it resets accumulation only.
   */
  clip?: Clip;
  /**
   * One entry per channel of the volume (scene/channels.ts): required when the volume has
   * more than one channel; given for a scalar volume it takes that volume through the
   * multichannel path. With channels, `transferFunction` is not drawn (each channel has its
   * own). Absent: the single-channel path, unchanged.
   */
  channels?: ChannelSettings[];
  /**
   * A slice drawn as an opaque, unlit plane inside the volume by the renderers that say
   * `drawsSlicePlane` (scene/slice-plane.ts); absent: no slice-plane code is compiled.
   */
  slicePlane?: SceneSlicePlane;
  /**
   * A label volume (segmentation) and its table (scene/labels.ts), drawn by the renderers that
   * say `drawsLabels`; absent: no label code is compiled.
   */
  labels?: SceneLabels;
}

export function validateScene(s: Scene): void {
  if (!s || typeof s !== 'object') throw new VptError('invalid-scene', 'Scene: missing');
  checkObject('Scene', s);
  validateVolume(s.volume);
  validateTransferFunction(s.transferFunction);
  validateCamera(s.camera);
  validateLights(s.lights ?? []);
  validateEnvironment(s.environment);
  // Bounded so extinction (densityScale × opacity) and the free-flight steps stay finite in float32.
  checkNumber('Scene: densityScale', s.densityScale, {
    min: 0,
    max: MAX_DENSITY_SCALE,
    unit: 'extinction per world unit; MAX_DENSITY_SCALE',
  });
  const maxOpacity =
    s.transferFunction.dimensions === '2d'
      ? Math.max(...s.transferFunction.widgets.map((w) => w.opacity))
      : Math.max(...s.transferFunction.points.map((p) => p.opacity));
  if (s.densityScale * maxOpacity > MAX_EXTINCTION) {
    throw new VptError(
      'invalid-scene',
      `Scene: densityScale ${s.densityScale} × the transfer function's largest opacity ${maxOpacity} = ${s.densityScale * maxOpacity} exceeds the limit ${MAX_EXTINCTION} (MAX_EXTINCTION: shorter free flights fall below float32 resolution)`,
    );
  }
  if (typeof s.seed !== 'number' || !Number.isInteger(s.seed) || s.seed < 0 || s.seed > 0xffffffff)
    throw new VptError('invalid-scene', `Scene: seed must be an integer in [0, 2^32), got ${s.seed}`);
  if (s.sampling !== undefined && s.sampling !== 'fast' && s.sampling !== 'exact')
    throw new VptError('invalid-scene', `Scene: sampling must be 'fast' or 'exact', got ${JSON.stringify(s.sampling)}`);
  if (s.clip !== undefined) validateClip(s.clip);
  if (s.channels !== undefined) validateChannels(s.channels, s.volume, s.densityScale);
  else if (channelCount(s.volume) > 1)
    throw new VptError(
      'invalid-scene',
      `Scene: the volume has ${channelCount(s.volume)} channels, so the scene needs "channels": one entry (transferFunction, enabled, color, range) per channel`,
    );
  if (s.slicePlane !== undefined) validateSlicePlane(s.slicePlane, s.volume);
  // The mixture's extinction is the image's plus the labels': scene/labels.ts bounds the sum.
  if (s.labels !== undefined) labelSupport().validateSceneLabels(s);
}
