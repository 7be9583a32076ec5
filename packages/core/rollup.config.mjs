import { libraryConfig } from '../../rollup.lib.mjs';
// scene/labels.ts is the subpath @vpt/core/labels (label volumes, opt-in), not reached from the index;
// shaders/blue-noise.ts the subpath @vpt/core/blue-noise (the blue-noise sampler) and shaders/sampling.ts
// @vpt/core/sampling (ISO's and MCRT's sampling chunks): imported by the renderers only.
export default libraryConfig({
  input: {
    index: 'src/index.ts',
    'scene/labels': 'src/scene/labels.ts',
    'shaders/blue-noise': 'src/shaders/blue-noise.ts',
    'shaders/sampling': 'src/shaders/sampling.ts',
  },
});
