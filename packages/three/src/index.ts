export { VptVolume, vptViewOf, type VptVolumeOptions, type VptVolumeScene, type VptView } from './vpt-volume.js';
export { VptCompositor, type VptCompositorOptions } from './compositor.js';
