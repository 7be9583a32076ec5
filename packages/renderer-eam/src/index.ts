export { EamRenderer, EAM_PARAM_SPECS, DEFAULT_EAM_STEP_VOXELS, type EamParams } from './eam-renderer.js';
