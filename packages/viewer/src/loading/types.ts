/**
 * The loading interface the viewer codes against: the one @vpt/loaders implements
 * (restated here so the viewer builds and type-checks without that package).
 */
import type { RequestPolicy, Volume } from '@vpt/core';

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
  /** A label volume: integer ids kept (never normalized or averaged), @vpt/loaders' LoadOptions.labels. */
  labels?: boolean;
}

/** A core Volume plus the format it was read from (and, from @vpt/loaders, orientation and metadata). */
export type LoadedVolumeLike = Volume & { format: string; orientation?: number[]; meta?: Record<string, unknown> };

export type LoadVolumeFn = (source: VolumeSource, options?: LoadOptions) => Promise<LoadedVolumeLike>;
