// Shared Rollup config for the library packages: ESM to dist/ with .d.ts, every
// dependency (workspace or npm) left external so users' bundlers dedupe and tree-shake.
import typescript from '@rollup/plugin-typescript';

export function libraryConfig({ input = { index: 'src/index.ts' }, extraExternal = [] } = {}) {
  return {
    input,
    output: { dir: 'dist', format: 'es', sourcemap: true, preserveModules: true, preserveModulesRoot: 'src' },
    external: (id) =>
      (!id.startsWith('.') && !id.startsWith('/') && !id.startsWith('\0')) || extraExternal.includes(id),
    // Sourcemaps carry the TypeScript text (inlineSources), and their paths stay inside the
    // package (dist/ → src/, both published), so a user's dev server finds every source.
    plugins: [typescript({ tsconfig: './tsconfig.build.json', compilerOptions: { inlineSources: true } })],
  };
}
