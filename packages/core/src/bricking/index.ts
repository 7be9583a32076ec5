export * from './source.js';
export * from './brick-geometry.js';
export * from './brick-cache.js';
export {
  BrickedVolume,
  MAX_BRICKED_CHANNELS,
  atlasSlots,
  type BrickChannels,
  type BrickingOptions,
  type BrickingStats,
} from './bricked-volume.js';
export { brickPriority, type BrickView } from './brick-priority.js';
