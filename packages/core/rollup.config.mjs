import { libraryConfig } from '../../rollup.lib.mjs';
// scene/labels.ts is the subpath @vpt/core/labels (label volumes, opt-in), not reached from the index.
export default libraryConfig({ input: { index: 'src/index.ts', 'scene/labels': 'src/scene/labels.ts' } });
