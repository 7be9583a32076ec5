/**
 * A scene as plain JSON: what `vpt-render scene.json` reads and what the headless page
 * turns into a core `Scene` + `RenderContext`. Everything is optional; missing fields
 * take the defaults below. Pure data and pure functions only: this module is also
 * loaded by the in-browser page.
 */

import type { Clip, SceneSlicePlane, TransferWidget } from '@vpt/core';

export type Vec3 = [number, number, number];
export type VoxelTypeName = 'uint8' | 'uint16' | 'int16' | 'float32';
export type BackendName = 'auto' | 'webgl2' | 'webgpu';
/** A renderer of core's RENDERER_CATALOG. */
export type RendererName = string;

/** Raw voxels at a URL (relative URLs resolve against the scene file's folder). */
export interface RawVolumeDescription {
  raw: string;
  dims: [number, number, number];
  type: VoxelTypeName;
  spacing?: Vec3;
  valueRange?: [number, number];
  /** Byte order of multi-byte voxels; default little. */
  endianness?: 'little' | 'big';
}

/**
 * A JSON sidecar as in data/*.json (dims, voxel_type, spacing, endianness,
 * value_range); the .raw sits beside it with the same base name.
 */
export interface SidecarVolumeDescription {
  sidecar: string;
}

/**
 * An OME-Zarr image (NGFF v0.4 or v0.5): a folder path (relative to the scene file) or an
 * http(s) URL of the store. `level` 0 is the finest (default); `channel` and `time` pick
 * along the `c` and `t` axes (default 0). The normalization range is `valueRange`, else
 * the channel's omero window, else the data type's (as for raw data).
 */
export interface ZarrVolumeDescription {
  zarr: string;
  level?: number;
  channel?: number;
  /** Several channels along `c`, in this order: a multichannel volume (the scene then needs top-level `channels`). */
  channels?: number[];
  time?: number;
  valueRange?: [number, number];
  /** A chunk the store lacks: 'fill' (default: the array's fill value, as the Zarr spec says) or 'error' (strict). */
  missingChunks?: 'error' | 'fill';
}

/** The formats `volume.format` may force (default 'auto': by name, confirmed by magic bytes). */
export type VolumeFileFormat = 'auto' | 'nifti' | 'nrrd' | 'dicom' | 'raw' | 'ome-zarr';
export const VOLUME_FILE_FORMATS: readonly VolumeFileFormat[] = ['auto', 'nifti', 'nrrd', 'dicom', 'raw', 'ome-zarr'];

/**
 * A volume file in any format @vpt/loaders reads, as the viewer reads it: NIfTI-1 (`.nii`,
 * `.nii.gz`, a `.hdr` with its `.img`), NRRD (`.nrrd`, an `.nhdr` with its data file), a
 * DICOM file, a raw file with its JSON sidecar (either named), an OME-Zarr folder, or a
 * folder of DICOM slices. A list names files loaded together (a series, a header and its
 * data). Paths are relative to the scene file. The normalization range is `valueRange`,
 * else the data's (as for raw data), else the OME-Zarr omero window.
 */
export interface FileVolumeDescription {
  file: string | string[];
  format?: VolumeFileFormat;
  valueRange?: [number, number];
  /** The step of a file holding a time series (a 4D NIfTI's dim[4], an OME-Zarr `t`); default 0. */
  time?: number;
}

/**
 * A time series as a list of files of one grid, one per step (each entry as `file` takes
 * it: a path, or a list of paths loaded together). The scene's `time` picks the step.
 */
export interface TimeSeriesVolumeDescription {
  timeSeries: (string | string[])[];
  format?: VolumeFileFormat;
  valueRange?: [number, number];
}

/** A test volume generated in code (core `createProceduralVolume`). */
export interface ProceduralVolumeDescription {
  procedural: 'sphere' | 'cube' | 'ramp' | 'blob';
  size?: number;
}

/** Several volumes of one grid and voxel type, one per channel (interleaved into one multichannel volume). */
export interface ChannelFilesVolumeDescription {
  channels: SingleVolumeDescription[];
}

/** One volume (one channel, or a scalar volume). */
export type SingleVolumeDescription =
  | RawVolumeDescription
  | SidecarVolumeDescription
  | ZarrVolumeDescription
  | FileVolumeDescription
  | TimeSeriesVolumeDescription
  | ProceduralVolumeDescription;

export type VolumeDescription = ChannelFilesVolumeDescription | SingleVolumeDescription;

/** A list of volumes, one per channel (not an OME-Zarr store's `channels` indices). */
export function isChannelFiles(v: VolumeDescription): v is ChannelFilesVolumeDescription {
  return 'channels' in v && !('zarr' in v);
}

export interface TransferPointDescription {
  value: number;
  color: Vec3;
  opacity: number;
}

export type EnvironmentDescription =
  | { type: 'constant'; radiance: Vec3 }
  /** RGB floats, row 0 at the top, as a plain array. */
  | { type: 'latlong'; width: number; height: number; data: number[]; scale?: number };

export interface SceneDescription {
  width?: number;
  height?: number;
  renderer?: RendererName;
  /** Passed to the renderer's constructor (e.g. `{ "stepSize": 0.005 }`). */
  rendererParams?: Record<string, unknown>;
  volume?: VolumeDescription;
  /** 1D (control points) or 2D (value x gradient-magnitude widgets, as core's TransferFunction2D). */
  transferFunction?:
    { dimensions?: '1d'; points: TransferPointDescription[] } | { dimensions: '2d'; widgets: TransferWidget[] };
  /** Merged over core's `defaultCamera()`; fovy is the full vertical angle in radians. */
  camera?: { position?: Vec3; target?: Vec3; up?: Vec3; fovy?: number };
  lights?: { type: 'directional'; direction: Vec3; irradiance: Vec3 }[];
  environment?: EnvironmentDescription;
  densityScale?: number;
  seed?: number;
  /** Volume sampling: 'fast' (default; compact texture, hardware filter) or 'exact' (r32float, manual trilinear). */
  sampling?: 'fast' | 'exact';
  /** Clip planes and a crop box in world units of the volume box (core's scene/clip.ts). */
  clip?: Clip;
  /**
   * A slice drawn as an opaque, unlit plane inside the volume by MIP, EAM, ISO and MCRT (core's
   * scene/slice-plane.ts): axis + index/position or normal + point, window [center, width] in data units, colormap.
   */
  slicePlane?: SceneSlicePlane;
  /** GPU memory budget in bytes (RenderContext's maxGpuBytes): a larger volume is downsampled, with a warning. */
  maxGpuBytes?: number;
  /** Post chain as JSON, for `postChainFromJSON` of @vpt/post (default SCENE_DEFAULTS.post, or DISPLAY_REFERRED_POST for a renderer whose descriptor is displayReferred). */
  post?: Record<string, unknown>[];
  iterations?: number;
  backend?: BackendName;
  /**
   * The time step to render (default 0) of a volume that is a time series: a `timeSeries`
   * list, a 4D NIfTI `file`, an OME-Zarr `zarr` with a `t` axis (where it sets no `time`).
   */
  time?: number;
  /**
   * One entry per channel of a multichannel volume (core's ChannelSettings): a 1D transfer
   * function, `enabled` (default true; at most 4 at once), an optional linear-RGB `color`
   * replacing the TF's colours and an optional data `range`. The top-level `transferFunction`
   * is then not drawn.
   */
  channels?: {
    transferFunction: { dimensions?: '1d'; points: TransferPointDescription[] };
    enabled?: boolean;
    color?: Vec3;
    range?: [number, number];
  }[];
  /**
   * A label volume (segmentation) on the image's grid and its table (core's SceneLabels): the
   * ids (uint8 / uint16 kept as they are; other types converted when every value is an integer
   * id; never normalized) and per id a linear-RGB `color`, `opacity`, `visible` and `name`;
   * without `table`, every id present with the default palette. Without `volume`, the labels are
   * drawn alone (an empty uint8 image of their grid).
   */
  labels?: {
    volume: SingleVolumeDescription;
    table?: { id: number; name?: string; color?: Vec3; opacity?: number; visible?: boolean }[];
  };
}

/** What an unset field means (an unset renderer is core's DEFAULT_RENDERER_NAME). */
export const SCENE_DEFAULTS = {
  width: 64,
  height: 64,
  volume: { procedural: 'sphere', size: 32 } as VolumeDescription,
  environment: { type: 'constant', radiance: [1, 1, 1] } as EnvironmentDescription,
  densityScale: 10,
  seed: 1,
  post: [{ type: 'exposure', exposure: 0 }, { type: 'tonemap', operator: 'aces' }, { type: 'srgb' }] as Record<
    string,
    unknown
  >[],
  iterations: 64,
  backend: 'auto' as BackendName,
};

/** The post chain of an unset `post` for a renderer whose descriptor says its HDR image holds display values: exposure → clamp. */
export const DISPLAY_REFERRED_POST: Record<string, unknown>[] = [
  { type: 'exposure', exposure: 0 },
  { type: 'tonemap', operator: 'clamp' },
];

export const BACKEND_NAMES: readonly BackendName[] = ['auto', 'webgl2', 'webgpu'];

/**
 * The description of one time step: the scene's `time` moved into its volume (a list's
 * entry becomes a `file`, a file or store gets `time`), so what loads is one volume. A
 * description without `time` and without a `timeSeries` volume comes back as it is.
 * Throws (naming the field) for a step past the end of a list, and for a `time` above 0 on
 * a volume that cannot be a time series (raw, sidecar, procedural).
 */
export function selectTimeStep(d: SceneDescription): SceneDescription {
  const v = d.volume as Record<string, unknown> | undefined;
  const isList = !!v && Array.isArray(v.timeSeries);
  if (d.time === undefined && !isList) return d;
  const { time: step = 0, ...rest } = d;
  if (!Number.isInteger(step) || step < 0)
    throw new Error(`Scene description: "time" must be a whole number ≥ 0, got ${JSON.stringify(step)}`);
  if (isList) {
    const { timeSeries, ...others } = v as unknown as TimeSeriesVolumeDescription;
    if (step >= timeSeries.length)
      throw new Error(
        `Scene description: "time" ${step} is past the end of volume.timeSeries (${timeSeries.length} steps, 0 to ${timeSeries.length - 1})`,
      );
    return { ...rest, volume: { ...others, file: timeSeries[step] } };
  }
  if (v && ('file' in v || 'zarr' in v))
    return { ...rest, volume: { ...(v as object), time: (v.time as number) ?? step } as VolumeDescription };
  if (step > 0)
    throw new Error(
      `Scene description: "time" ${step}: the volume is not a time series (use "timeSeries", a 4D NIfTI or NRRD "file" or an OME-Zarr "zarr")`,
    );
  return rest;
}

/**
 * Catch the mistakes a person makes when writing a scene file by hand, with a message
 * that names the field. (The scene model itself is validated again by core.)
 */
/**
 * Check a description's shape; `rendererNames` (core's catalog names, which this pure
 * module does not import) lets the caller reject an unknown renderer early.
 */
export function checkSceneDescription(d: unknown, rendererNames?: readonly string[]): asserts d is SceneDescription {
  const bad = (m: string): never => {
    throw new Error(`Scene description: ${m}`);
  };
  if (!d || typeof d !== 'object' || Array.isArray(d)) bad('must be a JSON object');
  const s = d as Record<string, unknown>;
  const posInt = (k: string) => {
    if (s[k] !== undefined && !(Number.isInteger(s[k]) && (s[k] as number) >= 1))
      bad(`"${k}" must be a positive integer, got ${JSON.stringify(s[k])}`);
  };
  posInt('width');
  posInt('height');
  posInt('iterations');
  if (s.seed !== undefined && !(Number.isInteger(s.seed) && (s.seed as number) >= 0))
    bad(`"seed" must be a non-negative integer, got ${JSON.stringify(s.seed)}`);
  if (s.sampling !== undefined && s.sampling !== 'fast' && s.sampling !== 'exact')
    bad(`"sampling" must be "fast" or "exact", got ${JSON.stringify(s.sampling)}`);
  if (s.maxGpuBytes !== undefined && !(typeof s.maxGpuBytes === 'number' && s.maxGpuBytes > 0))
    bad(`"maxGpuBytes" must be a positive number of bytes, got ${JSON.stringify(s.maxGpuBytes)}`);
  if (
    s.renderer !== undefined &&
    (typeof s.renderer !== 'string' || (rendererNames && !rendererNames.includes(s.renderer)))
  ) {
    bad(
      `"renderer" must be ${rendererNames ? `one of ${rendererNames.join(', ')}` : 'a renderer name'}, got ${JSON.stringify(s.renderer)}`,
    );
  }
  if (s.backend !== undefined && !BACKEND_NAMES.includes(s.backend as BackendName))
    bad(`"backend" must be one of ${BACKEND_NAMES.join(', ')}, got ${JSON.stringify(s.backend)}`);
  if (s.post !== undefined && !Array.isArray(s.post)) bad('"post" must be an array of steps');
  if (s.lights !== undefined && !Array.isArray(s.lights)) bad('"lights" must be an array');
  if (s.labels !== undefined) {
    const l = s.labels as Record<string, unknown>;
    if (!l || typeof l !== 'object' || Array.isArray(l)) bad('"labels" must be an object { volume, table }');
    if (!l.volume || typeof l.volume !== 'object') bad('"labels.volume" must be a volume description');
    if (l.table !== undefined && !Array.isArray(l.table)) bad('"labels.table" must be an array');
  }
  const v = s.volume as Record<string, unknown> | undefined;
  if (v !== undefined) {
    if (!v || typeof v !== 'object') bad('"volume" must be an object');
    else if (Array.isArray(v.channels) && typeof v.zarr !== 'string') {
      // One volume per channel: each is checked as a volume (validateSceneDescription does it field by field).
      if (!v.channels.length) bad('"volume.channels" names no channel');
    } else if (typeof v.raw === 'string') {
      if (!Array.isArray(v.dims) || v.dims.length !== 3) bad('"volume.dims" must be [nx, ny, nz]');
      if (!['uint8', 'uint16', 'int16', 'float32'].includes(v.type as string))
        bad(`"volume.type" must be uint8, uint16, int16 or float32, got ${JSON.stringify(v.type)}`);
    } else if (
      typeof v.sidecar !== 'string' &&
      typeof v.procedural !== 'string' &&
      typeof v.zarr !== 'string' &&
      typeof v.file !== 'string' &&
      !Array.isArray(v.file) &&
      !Array.isArray(v.timeSeries)
    ) {
      bad(
        '"volume" needs one of "file", "timeSeries", "raw" (with dims and type), "sidecar", "zarr", "procedural" or "channels"',
      );
    }
  }
}
