export { loadVolume } from './load-volume.js';
export { loadInThread } from './load-in-thread.js';
export { LoaderError, isLoaderError, LOADER_ERROR_REASONS, type LoaderErrorReason } from './errors.js';
export {
  DEFAULT_LIMITS,
  type VolumeSource,
  type LoadOptions,
  type LoadProgress,
  type LoadedVolume,
  type LoadLimits,
  type RawOptions,
  type LoaderFormat,
} from './types.js';
export { parseSidecar, rawFromName } from './formats/raw.js';
export { axisCodes } from './formats/orientation.js';
export * from './zarr/index.js';
export type { ZarrLoadOptions } from './types.js';
export { openTimeSeries, DEFAULT_KEEP_BYTES, type LoadedTimeSeries, type TimeSeriesOptions } from './time-series.js';
export { TimeSeriesCache, isTimeSeriesSource, volumeBytes, type TimeSeriesCacheOptions } from './time-series-cache.js';
