export {
  MipRenderer,
  MIP_PARAM_SPECS,
  defaultStepSize,
  DEFAULT_MIP_STEP_VOXELS,
  type MipParams,
} from './mip-renderer.js';
