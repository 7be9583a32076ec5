import { describe, expect, it } from 'vitest';
import { createVolume, inMemoryMultiscaleSource, type MultiscaleSource } from '@vpt/core';
import { StreamedChannels } from '../src/channels.js';

// A store's channels streamed as one source (channels.ts, StreamedChannels): a region holds
// every channel's values per voxel, the channel fastest; only the channels drawn since
// streaming began are read (the others are 0, which no brick keeps), each channel's source
// opened when first needed.
const D = 6;
/** Channel k of a C-channel store as its own source: voxel i holds 10k + i mod 7 (distinct per channel). */
function channelSource(k: number): MultiscaleSource {
  const data = new Uint16Array(D ** 3).map((_, i) => 10 * k + (i % 7));
  return inMemoryMultiscaleSource(createVolume([D, D, D], 'uint16', data, [1, 1, 1]), { coarsestSide: 2 });
}

function streamed(C: number) {
  const opened: number[] = [];
  const reads: number[] = [];
  const open = async (k: number): Promise<MultiscaleSource> => {
    opened.push(k);
    const s = channelSource(k);
    return { ...s, readRegion: (...a) => (reads.push(k), s.readRegion(...a)), readLevel: (l) => s.readLevel(l) };
  };
  const first = channelSource(0);
  const source = new StreamedChannels(
    { ...first, readRegion: (...a) => (reads.push(0), first.readRegion(...a)), readLevel: (l) => first.readLevel(l) },
    C,
    open,
  );
  return { source, opened, reads };
}

describe('StreamedChannels', () => {
  it("interleaves the drawn channels' regions, the others 0, opening a channel when first drawn", async () => {
    const { source, opened, reads } = streamed(3);
    expect([source.channels, source.type, source.levels.length]).toEqual([3, 'uint16', channelSource(0).levels.length]);
    source.draw([0, 2]);
    const min: [number, number, number] = [1, 2, 0],
      max: [number, number, number] = [4, 3, 2];
    const region = await source.readRegion(0, min, max);
    const one = (k: number) => channelSource(k).readRegion(0, min, max);
    const [r0, r2] = await Promise.all([one(0), one(2)]);
    expect(region).toBeInstanceOf(Uint16Array);
    expect(region.length).toBe(3 * r0.length);
    for (let i = 0; i < r0.length; i++)
      expect([region[3 * i], region[3 * i + 1], region[3 * i + 2]]).toEqual([r0[i], 0, r2[i]]);
    expect(opened).toEqual([2]);
    expect(reads.sort()).toEqual([0, 2]);
    // A channel drawn later is read from then on; one no longer drawn still is (an older brick cache may want it).
    source.draw([1]);
    const again = await source.readRegion(1, [0, 0, 0], [1, 1, 1]);
    const ones = await Promise.all([0, 1, 2].map((k) => channelSource(k).readRegion(1, [0, 0, 0], [1, 1, 1])));
    expect([...again]).toEqual(ones.map((r) => r[0]));
    expect(opened).toEqual([2, 1]);
    expect(source.read).toEqual([0, 1, 2]);
  });

  it('a channel whose source fails to open fails its reads, and is opened again by the next one', async () => {
    let fails = 1;
    const source = new StreamedChannels(channelSource(0), 2, async (k) => {
      if (fails-- > 0) throw new Error('offline');
      return channelSource(k);
    });
    source.draw([0, 1]);
    await expect(source.readRegion(0, [0, 0, 0], [1, 1, 1])).rejects.toThrow('offline');
    const region = await source.readRegion(0, [0, 0, 0], [1, 1, 1]);
    expect([...region]).toEqual([0, 10]);
  });

  it('readLevel gives every channel of a level, interleaved', async () => {
    const { source } = streamed(2);
    const level = await source.readLevel(1);
    const parts = await Promise.all([0, 1].map((k) => channelSource(k).readLevel(1)));
    expect(level.channels).toBe(2);
    expect(level.dims).toEqual(parts[0].dims);
    for (let i = 0; i < parts[0].data.length; i++)
      expect([level.data[2 * i], level.data[2 * i + 1]]).toEqual([parts[0].data[i], parts[1].data[i]]);
  });
});
