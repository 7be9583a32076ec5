/**
 * The loading interface the viewer codes against: the one @vpt/loaders implements
 * (restated here so the viewer builds and type-checks without that package).
 */
import type { RequestPolicy, TransferFunction, Volume } from '@vpt/core';

export type VolumeSource = string | URL | Blob | File | ArrayBuffer | readonly File[];

export interface LoadProgress {
  stage: string;
  loaded: number;
  total?: number;
}

export interface LoadOptions {
  format?: 'auto' | 'raw' | 'nrrd' | 'nifti' | 'dicom' | 'ome-zarr';
  raw?: {
    dims: [number, number, number];
    type: 'uint8' | 'uint16' | 'int16' | 'float32';
    spacing?: [number, number, number];
    endianness?: 'little' | 'big';
  };
  signal?: AbortSignal;
  onProgress?: (p: LoadProgress) => void;
  limits?: { maxTextureDimension3D?: number; maxBytes?: number };
  downsample?: boolean;
  /** Bounds on every request of the load (core's RequestPolicy overrides). */
  request?: Partial<RequestPolicy>;
  /** How headerless raw data gets its dims and type, as the loader's errors say it. */
  rawHint?: string;
  /** The time step of a source holding several (a 4D NIfTI, an OME-Zarr `t` axis). */
  time?: number;
  /** OME-Zarr: the indices along `c` read into one multichannel volume. */
  zarr?: { channels?: number[] };
  /** A label volume: integer ids kept (never normalized or averaged), @vpt/loaders' LoadOptions.labels. */
  labels?: boolean;
}

/**
 * A core Volume plus the format it was read from (and, from @vpt/loaders, orientation and
 * metadata). `multichannel`: set on the scalar view of channel 0 that the element shows of a
 * volume with a channel axis (channels.ts, a lazy chunk).
 */
export type LoadedVolumeLike = Volume & {
  format: string;
  orientation?: number[];
  meta?: Record<string, unknown>;
  multichannel?: ChannelView;
};

/** One channel's settings on `<vpt-viewer>`'s `channels` property (core's ChannelSettings as the element keeps them). */
export interface ViewerChannel {
  /** Linear RGB in [0, 1] replacing the transfer function's colours. */
  color: [number, number, number];
  enabled: boolean;
  /** A 1D transfer function over the channel's normalized value (default: fitted to its histogram). */
  transferFunction?: TransferFunction;
  /** The data range mapped to [0, 1] (default: the channel's own). */
  range?: [number, number];
}

/** What the Channels panel needs of the element. */
export interface ChannelsHost {
  readonly channels: ViewerChannel[] | null;
  setInternal(property: 'channels', value: unknown): void;
}

/** A multichannel volume as the element shows it (channels.ts). */
export interface ChannelView {
  /** The full volume (interleaved channels): the 3D scene's. */
  readonly volume: LoadedVolumeLike;
  /** Every channel's settings: the page's (or the panel's) entries over the defaults. */
  resolve(user: readonly Partial<ViewerChannel>[] | null): ViewerChannel[];
  /** Throws a VptError naming the field when these settings cannot be drawn. */
  check(user: unknown, densityScale: number): void;
  /** The Channels panel's template. */
  panel(host: ChannelsHost): unknown;
  /** The same channels over another object with these voxels (a streamed level 0's stand-in). */
  over(volume: LoadedVolumeLike): ChannelView;
}

export type LoadVolumeFn = (source: VolumeSource, options?: LoadOptions) => Promise<LoadedVolumeLike>;
