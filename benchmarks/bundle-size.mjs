#!/usr/bin/env node
/**
 * The one-file <vpt-viewer> bundle's size (issue 28): gzip bytes (level 9) of the entry file a
 * page loads up front, of each lazy chunk beside it (renderers, parsers, codecs, the loaders'
 * worker and its chunks), and any file shipped twice (the same content, or the same codec
 * name in the page's and the worker's chunks).
 *
 *   pnpm run build && node benchmarks/bundle-size.mjs [--dir packages/viewer/dist] [--budget 120]
 *
 * Prints a table, then one JSON line. Exits 1 when the entry is over --budget kB (1 kB = 1000
 * bytes) or a codec ships twice.
 */
import crypto from 'node:crypto';
import fs from 'node:fs';
import path from 'node:path';
import zlib from 'node:zlib';
import { parseCliOrExit } from '@vpt/cli-options';

const { dir, budget } = parseCliOrExit({
  name: 'node benchmarks/bundle-size.mjs',
  synopsis: '[--dir DIR] [--budget KB]',
  summary: 'Gzip sizes of the <vpt-viewer> bundle: up front and per lazy chunk (needs pnpm run build).',
  options: {
    dir: { type: 'string', default: 'packages/viewer/dist', description: "the viewer's dist folder" },
    budget: { type: 'number', min: 0, default: 120, description: 'the most kB (gzip) the entry file may have' },
  },
});

const ENTRY = 'vpt-viewer.bundle.js';
const entryPath = path.join(dir, ENTRY);
if (!fs.existsSync(entryPath)) {
  console.error(`${entryPath} not found: run pnpm run build first`);
  process.exit(2);
}

function files(folder) {
  if (!fs.existsSync(folder)) return [];
  return fs.readdirSync(folder, { withFileTypes: true }).flatMap((e) => {
    const p = path.join(folder, e.name);
    return e.isDirectory() ? files(p) : e.name.endsWith('.js') ? [p] : [];
  });
}

function measure(file) {
  const bytes = fs.readFileSync(file);
  return {
    file: path.relative(dir, file),
    bytes: bytes.length,
    gzip: zlib.gzipSync(bytes, { level: 9 }).length,
    sha: crypto.createHash('sha256').update(bytes).digest('hex').slice(0, 16),
  };
}

const entry = measure(entryPath);
const chunks = files(path.join(dir, 'bundle-chunks'))
  .map(measure)
  .sort((a, b) => b.gzip - a.gzip);
const codecOf = (f) => /(?:^|\/)(zstd|blosc|lz4)-[^/]+\.js$/.exec(f)?.[1] ?? null;
const codecs = {};
for (const c of chunks) {
  const name = codecOf(c.file);
  if (name) (codecs[name] ??= []).push(c.file);
}
const twiceCodecs = Object.entries(codecs).filter(([, list]) => list.length > 1);
const bySha = {};
for (const c of chunks) (bySha[c.sha] ??= []).push(c.file);
const sameContent = Object.values(bySha).filter((list) => list.length > 1);

const kb = (n) => (n / 1000).toFixed(1).padStart(8);
console.log(`${'gzip kB'.padStart(8)} ${'raw kB'.padStart(8)}  file`);
console.log(`${kb(entry.gzip)} ${kb(entry.bytes)}  ${entry.file}  (up front)`);
for (const c of chunks) console.log(`${kb(c.gzip)} ${kb(c.bytes)}  ${c.file}`);
const lazyGzip = chunks.reduce((a, c) => a + c.gzip, 0);
console.log(`${kb(lazyGzip)} ${' '.repeat(8)}  all lazy chunks`);
for (const [name, list] of twiceCodecs) console.log(`codec ${name} ships ${list.length} times: ${list.join(', ')}`);
for (const list of sameContent) console.log(`same content: ${list.join(', ')}`);

const over = entry.gzip > budget * 1000;
console.log(
  JSON.stringify({
    entry: { file: entry.file, bytes: entry.bytes, gzip: entry.gzip },
    budgetGzip: budget * 1000,
    overBudget: over,
    chunks: chunks.map(({ file, bytes, gzip }) => ({ file, bytes, gzip })),
    lazyGzip,
    codecsShippedTwice: Object.fromEntries(twiceCodecs),
    sameContent,
  }),
);
process.exit(over || twiceCodecs.length ? 1 : 0);
