import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import { describe, expect, it } from 'vitest';
import { rendererPlumbing } from '../../../scripts/renderer-plumbing.mjs';

const root = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '../../..');

// The import map, the viewer's loaders, the headless descriptors and the package lists are
// written from core's renderer catalog by `pnpm run gen:renderers`; a catalog line added
// without rerunning it (or a hand edit) fails here.
describe('renderer plumbing generated from the catalog', async () => {
  const files = await rendererPlumbing(root);
  for (const [file, expected] of Object.entries(files)) {
    it(`${file} is up to date (pnpm run gen:renderers)`, () => {
      expect(fs.readFileSync(path.join(root, file), 'utf8')).toBe(expected);
    });
  }
  it('follows a new catalog line into every file', async () => {
    // A copy of the generator's inputs with a fifth renderer added to the catalog.
    const tmp = fs.mkdtempSync(path.join(os.tmpdir(), 'vpt-plumbing-'));
    try {
      const inputs = [
        'packages/core/src/catalog/renderer-catalog.ts',
        'packages/headless/page/index.html',
        'packages/headless/package.json',
        'packages/viewer/package.json',
        '.prettierrc.json',
      ];
      for (const f of inputs) {
        fs.mkdirSync(path.dirname(path.join(tmp, f)), { recursive: true });
        fs.copyFileSync(path.join(root, f), path.join(tmp, f));
      }
      const catalog = path.join(tmp, inputs[0]);
      const line = "  { name: 'probe', packageName: '@vpt/renderer-probe', exportName: 'ProbeRenderer' },\n];";
      fs.writeFileSync(catalog, fs.readFileSync(catalog, 'utf8').replace(/\n\];/, `\n${line}`));
      const next = await rendererPlumbing(tmp);
      expect(Object.keys(next).sort()).toEqual(Object.keys(files).sort());
      for (const [file, content] of Object.entries(next)) {
        expect(content, file).toContain('@vpt/renderer-probe');
        expect(content, file).not.toBe(files[file]);
      }
      expect(next['packages/viewer/src/renderer-packages.generated.ts']).toContain("import('@vpt/renderer-probe')");
      expect(next['packages/headless/page/index.html']).toContain(
        '"@vpt/renderer-probe/descriptor": "/packages/renderer-probe/dist/descriptor.js"',
      );
      expect(JSON.parse(next['packages/viewer/package.json']).dependencies['@vpt/renderer-probe']).toBe('workspace:*');
      expect(next['packages/headless/src/renderers.generated.ts']).toMatch(/probe: typeof RendererProbe;/);
    } finally {
      fs.rmSync(tmp, { recursive: true, force: true });
    }
  });
});
