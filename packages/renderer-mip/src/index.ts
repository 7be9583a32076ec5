export { MipRenderer, MIP_PARAM_SPECS, defaultStepSize } from './mip-renderer.js';
export { MIP_DESCRIPTOR, descriptor, DEFAULT_MIP_STEP_VOXELS, type MipParams } from './descriptor.js';
