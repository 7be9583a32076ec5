import type { TimeSeriesSource } from '@vpt/core';
import { LoaderError } from './errors.js';
import { loadVolume } from './load-volume.js';
import type { LoadedVolume, LoadOptions, VolumeSource } from './types.js';

/** A time series of loaded volumes, with step 0 already read (its header told how many steps there are). */
export interface LoadedTimeSeries extends TimeSeriesSource<LoadedVolume> {
  /** Step 0, read to learn the series' grid and length. */
  readonly first: LoadedVolume;
}

/**
 * Open a time series: one source that holds its steps (an OME-Zarr store with a `t` axis, a
 * 4D NIfTI file: `meta.timeSteps` steps, each read with `LoadOptions.time`), or a list of
 * sources, one per step (raw + sidecar, NRRD, NIfTI… of one grid; a step of several files,
 * such as a DICOM series, is itself a File list). A one-volume source is a series of one
 * step. Steps of a list whose dims or voxel type differ from step 0's are refused
 * (`invalid-data`). A 4D NIfTI file is read again for each step (a URL's bytes usually come
 * from the HTTP cache the second time).
 */
export async function openTimeSeries(
  source: VolumeSource | readonly VolumeSource[],
  options: LoadOptions = {},
): Promise<LoadedTimeSeries> {
  const list = isStepList(source) ? source : null;
  if (list && list.length === 0)
    throw new LoaderError('empty', 'A time series needs at least one step; the list is empty');
  const first = await loadVolume(list ? list[0] : (source as VolumeSource), { ...options, time: list ? undefined : 0 });
  const steps = list ? list.length : Number((first.meta?.timeSteps as number | undefined) ?? 1);
  const stepSeconds = first.meta?.stepSeconds as number | undefined;
  let firstTaken = false;
  return {
    first,
    steps,
    ...(stepSeconds !== undefined ? { stepSeconds } : {}),
    async loadStep(index: number, signal?: AbortSignal): Promise<LoadedVolume> {
      if (!Number.isInteger(index) || index < 0 || index >= steps)
        throw new LoaderError(
          'bad-header',
          `time step ${index} does not exist (the series has ${steps}, 0 to ${steps - 1})`,
        );
      // Step 0 was read to open the series: handed out once, then read again like any step.
      if (index === 0 && !firstTaken) {
        firstTaken = true;
        return first;
      }
      const o = { ...options, ...(signal ? { signal } : {}) };
      const v = list
        ? await loadVolume(list[index], o)
        : await loadVolume(source as VolumeSource, { ...o, time: index });
      if (v.type !== first.type || v.dims.some((d, i) => d !== first.dims[i]))
        throw new LoaderError(
          'invalid-data',
          `time step ${index} is ${v.dims.join('×')} ${v.type}, unlike step 0's ${first.dims.join('×')} ${first.type}: the steps of a series must share one grid`,
        );
      return v;
    },
  };
}

/** A list is always one source per step here (a multi-file step is a File list inside it). */
function isStepList(s: VolumeSource | readonly VolumeSource[]): s is readonly VolumeSource[] {
  return Array.isArray(s);
}
