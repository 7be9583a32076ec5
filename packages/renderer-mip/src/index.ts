export { MipRenderer, MIP_PARAM_SPECS, defaultStepSize, type MipParams } from './mip-renderer.js';
