export { EamRenderer, type EamParams } from './eam-renderer.js';
