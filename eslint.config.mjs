// ESLint flat config: typescript-eslint's recommended rules (no type-aware rules, so a lint
// run needs no build and stays fast) over every TypeScript and JavaScript source.
import js from '@eslint/js';
import tseslint from 'typescript-eslint';

export default tseslint.config(
  {
    ignores: [
      '**/dist/**',
      '**/node_modules/**',
      'benchmarks/results/**',
      'docs/benchmarks/**',
      'apps/gallery/dist/**',
      'out/**',
      'data/**',
    ],
  },
  js.configs.recommended,
  ...tseslint.configs.recommended,
  {
    languageOptions: {
      ecmaVersion: 2022,
      sourceType: 'module',
      globals: {
        window: 'readonly',
        document: 'readonly',
        console: 'readonly',
        performance: 'readonly',
        fetch: 'readonly',
        URL: 'readonly',
        setTimeout: 'readonly',
        clearTimeout: 'readonly',
        requestAnimationFrame: 'readonly',
        cancelAnimationFrame: 'readonly',
        process: 'readonly',
        Buffer: 'readonly',
        navigator: 'readonly',
        location: 'readonly',
        history: 'readonly',
        customElements: 'readonly',
        HTMLElement: 'readonly',
        GPUBufferUsage: 'readonly',
        GPUMapMode: 'readonly',
        GPUTextureUsage: 'readonly',
        Worker: 'readonly',
        self: 'readonly',
        ResizeObserver: 'readonly',
        URLSearchParams: 'readonly',
        Option: 'readonly',
        Blob: 'readonly',
        File: 'readonly',
        Response: 'readonly',
        structuredClone: 'readonly',
        btoa: 'readonly',
        atob: 'readonly',
      },
    },
    rules: {
      // Page code reached through page.evaluate, WebGPU/GL internals and JSON input are typed
      // at their edges with `any` on purpose; the strict TypeScript build checks the rest.
      '@typescript-eslint/no-explicit-any': 'off',
      // `_`-prefixed parameters are the code base's way to say "unused on purpose".
      '@typescript-eslint/no-unused-vars': [
        'error',
        { argsIgnorePattern: '^_', varsIgnorePattern: '^_', caughtErrors: 'none' },
      ],
      // Optional renderer packages are imported where type-checking may not find them.
      '@typescript-eslint/ban-ts-comment': [
        'error',
        { 'ts-ignore': 'allow-with-description', 'ts-expect-error': 'allow-with-description' },
      ],
    },
  },
  {
    // Plain-JS sources (build scripts, the gallery, test fixtures) run in Node or the browser.
    files: ['**/*.js', '**/*.mjs'],
    rules: { '@typescript-eslint/no-unused-vars': ['error', { argsIgnorePattern: '^_', caughtErrors: 'none' }] },
  },
);
