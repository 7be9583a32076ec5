export {
  EamRenderer,
  EAM_PARAM_SPECS,
  DEFAULT_EAM_STEP_VOXELS,
  DEFAULT_EAM_CUTOFF,
  type EamParams,
} from './eam-renderer.js';
