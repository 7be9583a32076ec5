import { libraryConfig } from '../../rollup.lib.mjs';
// Two entries: the WebGLRenderer compositor, and the WebGPURenderer one (which imports three/webgpu).
export default libraryConfig({ input: { index: 'src/index.ts', webgpu: 'src/webgpu.ts' } });
