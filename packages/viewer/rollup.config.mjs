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
import { libraryConfig } from '../../rollup.lib.mjs';

// Packages the viewer imports only dynamically and that may not be installed (or built):
// each missing one becomes a module that rejects, so only its renderer (or the full
// loaders) is unavailable and the rest of the viewer builds and runs.
const OPTIONAL = ['@vpt/renderer-iso', '@vpt/renderer-mcrt', '@vpt/renderer-slice', '@vpt/loaders'];

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
        return missing.includes(id) ? PREFIX + id : null;
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

const lib = libraryConfig({ input: { index: 'src/index.ts', bundle: 'src/bundle.ts' } });
const libOptional = optionalPackages(false);
const libExternal = lib.external;
lib.external = (id, ...rest) => !libOptional.missing.includes(id) && libExternal(id, ...rest);
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

fs.rmSync('dist/bundle-chunks', { recursive: true, force: true });
const bundle = {
  input: { 'vpt-viewer.bundle': 'dist/bundle.js' },
  preserveEntrySignatures: 'allow-extension',
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

export default [lib, bundle];
