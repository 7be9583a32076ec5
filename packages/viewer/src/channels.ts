/**
 * The viewer's multichannel volumes and its Channels panel: a lazy chunk, imported by
 * loading/volume-source.ts only for a source with a channel axis (an NRRD list/vector/colour
 * axis, NIfTI dim[5], RGB24), so a page of scalar volumes never loads it.
 *
 * The element keeps a scalar view of channel 0 as its volume (histogram of the Transfer
 * function panel, slice panes, probe, camera fit work as for one channel) and carries this
 * module's `Channels` on it as `multichannel`; the 3D scene takes the full volume and the
 * `channels` settings from it (core's scene `channels`: EAM and MCRT see one mixture, MIP the
 * maximum per channel in its colour, added; see docs/architecture.md, "Multichannel volumes").
 *
 * Defaults as microscopy viewers (Vol-E, napari) give them: each channel's transfer function
 * fitted to its own histogram (the viewer's autoTransferFunction), distinct additive colours
 * (green, magenta, cyan, yellow, then red, blue), the first MAX_ENABLED_CHANNELS enabled.
 */
import { html } from 'lit';
import {
  channelCount,
  channelVolume,
  interleaveChannels,
  MAX_ENABLED_CHANNELS,
  validateChannels,
  VptError,
  type MultiscaleLevel,
  type MultiscaleSource,
  type TransferFunction,
  type Volume,
  type VoxelArray,
  type VoxelType,
} from '@vpt/core';
import { hexToLinear, linearToHex } from './color.js';
import { autoTransferFunction } from './defaults.js';
import { valueHistogram, type Histogram1D } from './histogram.js';
import type { ChannelView, ChannelsHost, LoadedVolumeLike, ViewerChannel } from './loading/types.js';

type Rgb = [number, number, number];
type Tf1D = Extract<TransferFunction, { dimensions: '1d' }>;

/** Channel k's default colour (linear RGB): green, magenta, cyan, yellow, red, blue, repeating. */
export const CHANNEL_COLORS: readonly Rgb[] = [
  [0, 1, 0],
  [1, 0, 1],
  [0, 1, 1],
  [1, 1, 0],
  [1, 0, 0],
  [0, 0, 1],
];

/** A 1D transfer function with every point in one colour (what the kernels draw for a channel with `color`). */
export function recolor(tf: TransferFunction, color: readonly number[]): TransferFunction {
  if (tf.dimensions !== '1d') return tf;
  return { ...tf, points: tf.points.map((p) => ({ ...p, color: [color[0], color[1], color[2]] })) };
}

/**
 * The default settings of every channel of a multichannel volume: its transfer function
 * fitted to the channel's histogram over its own range (`ranges[k]`, else the channel's
 * normalization range, as the kernels map it), drawn in its default colour; the first
 * MAX_ENABLED_CHANNELS enabled. Pure: a function of the data.
 */
export function defaultChannels(
  volume: Volume,
  ranges?: readonly (readonly number[] | null | undefined)[],
  colors?: readonly unknown[],
): ViewerChannel[] {
  return Array.from({ length: channelCount(volume) }, (_, k) => {
    const r = ranges?.[k];
    const range = r && r.length === 2 && r[0] !== r[1] ? ([r[0], r[1]] as [number, number]) : undefined;
    // The file's display colour (OME-Zarr omero `RRGGBB`, sRGB) where it gives one, as napari takes it.
    const hex = colors?.[k];
    const color =
      typeof hex === 'string' && /^[0-9a-f]{6}$/i.test(hex)
        ? hexToLinear(hex)
        : ([...CHANNEL_COLORS[k % CHANNEL_COLORS.length]] as Rgb);
    return {
      color,
      enabled: k < MAX_ENABLED_CHANNELS,
      transferFunction: recolor(autoTransferFunction(channelVolume(volume, k, range)), color),
      ...(range ? { range } : {}),
    };
  });
}

/** One channel's entry given by the page or the panel over its default: fields that are set win. */
function over(d: ViewerChannel, u: Partial<ViewerChannel> | undefined): ViewerChannel {
  const out: Record<string, unknown> = { ...d };
  if (u && typeof u === 'object') for (const [k, v] of Object.entries(u)) if (v !== undefined) out[k] = v;
  return out as unknown as ViewerChannel;
}

/** A multichannel volume as the element shows it (see the module comment). */
export class Channels implements ChannelView {
  readonly defaults: ViewerChannel[];
  /** Each channel's name in the panel: the file's label (omero), else its index. */
  readonly names: string[];
  private readonly histograms = new Map<string, Histogram1D>();

  constructor(readonly volume: LoadedVolumeLike) {
    const { channelRanges: ranges, channelColors: colors, channelLabels: labels } = volume.meta ?? {};
    const list = (x: unknown) => (Array.isArray(x) ? x : undefined);
    this.defaults = defaultChannels(volume, list(ranges), list(colors));
    this.names = this.defaults.map((_, k) => {
      const label = list(labels)?.[k];
      return typeof label === 'string' && label ? label : `Channel ${k}`;
    });
  }

  /**
   * The same channels (defaults, names, histograms) over another object with these voxels: the
   * stand-in of a streamed level 0 (RenderContext.setVolumeSource wants a volume of its own).
   */
  over(volume: LoadedVolumeLike): Channels {
    return Object.assign(Object.create(Channels.prototype) as Channels, { ...this, volume });
  }

  resolve(user: readonly Partial<ViewerChannel>[] | null): ViewerChannel[] {
    return this.defaults.map((d, k) => over(d, user?.[k]));
  }

  check(user: unknown, densityScale: number): void {
    if (user === null) return;
    const n = this.defaults.length;
    if (!Array.isArray(user) || user.length > n)
      throw new VptError(
        'invalid-scene',
        `channels: must be an array of at most ${n} channel settings ({color, enabled, transferFunction, range}), got ${JSON.stringify(user)?.slice(0, 80)}`,
      );
    validateChannels(this.resolve(user), this.volume, densityScale);
  }

  /** Channel k's histogram over the range it is drawn in (the 1D editor's backdrop); computed once per range. */
  histogram(k: number, range?: [number, number]): Histogram1D {
    const key = `${k}|${range ?? ''}`;
    let h = this.histograms.get(key);
    if (!h) this.histograms.set(key, (h = valueHistogram(channelVolume(this.volume, k, range))));
    return h;
  }

  /** The Channels panel: per channel an enable toggle, a colour picker and its histogram with the 1D editor. */
  panel(host: ChannelsHost) {
    const list = host.channels ?? this.defaults;
    const on = list.filter((c) => c.enabled).length;
    const set = (k: number, patch: Partial<ViewerChannel>) =>
      host.setInternal(
        'channels',
        list.map((c, i) => (i === k ? { ...c, ...patch } : c)),
      );
    return html`<details open>
      <summary>Channels</summary>
      <div class="panel">
        ${list.map((c, k) => {
          const name = this.names[k];
          const onTf = (e: CustomEvent<{ transferFunction: TransferFunction }>) =>
            set(k, { transferFunction: e.detail.transferFunction });
          return html`<div class="channel" part="channel" data-channel=${k}>
            <div class="row">
              <label
                ><input
                  type="checkbox"
                  data-enable
                  .checked=${c.enabled}
                  ?disabled=${!c.enabled && on >= MAX_ENABLED_CHANNELS}
                  title=${!c.enabled && on >= MAX_ENABLED_CHANNELS ? `At most ${MAX_ENABLED_CHANNELS} channels are drawn at once` : ''}
                  @change=${(e: Event) => set(k, { enabled: (e.target as HTMLInputElement).checked })}
                />
                ${name}</label
              >
              <input
                type="color"
                aria-label="${name} colour"
                .value=${linearToHex(c.color)}
                @change=${(e: Event) => {
                  const color = hexToLinear((e.target as HTMLInputElement).value);
                  set(k, {
                    color,
                    ...(c.transferFunction ? { transferFunction: recolor(c.transferFunction, color) } : {}),
                  });
                }}
              />
            </div>
            <vpt-tf-editor
              .value=${c.transferFunction as Tf1D}
              .histogram=${this.histogram(k, c.range)}
              @input=${onTf}
              @change=${onTf}
            ></vpt-tf-editor>
          </div>`;
        })}
      </div>
    </details>`;
  }
}

/**
 * A loaded volume with a channel axis as the element takes it: channel 0 as a scalar volume
 * (its own data range; placement and meta kept) carrying `multichannel`, the full volume's Channels.
 */
export function withChannels(volume: LoadedVolumeLike): LoadedVolumeLike {
  const one = channelVolume(volume, 0);
  // Every field but the data range (a getter over all channels' voxels): channel 0's own.
  const meta: Record<string, unknown> = {};
  for (const k of Object.keys(volume.meta ?? {})) if (k !== 'dataRange') meta[k] = volume.meta![k];
  let min = Infinity,
    max = -Infinity;
  for (let i = 0; i < one.data.length; i++) {
    const x = one.data[i];
    if (x < min) min = x;
    if (x > max) max = x;
  }
  if (min <= max) meta.dataRange = [min, max];
  const { channels: _all, data: _data, ...rest } = volume;
  void _all;
  void _data;
  return {
    ...rest,
    data: one.data,
    meta: { ...meta, channelCount: volume.channels },
    multichannel: new Channels(volume),
  };
}

const ARRAYS: Record<VoxelType, new (n: number) => VoxelArray> = {
  uint8: Uint8Array,
  uint16: Uint16Array,
  int16: Int16Array,
  float32: Float32Array,
};

/**
 * A store's channels as one multiscale source for the brick cache (MultiscaleSource.channels:
 * the values of every channel per voxel, interleaved, the channel fastest), over one source per
 * channel (`open(k)`, opened on first use; channel 0's given). The bricks keep only the drawn
 * channels (core's BrickChannels.pick), so a region is read only from the channels drawn since
 * streaming began (`draw`, called before a scene that draws them is set, so every brick cache's
 * channels are among them); the others read as 0, which no brick keeps.
 */
export class StreamedChannels implements MultiscaleSource {
  readonly type: VoxelType;
  readonly levels: MultiscaleLevel[];
  private readonly drawn = new Set<number>();
  private readonly parts = new Map<number, Promise<MultiscaleSource>>();

  constructor(
    first: MultiscaleSource,
    readonly channels: number,
    private readonly open: (channel: number) => Promise<MultiscaleSource>,
  ) {
    this.type = first.type;
    this.levels = first.levels;
    this.parts.set(0, Promise.resolve(first));
  }

  /** Channels a scene about to be set draws: read from now on. */
  draw(channels: Iterable<number>): void {
    for (const k of channels) if (k >= 0 && k < this.channels) this.drawn.add(k);
  }

  /** The channels read (drawn since streaming began), in order. */
  get read(): number[] {
    return [...this.drawn].sort((a, b) => a - b);
  }

  private part(k: number): Promise<MultiscaleSource> {
    let p = this.parts.get(k);
    if (!p) {
      p = this.open(k);
      this.parts.set(k, p);
      // A failed open is tried again by the next brick that needs the channel.
      p.catch(() => {
        if (this.parts.get(k) === p) this.parts.delete(k);
      });
    }
    return p;
  }

  async readRegion(
    level: number,
    min: [number, number, number],
    max: [number, number, number],
    signal?: AbortSignal,
  ): Promise<VoxelArray> {
    const read = this.read;
    const regions = await Promise.all(read.map(async (k) => (await this.part(k)).readRegion(level, min, max, signal)));
    const n = (max[0] - min[0]) * (max[1] - min[1]) * (max[2] - min[2]);
    const C = this.channels;
    const out = new ARRAYS[this.type](n * C);
    read.forEach((k, j) => {
      const r = regions[j];
      for (let i = 0; i < n; i++) out[k + C * i] = r[i];
    });
    return out;
  }

  /** A whole level with every channel (a user of the source may want them all; the bricks never read this). */
  async readLevel(level: number, signal?: AbortSignal): Promise<Volume> {
    const all = [...Array(this.channels).keys()];
    const volumes = await Promise.all(all.map(async (k) => (await this.part(k)).readLevel(level, signal)));
    return interleaveChannels(volumes.map((v) => ({ ...v, valueRange: undefined })));
  }
}
