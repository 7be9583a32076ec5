/**
 * The channels of a multichannel volume (Volume.channels > 1, or a scalar volume given one
 * channel entry): per channel a 1D transfer function, an enable flag, an optional display
 * colour and an optional value range. At most MAX_ENABLED_CHANNELS are enabled at once;
 * those, in order, are what the GPU holds (one multi-component texture: gpu/volume-format.ts)
 * and what the kernels' VPT_CHANNELS variant reads as a vec4 (shaders/common.*: unused
 * components are 0).
 *
 * How the renderers combine them: EAM and MCRT see one mixture (σ_t = Σ σ_k, colour / albedo
 * the σ-weighted mean of the channels' colours: transferAt in the CHANNELS chunk); MIP keeps
 * the maximum per channel and adds the channels' colours; ISO draws surface k on channel k;
 * the slice shows the first enabled channel.
 */
import { VptError } from '../errors.js';
import { checkNumber } from '../validation/checks.js';
import { MAX_EXTINCTION } from '../validation/limits.js';
import {
  rasterizeTransferFunction,
  TF_RESOLUTION,
  validateTransferFunction,
  type TransferFunction,
} from './transfer-function.js';
import { channelCount, channelVolume, normalizationRange, type Volume } from './volume.js';

/** Channels drawn at once (the components of one RGBA texture). */
export const MAX_ENABLED_CHANNELS = 4;

export interface ChannelSettings {
  /** The channel's 1D transfer function (colour and opacity over its normalized value). */
  transferFunction: TransferFunction;
  /** Drawn when true (default true). */
  enabled?: boolean;
  /**
   * Linear RGB in [0, 1] that replaces the transfer function's colour (a microscopy channel
   * is one hue; its TF then shapes only the opacity). Absent: the TF's own colours.
   */
  color?: [number, number, number];
  /** The data range mapped to [0, 1] for this channel (as Volume.valueRange); absent: the volume's. */
  range?: [number, number];
}

/** The channels a scene draws, in order: indices into the volume's channels (at most 4). */
export function enabledChannels(channels: readonly ChannelSettings[]): number[] {
  const out: number[] = [];
  channels.forEach((c, i) => {
    if (c.enabled !== false) out.push(i);
  });
  return out;
}

/** Check a scene's channel list against its volume; throws VptError('invalid-scene') naming the field. */
export function validateChannels(channels: unknown, volume: Volume, densityScale: number): void {
  const bad = (msg: string) => {
    throw new VptError('invalid-scene', `Scene: channels${msg}`);
  };
  if (!Array.isArray(channels)) bad(` must be an array of channel settings, got ${JSON.stringify(channels)}`);
  const list = channels as ChannelSettings[];
  const n = channelCount(volume);
  if (list.length !== n)
    bad(`: ${list.length} entries for a volume of ${n} channel${n === 1 ? '' : 's'} (one per channel)`);
  let maxSum = 0;
  list.forEach((c, i) => {
    const at = (f: string) => `[${i}]${f}`;
    if (!c || typeof c !== 'object' || Array.isArray(c)) bad(`${at('')} must be an object`);
    for (const k of Object.keys(c))
      if (!['transferFunction', 'enabled', 'color', 'range'].includes(k))
        bad(`${at('')}: unknown field "${k}" (transferFunction, enabled, color, range)`);
    validateTransferFunction(c.transferFunction);
    if (c.transferFunction.dimensions === '2d')
      bad(`${at('.transferFunction')}: a channel takes a 1D transfer function (2D ones are single-channel only)`);
    if (c.enabled !== undefined && typeof c.enabled !== 'boolean')
      bad(`${at('.enabled')} must be true or false, got ${JSON.stringify(c.enabled)}`);
    if (c.color !== undefined) {
      if (!Array.isArray(c.color) || c.color.length !== 3) bad(`${at('.color')} must be [r, g, b]`);
      c.color.forEach((x, j) => checkNumber(`Scene: channels${at(`.color[${j}]`)}`, x, { min: 0, max: 1 }));
    }
    if (
      c.range !== undefined &&
      (!Array.isArray(c.range) ||
        c.range.length !== 2 ||
        !c.range.every((x) => typeof x === 'number' && Number.isFinite(x)) ||
        c.range[0] === c.range[1])
    )
      bad(
        `${at('.range')} must be two different finite numbers [LO, HI] (LO > HI inverts), got ${JSON.stringify(c.range)}`,
      );
    const tf = c.transferFunction;
    if (c.enabled !== false && tf.dimensions !== '2d') maxSum += Math.max(...tf.points.map((p) => p.opacity));
  });
  const on = enabledChannels(list).length;
  if (on === 0) bad(': no channel is enabled (enable at least one)');
  if (on > MAX_ENABLED_CHANNELS)
    bad(`: ${on} channels enabled, at most ${MAX_ENABLED_CHANNELS} (MAX_ENABLED_CHANNELS) are drawn at once`);
  // The mixture's extinction is the sum of the channels': bounded as one channel's is.
  if (densityScale * maxSum > MAX_EXTINCTION)
    throw new VptError(
      'invalid-scene',
      `Scene: densityScale ${densityScale} × the sum of the enabled channels' largest opacities ${maxSum} = ${densityScale * maxSum} exceeds the limit ${MAX_EXTINCTION} (MAX_EXTINCTION)`,
    );
}

/** The range [LO, HI] of channel `c` that maps to [0, 1]: its own, else the volume's rule for that channel's data. */
export function channelNormalizationRange(volume: Volume, c: number, settings?: ChannelSettings): [number, number] {
  return normalizationRange(channelVolume(volume, c, settings?.range));
}

/** Channel `c` of a scene as the scalar volume its settings describe (its range applied): the CPU twins' input. */
export function sceneChannelVolume(volume: Volume, channels: readonly ChannelSettings[], c: number): Volume {
  return channelVolume(volume, c, channels[c]?.range ?? channelNormalizationRange(volume, c));
}

/**
 * The transfer-function texture of a channel scene: one row per enabled channel (row k: the
 * k-th enabled channel's TF rasterized at `resolution` texels), a channel's `color` replacing
 * its TF's colours. RGBA float, `resolution` × rows.
 */
export function rasterizeChannelTransferFunctions(
  channels: readonly ChannelSettings[],
  resolution = TF_RESOLUTION,
): Float32Array {
  const on = enabledChannels(channels);
  const out = new Float32Array(4 * resolution * on.length);
  on.forEach((c, row) => {
    const texels = rasterizeTransferFunction(channels[c].transferFunction, resolution);
    const color = channels[c].color;
    if (color)
      for (let i = 0; i < resolution; i++) {
        texels[4 * i] = color[0];
        texels[4 * i + 1] = color[1];
        texels[4 * i + 2] = color[2];
      }
    out.set(texels, 4 * resolution * row);
  });
  return out;
}

/**
 * A channel scene of one drawn channel as the scalar scene it draws (that channel's data and
 * range, its TF with `color` applied, no `channels`), else null. Used where a CPU bound or
 * choice must be the scalar path's for one channel (majorant grids, MCRT's estimator choice),
 * so one channel through the multichannel path renders the scalar path's bits.
 */
export function scalarSceneOf<
  S extends { volume: Volume; transferFunction: TransferFunction; channels?: ChannelSettings[] },
>(scene: S): S | null {
  if (!scene.channels) return null;
  const memo = scalarScenes.get(scene);
  if (memo !== undefined) return memo as S | null;
  const out = makeScalarScene(scene);
  scalarScenes.set(scene, out);
  return out;
}

// Per scene object (kernels' parameter values ask every iteration; the volume object must stay the same).
const scalarScenes = new WeakMap<object, object | null>();

function makeScalarScene<
  S extends { volume: Volume; transferFunction: TransferFunction; channels?: ChannelSettings[] },
>(scene: S): S | null {
  if (!scene.channels) return null;
  const drawn = enabledChannels(scene.channels);
  if (drawn.length !== 1) return null;
  const c = drawn[0];
  const s = scene.channels[c];
  const tf = s.transferFunction;
  const transferFunction: TransferFunction =
    s.color && tf.dimensions !== '2d'
      ? { ...tf, points: tf.points.map((p) => ({ ...p, color: [...s.color!] as [number, number, number] })) }
      : tf;
  const { channels: _drop, ...rest } = scene;
  void _drop;
  return { ...rest, volume: sceneChannelVolume(scene.volume, scene.channels, c), transferFunction } as S;
}
