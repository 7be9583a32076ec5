import fs from 'node:fs';
import { describe, expect, it } from 'vitest';

// Issue 28: the README's attribute table lacked `denoise`. Every reflected attribute of
// <vpt-viewer> (VptViewer.properties, not the internal state) must have a row.
const source = fs.readFileSync(new URL('../src/viewer-element.ts', import.meta.url), 'utf8');
const readme = fs.readFileSync(new URL('../README.md', import.meta.url), 'utf8');

function elementAttributes(): string[] {
  const block = /static override properties = \{([\s\S]*?)\n {2}\};/.exec(source)?.[1] ?? '';
  const names: string[] = [];
  for (const m of block.matchAll(/^ {4}(\w+): \{([^}]*)\}/gm)) {
    if (/state: true/.test(m[2])) continue;
    names.push(/attribute: '([^']+)'/.exec(m[2])?.[1] ?? m[1].toLowerCase());
  }
  return names;
}

describe('packages/viewer/README.md', () => {
  it('has a row in the attribute table for every attribute of the element', () => {
    const attrs = elementAttributes();
    expect(attrs.length).toBeGreaterThan(15);
    expect(attrs).toContain('denoise');
    const missing = attrs.filter((a) => !readme.includes(`| \`${a}\` |`));
    expect(missing).toEqual([]);
  });
});
