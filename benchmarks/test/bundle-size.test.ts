import { spawnSync } from 'node:child_process';
import fs from 'node:fs';
import { fileURLToPath } from 'node:url';
import { describe, expect, it } from 'vitest';

// Issue 28: the one-file <vpt-viewer> bundle had grown to 136 kB gzip up front, and the Zarr
// codecs shipped twice (page and worker chunks). Measured on the built bundle (skipped unbuilt).
const ROOT = fileURLToPath(new URL('../..', import.meta.url));
const built = fs.existsSync(`${ROOT}packages/viewer/dist/vpt-viewer.bundle.js`);

describe('benchmarks/bundle-size.mjs on the built viewer bundle', () => {
  it.skipIf(!built)('the entry is within 120 kB gzip (figures: docs/benchmarks.md) and no codec ships twice', () => {
    const r = spawnSync(process.execPath, ['benchmarks/bundle-size.mjs'], { cwd: ROOT, encoding: 'utf8' });
    const report = JSON.parse(r.stdout.trim().split('\n').pop()!);
    expect(report.entry.gzip).toBeLessThanOrEqual(120_000);
    expect(report.codecsShippedTwice).toEqual({});
    expect(r.status).toBe(0);
  });
});
