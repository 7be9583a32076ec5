export { EamRenderer, EAM_PARAM_SPECS, type EamParams } from './eam-renderer.js';
