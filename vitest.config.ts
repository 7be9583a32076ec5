import { defineConfig } from 'vitest/config';

// Two projects: fast node-side unit tests next to each package, and end-to-end browser
// tests (headless Chromium on SwiftShader) under tests/, which need `pnpm build` first.
export default defineConfig({
  test: {
    projects: [
      {
        test: {
          name: 'unit',
          include: ['packages/*/test/**/*.test.ts'],
          environment: 'node',
        },
      },
      {
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
