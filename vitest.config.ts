import { fileURLToPath } from 'node:url';
import { defineConfig } from 'vitest/config';

// Two projects: fast node-side unit tests next to each package, and end-to-end browser
// tests (headless Chromium on SwiftShader) under tests/, which need `pnpm build` first.

export default defineConfig({
  // Node-side code imports the workspace packages from source; the browser side loads dist/.
  resolve: {
    // Core, post, loaders and every renderer package (renderer-*) by the package's folder name.
    alias: [
      {
        find: /^@vpt\/(core|post|loaders|renderer-[a-z0-9-]+)$/,
        replacement: `${fileURLToPath(new URL('./packages/', import.meta.url))}$1/src/index.ts`,
      },
      // Core's label volumes subpath (@vpt/core/labels).
      {
        find: /^@vpt\/core\/labels$/,
        replacement: `${fileURLToPath(new URL('./packages/', import.meta.url))}core/src/scene/labels.ts`,
      },
      // Core's blue-noise sampler subpath (@vpt/core/blue-noise).
      {
        find: /^@vpt\/core\/blue-noise$/,
        replacement: `${fileURLToPath(new URL('./packages/', import.meta.url))}core/src/shaders/blue-noise.ts`,
      },
      // Core's sampling chunks subpath (@vpt/core/sampling).
      {
        find: /^@vpt\/core\/sampling$/,
        replacement: `${fileURLToPath(new URL('./packages/', import.meta.url))}core/src/shaders/sampling.ts`,
      },
      // A renderer package's descriptor subpath (@vpt/renderer-<name>/descriptor).
      {
        find: /^@vpt\/(renderer-[a-z0-9-]+)\/descriptor$/,
        replacement: `${fileURLToPath(new URL('./packages/', import.meta.url))}$1/src/descriptor.ts`,
      },
    ],
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
