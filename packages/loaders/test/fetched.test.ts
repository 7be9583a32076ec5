/**
 * The larger real datasets, when `pnpm data:fetch` has put them in data/fetched/: each raw
 * file loads through its sidecar to the verified sha256, and each original NIfTI/NRRD file
 * loads to exactly the same voxels. Skipped where the data has not been fetched (CI).
 */
import fs from 'node:fs';
import path from 'node:path';
import { describe, expect, it } from 'vitest';
import { loadVolume } from '../src/index.js';
import { HERE, fileOf, sha256 } from './helpers.js';

const root = path.resolve(HERE, '../../..');
const fetched = path.join(root, 'data', 'fetched');
const catalog: { name: string; file: string; sha256: string; sidecar: { dims: number[]; spacing: number[]; voxel_type: string }; original?: { file: string } }[] =
  JSON.parse(fs.readFileSync(path.join(root, 'data', 'datasets.json'), 'utf8')).datasets;
const read = (f: string) => new Uint8Array(fs.readFileSync(path.join(fetched, f)));

describe('fetched datasets (data/fetched/)', () => {
  for (const d of catalog) {
    const present = fs.existsSync(path.join(fetched, d.file)) && fs.existsSync(path.join(fetched, d.file.replace(/\.raw$/, '.json')));
    it.skipIf(!present)(`${d.name}: raw + sidecar load to the recorded sha256`, async () => {
      const json = d.file.replace(/\.raw$/, '.json');
      const v = await loadVolume([fileOf(read(json), json), fileOf(read(d.file), d.file)], { limits: { maxBytes: 256 << 20 } });
      expect(v.dims).toEqual(d.sidecar.dims);
      expect(v.spacing).toEqual(d.sidecar.spacing);
      expect(v.type).toBe(d.sidecar.voxel_type);
      expect(sha256(v.data)).toBe(d.sha256);
    }, 60_000);
    const original = d.original && fs.existsSync(path.join(fetched, d.original.file)) ? d.original.file : undefined;
    it.skipIf(!original || !present)(`${d.name}: the original ${d.original?.file ?? ''} equals the raw data`, async () => {
      const v = await loadVolume(fileOf(read(original!), original!), { limits: { maxBytes: 256 << 20 } });
      expect(v.dims).toEqual(d.sidecar.dims);
      for (let i = 0; i < 3; i++) expect(v.spacing[i]).toBeCloseTo(d.sidecar.spacing[i], 3);
      expect(v.type).toBe(d.sidecar.voxel_type);
      expect(sha256(v.data)).toBe(d.sha256);
    }, 60_000);
  }
});
