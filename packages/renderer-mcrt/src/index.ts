export { McrtRenderer, MCRT_PARAM_FIELDS } from './mcrt-renderer.js';
export { MCRT_DESCRIPTOR, descriptor } from './descriptor.js';
export {
  MCRT_DEFAULTS,
  FIXED_TRACKING,
  FIXED_ENVIRONMENT_SAMPLING,
  MCRT_PARAM_SPECS,
  MAX_ANISOTROPY,
  MAX_LIGHT_SAMPLES,
  resolveParams,
  type McrtParams,
  type ResolvedMcrtParams,
  type TrackingMode,
  type EnvironmentSampling,
} from './params.js';
export { computeFeatures, activeLights, MAX_LIGHTS, type McrtFeatures } from './features.js';
export {
  buildMajorantGrid,
  computeCellValueRanges,
  cellVoxelRange,
  gridCells,
  OpacityRangeTable,
  volumeCellRanges,
  MAX_GRID_CELLS_PER_AXIS,
  type MajorantGrid,
  type CellValueRanges,
} from '@vpt/core';
export { extinctionCap, OPTICAL_DEPTH_PER_VOXEL_MAX } from './extinction-cap.js';
export { generateKernel } from './kernel-sources.js';
export {
  chooseEstimator,
  chooseLightSamples,
  environmentPeakRatio,
  gridStatistics,
  ENV_PEAK_RATIO_FOR_MIS,
  ENV_PEAK_RATIO_PHASE_TO_MIS,
  GRID_GAIN_FOR_WALK,
  RESIDUAL_MINORANT_FRACTION,
  SINGLE_SCATTERING_LIGHT_SAMPLES,
  PHASE_PEAK_FOR_LIGHT_ONLY,
  phasePeakRatio,
  DELTA_MINORANT_DEPTH,
  type EstimatorChoice,
  type EstimatorRequest,
  type GridStatistics,
} from './estimator-choice.js';
