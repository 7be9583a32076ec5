export { MipRenderer, defaultStepSize, type MipParams } from './mip-renderer.js';
