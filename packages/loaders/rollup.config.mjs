import fs from 'node:fs';
import commonjs from '@rollup/plugin-commonjs';
import { nodeResolve } from '@rollup/plugin-node-resolve';
import typescript from '@rollup/plugin-typescript';
import { libraryConfig } from '../../rollup.lib.mjs';

// Two builds: the library (dist/, dependencies external like every vpt package), and the
// worker (dist/worker/loader-worker.js), which bundles its parsers because a module worker
// gets no import map; the heavy ones (nifti-reader-js, dicom-parser) stay separate chunks
// loaded on first use.
// Chunk names carry content hashes: drop the previous build's chunks, and a sourcemap left by
// an older build that mapped the worker (it would point outside the package when packed).
fs.rmSync('dist/worker/chunks', { recursive: true, force: true });
fs.rmSync('dist/worker/loader-worker.js.map', { force: true });

const worker = {
  input: { 'loader-worker': 'src/worker/loader-worker.ts' },
  // No sourcemap: the worker inlines core and third-party parsers, whose sources lie
  // outside this package; the library build above maps the loaders' own code.
  output: { dir: 'dist/worker', format: 'es', sourcemap: false, chunkFileNames: 'chunks/[name]-[hash].js' },
  plugins: [
    // dicom-parser's UMD build names Node's zlib; the worker passes its own inflater (fflate).
    {
      name: 'no-zlib',
      resolveId: (id) => (id === 'zlib' ? '\0zlib' : null),
      load: (id) => (id === '\0zlib' ? 'export default {};' : null),
    },
    nodeResolve({ browser: true, exportConditions: ['browser', 'import', 'default'] }),
    commonjs(),
    typescript({ tsconfig: './tsconfig.worker.json', compilerOptions: { sourceMap: false, declarationMap: false } }),
  ],
  onwarn(warning, warn) {
    if (warning.code === 'THIS_IS_UNDEFINED' || warning.code === 'CIRCULAR_DEPENDENCY') return;
    warn(warning);
  },
};

export default [libraryConfig(), worker];
