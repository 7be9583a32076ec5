#!/usr/bin/env node
/**
 * `pnpm run gen:renderers`: rewrite the plumbing derived from core's renderer catalog (import
 * map, the viewer's loaders, the headless descriptors and page types, package lists; see
 * renderer-plumbing.mjs). Run it after adding a catalog line, then `pnpm install`.
 */
import fs from 'node:fs';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import { parseCliOrExit } from '@vpt/cli-options';

parseCliOrExit({
  name: 'pnpm run gen:renderers',
  synopsis: '',
  summary:
    "Rewrite the plumbing derived from core's renderer catalog (import map, the viewer's loaders,\n" +
    'the headless descriptors and page types, package lists). Run it after adding a catalog line, then pnpm install.',
  options: {},
});
// Imported after the arguments are checked: the plumbing reads core's built catalog.
const { rendererPlumbing } = await import('./renderer-plumbing.mjs');

const root = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '..');
for (const [file, content] of Object.entries(await rendererPlumbing(root))) {
  const target = path.join(root, file);
  if (fs.existsSync(target) && fs.readFileSync(target, 'utf8') === content) continue;
  fs.writeFileSync(target, content);
  console.log(`wrote ${file}`);
}
