export { EamRenderer, EAM_PARAM_SPECS } from './eam-renderer.js';
export {
  EAM_DESCRIPTOR,
  descriptor,
  DEFAULT_EAM_STEP_VOXELS,
  DEFAULT_EAM_CUTOFF,
  type EamParams,
} from './descriptor.js';
