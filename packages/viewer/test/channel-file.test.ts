import fs from 'node:fs';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import { describe, expect, it } from 'vitest';
import { loadVolumeSource } from '../src/loading/volume-source.js';

// A file with a channel axis: the element's volume is channel 0 as a scalar volume (what the
// Transfer function panel's histogram, the slice panes and the probe read), carrying the whole
// volume and its channels' defaults as `multichannel` (channels.ts), which the 3D scene draws.
const DIR = path.join(path.dirname(fileURLToPath(import.meta.url)), '../../loaders/test/fixtures/multiaxis');
const expected = JSON.parse(fs.readFileSync(path.join(DIR, 'expected.json'), 'utf8')).files;

describe('viewer: a file with a channel axis', () => {
  it('loads channel 0 as a scalar volume (the reference reader’s channel 0) carrying every channel', async () => {
    for (const name of ['rgba-last.nrrd', 'vector5d.nii.gz']) {
      const want = expected[name];
      const file = new File([fs.readFileSync(path.join(DIR, name))], name);
      const v = await loadVolumeSource(file, { worker: false } as never);
      expect(v.channels, name).toBeUndefined();
      expect(v.dims).toEqual(want.dims);
      const channel0 = (want.steps[0] as number[]).filter((_, i) => i % want.channels === 0);
      expect(Array.from(v.data), name).toEqual(Array.from(Float32Array.from(channel0)));
      const mc = v.multichannel!;
      expect(mc.volume.channels, name).toBe(want.channels);
      expect(Array.from(mc.volume.data), name).toEqual(Array.from(Float32Array.from(want.steps[0] as number[])));
      const chans = mc.resolve(null);
      expect(chans.length).toBe(want.channels);
      expect(new Set(chans.map((c) => c.color.join())).size, name).toBe(want.channels);
      const range = v.meta?.dataRange as number[];
      expect(range).toEqual([Math.min(...channel0), Math.max(...channel0)].map((x) => Math.fround(x)));
    }
  });
});
