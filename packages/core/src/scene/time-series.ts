import type { Volume } from './volume.js';

/**
 * A volume that changes over time: `steps` volumes of one grid (dims, voxel type), read one
 * at a time. @vpt/loaders makes them from an OME-Zarr `t` axis, a 4D NIfTI file and a list
 * of files (`openTimeSeries`) and hold its steps within a byte budget (`TimeSeriesCache`);
 * any object of this shape works.
 */
export interface TimeSeriesSource<V extends Volume = Volume> {
  readonly steps: number;
  /** Seconds between steps, when the source says (NIfTI pixdim[4], an OME-Zarr `t` scale). */
  readonly stepSeconds?: number;
  loadStep(index: number, signal?: AbortSignal): Promise<V>;
}
