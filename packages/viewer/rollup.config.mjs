// Two builds: the library (ESM, preserveModules, every dependency external, like the
// other packages) and dist/vpt-viewer.bundle.js, one self-contained file for a plain
// <script type="module"> (Lit, Three.js parts, core, post, renderers inlined). The second
// is bundled from the first's output, so it runs after it (Rollup builds an array in order).
import fs from 'node:fs';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import { nodeResolve } from '@rollup/plugin-node-resolve';
import terser from '@rollup/plugin-terser';
import commonjs from '@rollup/plugin-commonjs';
import typescript from '@rollup/plugin-typescript';
import { libraryConfig } from '../../rollup.lib.mjs';

// Packages that may not be installed (or built): every renderer package (this package's
// @vpt/renderer-* dependencies, written from core's catalog by `pnpm run gen:renderers`) and
// the full loaders. Each missing one (and its subpaths, such as its descriptor) becomes a stub
// module, so only that renderer (or the full loaders) is unavailable and the rest builds and runs.
const OWN_PACKAGE = JSON.parse(fs.readFileSync(new URL('./package.json', import.meta.url), 'utf8'));
const OPTIONAL = [
  ...Object.keys(OWN_PACKAGE.dependencies).filter((name) => name.startsWith('@vpt/renderer-')),
  '@vpt/loaders',
];

// Only this package's own node_modules counts (a declared dependency): Node's resolution
// from here would also find pnpm's hidden hoisted copies, which a user's install lacks.
function packageEntry(name) {
  const dir = path.join(path.dirname(fileURLToPath(import.meta.url)), 'node_modules', ...name.split('/'));
  if (!fs.existsSync(path.join(dir, 'package.json'))) return { installed: false, built: false };
  const pkg = JSON.parse(fs.readFileSync(path.join(dir, 'package.json'), 'utf8'));
  const entry = path.join(dir, pkg.exports?.['.']?.import ?? pkg.main ?? 'dist/index.js');
  return { installed: true, built: fs.existsSync(entry) };
}

function optionalPackages(needBuilt) {
  const missing = OPTIONAL.filter((name) => {
    const p = packageEntry(name);
    return needBuilt ? !p.built : !p.installed;
  });
  if (missing.length)
    console.warn(`@vpt/viewer: not available, stubbed (they will reject when used): ${missing.join(', ')}`);
  const PREFIX = '\0vpt-missing:';
  return {
    missing,
    plugin: {
      name: 'vpt-optional-packages',
      resolveId(id) {
        return missing.some((name) => id === name || id.startsWith(`${name}/`)) ? PREFIX + id : null;
      },
      load(id) {
        if (!id.startsWith(PREFIX)) return null;
        const name = id.slice(PREFIX.length);
        // No throw here: a bundle inlines dynamic imports, so this runs at page load. The
        // importer reports the message when the export it needs is absent.
        return `export const __vptMissing = ${JSON.stringify(`${name} is not installed in this build of @vpt/viewer`)};\n`;
      },
    },
  };
}

const lib = libraryConfig({
  input: { index: 'src/index.ts', bundle: 'src/bundle.ts', 'tf-editor': 'src/tf-editor.ts' },
});
const libOptional = optionalPackages(false);
const libExternal = lib.external;
lib.external = (id, ...rest) =>
  !libOptional.missing.some((name) => id === name || id.startsWith(`${name}/`)) && libExternal(id, ...rest);
lib.plugins = [libOptional.plugin, ...lib.plugins];

const bundleOptional = optionalPackages(true);

// @vpt/loaders parses in a module worker it finds at new URL('./loader-worker.js',
// import.meta.url): put its self-contained worker (and the parser chunks it loads on
// demand) beside the bundle.
function copyLoaderWorker() {
  return {
    name: 'vpt-copy-loader-worker',
    writeBundle(options, bundle) {
      const from = path.join(
        path.dirname(fileURLToPath(import.meta.url)),
        'node_modules',
        '@vpt',
        'loaders',
        'dist',
        'worker',
      );
      if (!fs.existsSync(path.join(from, 'loader-worker.js'))) return;
      // Beside whichever output file holds the worker client (an entry or a lazy chunk).
      const dirs = new Set(
        Object.values(bundle)
          .filter((c) => c.type === 'chunk' && c.code.includes('loader-worker.js'))
          .map((c) => path.dirname(path.join(options.dir, c.fileName))),
      );
      for (const dir of dirs) {
        fs.rmSync(path.join(dir, 'chunks'), { recursive: true, force: true });
        fs.copyFileSync(path.join(from, 'loader-worker.js'), path.join(dir, 'loader-worker.js'));
        fs.cpSync(path.join(from, 'chunks'), path.join(dir, 'chunks'), {
          recursive: true,
          filter: (f) => !f.endsWith('.map'),
        });
      }
    },
  };
}

// The Zarr codecs (numcodecs' zstd, blosc, lz4: WebAssembly inlined, ~450 kB gzip the set) are
// in the loaders' worker chunks, which copyLoaderWorker puts in bundle-chunks/chunks/. The
// page's Zarr reads (bricks streamed from level 0) import those same files instead of a
// second copy of each.
const WORKER_CHUNKS = path.join(
  path.dirname(fileURLToPath(import.meta.url)),
  'node_modules',
  '@vpt',
  'loaders',
  'dist',
  'worker',
  'chunks',
);
const SHARED_CODECS = ['zstd', 'blosc', 'lz4'];
function sharedCodecs() {
  const files = fs.existsSync(WORKER_CHUNKS) ? fs.readdirSync(WORKER_CHUNKS) : [];
  return {
    name: 'vpt-shared-codecs',
    resolveId(id) {
      const m = /^numcodecs\/(\w+)$/.exec(id);
      if (!m || !SHARED_CODECS.includes(m[1])) return null;
      const file = files.find((f) => f.startsWith(`${m[1]}-`) && f.endsWith('.js'));
      if (!file) return null; // no worker build: bundle the codec as before
      // Where the worker's copy lands (bundle-chunks/chunks/), made relative to each importer.
      return { id: path.resolve('dist/bundle-chunks/chunks', file), external: true };
    },
  };
}

// The environment decoder's module worker (src/loading/environment-worker.ts), self-contained
// (a module worker gets no import map) at dist/loading/environment-worker.js, where the
// library's environment-loader.js finds it (new URL('./environment-worker.js', import.meta.url)).
const environmentWorker = {
  input: { 'environment-worker': 'src/loading/environment-worker.ts' },
  output: { dir: 'dist/loading', format: 'es', sourcemap: false, inlineDynamicImports: true },
  plugins: [
    nodeResolve({ browser: true, exportConditions: ['browser', 'import', 'default'] }),
    typescript({ tsconfig: './tsconfig.worker.json' }),
    ...(process.env.VPT_NO_MINIFY ? [] : [terser({ module: true, format: { comments: false } })]),
  ],
  onwarn(warning, warn) {
    if (warning.code === 'THIS_IS_UNDEFINED' || warning.code === 'CIRCULAR_DEPENDENCY') return;
    warn(warning);
  },
};

// The one-file bundle's environment loader is a lazy chunk: put the worker beside it.
function copyEnvironmentWorker() {
  return {
    name: 'vpt-copy-environment-worker',
    writeBundle(options, bundle) {
      const from = path.join(path.dirname(fileURLToPath(import.meta.url)), 'dist', 'loading', 'environment-worker.js');
      if (!fs.existsSync(from)) return;
      for (const c of Object.values(bundle))
        if (c.type === 'chunk' && c.code.includes('environment-worker.js'))
          fs.copyFileSync(from, path.join(path.dirname(path.join(options.dir, c.fileName)), 'environment-worker.js'));
    },
  };
}

fs.rmSync('dist/bundle-chunks', { recursive: true, force: true });
const bundle = {
  input: { 'vpt-viewer.bundle': 'dist/bundle.js' },
  preserveEntrySignatures: 'allow-extension',
  // The shared codecs are external by absolute path: import them relative to the chunk.
  makeAbsoluteExternalsRelative: true,
  // One entry file for a plain page; what the viewer imports dynamically (the iso and mcrt
  // renderers, the NIfTI/DICOM parsers) becomes chunks beside it, fetched on first use.
  output: {
    dir: 'dist',
    format: 'es',
    entryFileNames: '[name].js',
    chunkFileNames: 'bundle-chunks/[name]-[hash].js',
    sourcemap: false,
  },
  plugins: [
    bundleOptional.plugin,
    sharedCodecs(),
    // dicom-parser's UMD build names Node's zlib; @vpt/loaders passes its own inflater (fflate).
    {
      name: 'no-zlib',
      resolveId: (id) => (id === 'zlib' ? '\0zlib' : null),
      load: (id) => (id === '\0zlib' ? 'export default {};' : null),
    },
    nodeResolve({ browser: true, exportConditions: ['browser', 'import', 'default'] }),
    commonjs(),
    ...(process.env.VPT_NO_MINIFY ? [] : [terser({ module: true, format: { comments: false } })]),
    copyLoaderWorker(),
    copyEnvironmentWorker(),
  ],
  onwarn(warning, warn) {
    if (
      warning.code === 'THIS_IS_UNDEFINED' ||
      (warning.code === 'CIRCULAR_DEPENDENCY' && /node_modules/.test(warning.message))
    )
      return;
    warn(warning);
  },
};

export default [lib, environmentWorker, bundle];
