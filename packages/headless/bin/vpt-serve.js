#!/usr/bin/env node
// The vpt-serve command. Committed, not built, so the file exists when pnpm links bins at
// install time (before any build): bins pointing into dist/ printed "Failed to create bin".
try {
  await import('../dist/cli/serve.js');
} catch (e) {
  if (e?.code !== 'ERR_MODULE_NOT_FOUND' || !String(e.message).includes('dist/cli/serve.js')) throw e;
  console.error('vpt-serve: @vpt/headless is not built yet; run pnpm run build in the vpt workspace');
  process.exit(1);
}
