import fs from 'node:fs';
import { describe, expect, it } from 'vitest';
import { loadVolume } from '../src/index.js';

const HEAD = new URL('../../../data/mri_head_volpack_brainsmall_128x128x84_uint8.json', import.meta.url);

describe('sidecar axes', () => {
  it('the bundled head\'s "axes" (PIR) become its orientation: superior is −y of the volume, anterior −x', async () => {
    const sidecar = new File([fs.readFileSync(HEAD)], 'head.json');
    const raw = new File(
      [fs.readFileSync(new URL('mri_head_volpack_brainsmall_128x128x84_uint8.raw', HEAD))],
      'mri_head_volpack_brainsmall_128x128x84_uint8.raw',
    );
    const v = await loadVolume([sidecar, raw], { worker: false });
    expect(v.meta?.axisCodes).toBe('PIR');
    expect(v.meta?.space).toBe('RAS');
    // Columns are the world (RAS) directions of the index axes: x → P, y → I, z → R.
    expect(v.orientation).toEqual([0, 0, 1, -1, 0, 0, 0, -1, 0]);
  });

  it('rejects axes that do not name three different directions', async () => {
    const bad = JSON.stringify({ dims: [2, 2, 2], voxel_type: 'uint8', axes: 'RRA' });
    await expect(
      loadVolume([new File([bad], 'v.json'), new File([new Uint8Array(8)], 'v.raw')], { worker: false }),
    ).rejects.toMatchObject({ reason: 'bad-header' });
  });
});
