import { libraryConfig } from '../../rollup.lib.mjs';
// scene/labels.ts is the subpath @vpt/core/labels (label volumes, opt-in), not reached from the index;
// shaders/blue-noise-mask.ts the subpath @vpt/core/blue-noise (the index reaches it only by a dynamic import).
export default libraryConfig({
  input: {
    index: 'src/index.ts',
    'scene/labels': 'src/scene/labels.ts',
    'shaders/blue-noise-mask': 'src/shaders/blue-noise-mask.ts',
  },
});
