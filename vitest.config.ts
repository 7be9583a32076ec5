import { fileURLToPath } from 'node:url';
import { defineConfig } from 'vitest/config';

// Two projects: fast node-side unit tests next to each package, and end-to-end browser
// tests (headless Chromium on SwiftShader) under tests/, which need `pnpm build` first.
const src = (pkg: string) => fileURLToPath(new URL(`./packages/${pkg}/src/index.ts`, import.meta.url));

export default defineConfig({
  // Node-side code imports the workspace packages from source; the browser side loads dist/.
  resolve: {
    alias: {
      '@vpt/core': src('core'),
      '@vpt/renderer-mip': src('renderer-mip'),
      '@vpt/renderer-eam': src('renderer-eam'),
      '@vpt/renderer-iso': src('renderer-iso'),
      '@vpt/renderer-mcrt': src('renderer-mcrt'),
      '@vpt/post': src('post'),
      '@vpt/loaders': src('loaders'),
    },
  },
  test: {
    projects: [
      {
        extends: true,
        test: {
          name: 'unit',
          include: ['packages/*/test/**/*.test.ts', 'benchmarks/test/**/*.test.ts'],
          environment: 'node',
        },
      },
      {
        extends: true,
        test: {
          name: 'browser',
          include: ['tests/**/*.test.ts'],
          environment: 'node',
          testTimeout: 240_000,
          hookTimeout: 120_000,
          // SwiftShader is CPU-bound and CI has 2 cores: one browser at a time.
          fileParallelism: false,
        },
      },
    ],
  },
});
