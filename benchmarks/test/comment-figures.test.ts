// Code comments say what the code does and why; measured figures and history live in
// docs/benchmarks.md ("Figures behind code comments"), which comments point at as
// `docs/benchmarks.md#<id>`. This checks that every such pointer names an id the doc has,
// and that no comment line carries history again (an issue number, "(was …", a dated
// measurement). Tests are not scanned: they may name the issue item they check.
import { readdirSync, readFileSync, statSync } from 'node:fs';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import { describe, expect, it } from 'vitest';

const root = fileURLToPath(new URL('../..', import.meta.url));
const CODE_DIRS = [
  ...readdirSync(path.join(root, 'packages')).map((p) => path.join('packages', p, 'src')),
  ...readdirSync(path.join(root, 'apps')).map((p) => path.join('apps', p, 'src')),
  'benchmarks/src',
  'scripts',
  'tools',
];
const CODE = /\.(ts|mts|js|mjs)$/;

function files(dir: string): string[] {
  const abs = path.join(root, dir);
  let names: string[];
  try {
    names = readdirSync(abs);
  } catch {
    return [];
  }
  return names.flatMap((n) => {
    if (n === 'node_modules' || n === 'dist') return [];
    const rel = path.join(dir, n);
    return statSync(path.join(root, rel)).isDirectory() ? files(rel) : CODE.test(n) ? [rel] : [];
  });
}

/** Comment lines (`//`, `/*`, ` *`) with their place, as `file:line`. */
function commentLines(): { at: string; text: string }[] {
  return CODE_DIRS.flatMap(files).flatMap((f) =>
    readFileSync(path.join(root, f), 'utf8')
      .split('\n')
      .flatMap((line, i) => (/^\s*(\/\/|\/\*|\*)/.test(line) ? [{ at: `${f}:${i + 1}`, text: line }] : [])),
  );
}

const HISTORY = [/\b[Ii]ssue \d+/, /\(was /, /\bwas 0\.\d/, /\b[Mm]easured (on )?20\d\d-\d\d/, /\b20\d\d-\d\d-\d\d\b/];

describe('comments and docs/benchmarks.md', () => {
  const lines = commentLines();
  const doc = readFileSync(path.join(root, 'docs', 'benchmarks.md'), 'utf8');
  const ids = new Set([...doc.matchAll(/<a id="([^"]+)"><\/a>/g)].map((m) => m[1]));

  it('scans the code', () => {
    expect(lines.length).toBeGreaterThan(1000);
  });

  it('every docs/benchmarks.md#id pointer in a comment names an anchor of the doc', () => {
    const pointers = lines.flatMap(({ at, text }) =>
      [...text.matchAll(/docs\/benchmarks\.md#([\w-]+)/g)].map((m) => ({ at, id: m[1] })),
    );
    expect(pointers.length).toBeGreaterThan(0);
    const broken = pointers.filter((p) => !ids.has(p.id)).map((p) => `${p.at}: #${p.id}`);
    expect(broken, broken.join('\n')).toEqual([]);
  });

  it('no comment carries history (issue numbers, "(was …", dated measurements)', () => {
    const found = lines
      .filter(({ text }) => HISTORY.some((re) => re.test(text)))
      .map((l) => `${l.at}: ${l.text.trim()}`);
    expect(found, `move these to docs/benchmarks.md ("Figures behind code comments"):\n${found.join('\n')}`).toEqual(
      [],
    );
  });
});
