/**
 * Every dataset of data/datasets.json: its raw file loads through its sidecar to the
 * recorded sha256, and where the catalog names an original NIfTI/NRRD file, that file loads
 * to exactly the same voxels. Datasets committed to the repository (`committedAt`: the
 * bundled head in data/, the loader fixtures) always run; the larger ones run when
 * `pnpm data:fetch` has put them in data/fetched/, and are skipped otherwise (CI) — the
 * skip is in the test's title and printed once at run time.
 */
import fs from 'node:fs';
import path from 'node:path';
import { afterAll, describe, expect, it } from 'vitest';
import { loadVolume } from '../src/index.js';
import { HERE, fileOf, sha256 } from './helpers.js';

const root = path.resolve(HERE, '../../..');
const fetched = path.join(root, 'data', 'fetched');
interface Dataset {
  name: string;
  file: string;
  sha256: string;
  committedAt?: string;
  sidecar: { dims: number[]; spacing: number[]; voxel_type: string };
  original?: { file: string };
}
const catalog: Dataset[] = JSON.parse(fs.readFileSync(path.join(root, 'data', 'datasets.json'), 'utf8')).datasets;

/** The folder that holds a dataset's files: where it is committed, else data/fetched/. */
const folderOf = (d: Dataset) => (d.committedAt ? path.dirname(path.join(root, d.committedAt)) : fetched);
const read = (d: Dataset, f: string) => new Uint8Array(fs.readFileSync(path.join(folderOf(d), f)));
const sidecarOf = (d: Dataset) => d.file.replace(/\.raw$/, '.json');

const skipped: string[] = [];
const NOT_FETCHED = 'skipped: not in data/fetched/, run `pnpm data:fetch`';

describe('datasets of data/datasets.json (committed ones always, fetched ones when present)', () => {
  it('the catalog lists the bundled head and the committed loader fixtures, and their files are in the repository', () => {
    const committed = catalog.filter((d) => d.committedAt).map((d) => d.committedAt);
    expect(committed).toContain('data/mri_head_volpack_brainsmall_128x128x84_uint8.raw');
    expect(committed.length).toBeGreaterThanOrEqual(3);
    for (const d of catalog.filter((x) => x.committedAt)) {
      expect(fs.existsSync(path.join(root, d.committedAt!)), d.committedAt).toBe(true);
      expect(path.basename(d.committedAt!)).toBe(d.file);
      expect(fs.existsSync(path.join(folderOf(d), sidecarOf(d))), `${d.name} sidecar`).toBe(true);
    }
  });

  for (const d of catalog) {
    const present =
      fs.existsSync(path.join(folderOf(d), d.file)) && fs.existsSync(path.join(folderOf(d), sidecarOf(d)));
    // A committed dataset never skips: a missing file must fail (the test above says which).
    const skip = !d.committedAt && !present;
    if (skip) skipped.push(d.name);
    const where = d.committedAt ? `committed at ${path.dirname(d.committedAt)}/` : present ? 'fetched' : NOT_FETCHED;
    it.skipIf(skip)(
      `${d.name} (${where}): raw + sidecar load to the recorded sha256`,
      async () => {
        const json = sidecarOf(d);
        const v = await loadVolume([fileOf(read(d, json), json), fileOf(read(d, d.file), d.file)], {
          limits: { maxBytes: 256 << 20 },
        });
        expect(v.dims).toEqual(d.sidecar.dims);
        expect(v.spacing).toEqual(d.sidecar.spacing);
        expect(v.type).toBe(d.sidecar.voxel_type);
        expect(sha256(v.data)).toBe(d.sha256);
      },
      60_000,
    );

    if (!d.original) continue; // only datasets converted from a real-format file have one
    const original = d.original.file;
    const originalPresent = present && fs.existsSync(path.join(folderOf(d), original));
    if (!originalPresent && !d.committedAt) skipped.push(`${d.name} (original ${original})`);
    it.skipIf(!originalPresent && !d.committedAt)(
      `${d.name} (${originalPresent ? 'fetched' : NOT_FETCHED}): the original ${original} equals the raw data`,
      async () => {
        const v = await loadVolume(fileOf(read(d, original), original), { limits: { maxBytes: 256 << 20 } });
        expect(v.dims).toEqual(d.sidecar.dims);
        for (let i = 0; i < 3; i++) expect(v.spacing[i]).toBeCloseTo(d.sidecar.spacing[i], 3);
        expect(v.type).toBe(d.sidecar.voxel_type);
        expect(sha256(v.data)).toBe(d.sha256);
      },
      60_000,
    );
  }

  afterAll(() => {
    if (skipped.length)
      console.warn(
        `fetched datasets: ${skipped.length} test(s) skipped, data not in data/fetched/ (run \`pnpm data:fetch\`): ${skipped.join(', ')}`,
      );
  });
});
