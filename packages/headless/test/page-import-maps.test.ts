/**
 * Every HTML page that loads the built packages through an import map (the headless render
 * page and the browser tests' pages) must map each bare `@vpt/*` specifier that the modules it
 * loads import statically: a missing entry fails the module graph silently (the page never
 * becomes ready), as when a renderer began importing `@vpt/core/labels`.
 */
import fs from 'node:fs';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import { describe, expect, it } from 'vitest';

const ROOT = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '../../..');
const PAGES = [
  'packages/headless/page/index.html',
  ...fs
    .readdirSync(path.join(ROOT, 'tests/pages'))
    .filter((f) => f.endsWith('.html'))
    .map((f) => `tests/pages/${f}`),
];

function importMapOf(html: string): Record<string, string> | undefined {
  const m = /<script type="importmap">([\s\S]*?)<\/script>/.exec(html);
  return m ? (JSON.parse(m[1]!) as { imports: Record<string, string> }).imports : undefined;
}

/** Static imports of one ES module: relative ones resolved to files, bare ones as written. */
function staticImports(file: string): { relative: string[]; bare: string[] } {
  const src = fs.readFileSync(file, 'utf8');
  const relative: string[] = [];
  const bare: string[] = [];
  // `import … from 'x'`, `export … from 'x'` and `import 'x'` (dynamic import() is lazy: not followed).
  for (const m of src.matchAll(/(?:^|[;\s}])(?:import|export)\s*(?:[\w*{}\s,$]+\s*from\s*)?['"]([^'"]+)['"]/g)) {
    const spec = m[1]!;
    if (spec.startsWith('.')) relative.push(path.resolve(path.dirname(file), spec));
    else if (!/^[a-z]+:/i.test(spec)) bare.push(spec); // URLs (in comments of three's bundle) need no map
  }
  return { relative, bare };
}

/** Bare specifiers reachable from the page's mapped entries through static imports. */
function unmapped(map: Record<string, string>, entries: string[]): string[] {
  const missing = new Set<string>();
  const seen = new Set<string>();
  const queue = entries.map((e) => path.join(ROOT, map[e]!));
  while (queue.length) {
    const file = queue.pop()!;
    if (seen.has(file) || !fs.existsSync(file)) continue;
    seen.add(file);
    const { relative, bare } = staticImports(file);
    queue.push(...relative);
    for (const spec of bare) {
      if (!(spec in map)) missing.add(spec);
      else queue.push(path.join(ROOT, map[spec]!));
    }
  }
  return [...missing].sort();
}

const built = fs.existsSync(path.join(ROOT, 'packages/core/dist/index.js'));

describe.skipIf(!built)('import maps of the pages that load built packages', () => {
  for (const page of PAGES) {
    const map = importMapOf(fs.readFileSync(path.join(ROOT, page), 'utf8'));
    if (!map) continue;
    it(`${page} maps every bare specifier its modules import`, () => {
      const entries = Object.keys(map).filter((k) => map[k]!.endsWith('.js'));
      expect(unmapped(map, entries)).toEqual([]);
    });
  }
});
