import { describe, expect, it } from 'vitest';
import { createVolume, isVptError, MAX_ENABLED_CHANNELS, validateChannels, type Volume } from '@vpt/core';
import { CHANNEL_COLORS, Channels, defaultChannels, recolor } from '../src/channels.js';
import type { LoadedVolumeLike } from '../src/loading/types.js';

// The Channels panel's defaults (channels.ts): distinct additive colours, every channel's
// transfer function fitted to that channel's own histogram, at most MAX_ENABLED_CHANNELS drawn.

/** A C-channel uint8 volume whose channel k holds the values lo[k]..hi[k] spread evenly over its voxels. */
function spread(lo: number[], hi: number[]): Volume {
  const C = lo.length,
    n = 8 ** 3;
  const data = new Uint8Array(n * C);
  for (let i = 0; i < n; i++)
    for (let k = 0; k < C; k++) data[k + C * i] = Math.round(lo[k] + ((hi[k] - lo[k]) * i) / (n - 1));
  return createVolume([8, 8, 8], 'uint8', data, [1, 1, 1], C);
}

const values = (tf: { dimensions: string; points?: { value: number }[] }) => tf.points!.map((p) => p.value);

describe('viewer channels: defaults', () => {
  it('gives every channel a distinct colour in [0, 1] (green, magenta first, as microscopy viewers do)', () => {
    const v = spread([1, 1, 1, 1, 1, 1], [255, 255, 255, 255, 255, 255]);
    const chans = defaultChannels(v);
    const keys = chans.map((c) => c.color.join());
    expect(new Set(keys).size).toBe(6);
    expect(chans[0].color).toEqual([0, 1, 0]);
    expect(chans[1].color).toEqual([1, 0, 1]);
    for (const c of chans) for (const x of c.color) expect(x >= 0 && x <= 1).toBe(true);
    // Two of them add to white: the channels are told apart where they overlap.
    expect(chans[0].color.map((x, i) => x + chans[1].color[i])).toEqual([1, 1, 1]);
    // At most MAX_ENABLED_CHANNELS drawn, and the defaults are a scene core accepts.
    expect(chans.filter((c) => c.enabled).length).toBe(MAX_ENABLED_CHANNELS);
    expect(() => validateChannels(chans, v, 20)).not.toThrow();
    expect(CHANNEL_COLORS.length).toBeGreaterThanOrEqual(MAX_ENABLED_CHANNELS);
    // A file's own display colours (OME-Zarr omero, sRGB hex) win where they are valid.
    const given = defaultChannels(spread([1, 1], [255, 255]), undefined, ['FF0000', 'red']);
    expect(given.map((c) => c.color)).toEqual([
      [1, 0, 0],
      [1, 0, 1],
    ]);
  });

  it("fits each channel's transfer function to that channel's own values, in its colour", () => {
    // Channel 0 holds 1..100, channel 1 150..250 (of 255): each ramp lies within its own values.
    const v = spread([1, 150], [100, 250]);
    const [a, b] = defaultChannels(v);
    for (const x of values(a.transferFunction!)) expect(x).toBeLessThanOrEqual(101 / 255);
    for (const x of values(b.transferFunction!)) expect(x).toBeGreaterThanOrEqual(150 / 255);
    expect(Math.min(...values(b.transferFunction!))).toBeGreaterThan(Math.max(...values(a.transferFunction!)));
    // Points in the channel's colour (the kernels replace them with it anyway): the editor shows that colour.
    const colours = (tf: typeof a.transferFunction) =>
      new Set((tf as { points: { color: number[] }[] }).points.map((p) => p.color.join()));
    expect([...colours(a.transferFunction)]).toEqual([a.color.join()]);
    expect([...colours(b.transferFunction)]).toEqual([b.color.join()]);
    // A channel's given range (an OME-Zarr omero window) is the one the function is fitted in.
    const [, inRange] = defaultChannels(v, [null, [150, 250]]);
    expect(inRange.range).toEqual([150, 250]);
    expect(Math.max(...values(inRange.transferFunction!))).toBeGreaterThan(0.5);
    expect(Math.min(...values(inRange.transferFunction!))).toBeLessThan(Math.min(...values(b.transferFunction!)));
  });

  it('resolves the page’s entries over the defaults and refuses what cannot be drawn with a typed error', () => {
    const v = Object.assign(spread([1, 150, 20], [100, 250, 60]), { format: 'test' }) as LoadedVolumeLike;
    const ch = new Channels(v);
    const got = ch.resolve([{ enabled: false }, undefined as never, { color: [1, 0, 0] }]);
    expect(got.map((c) => c.enabled)).toEqual([false, true, true]);
    expect(got[0].transferFunction).toEqual(ch.defaults[0].transferFunction);
    expect(got[2].color).toEqual([1, 0, 0]);
    expect(ch.resolve(null)).toEqual(ch.defaults);
    const refused = (user: unknown) => {
      try {
        ch.check(user, 20);
        return null;
      } catch (e) {
        expect(isVptError(e, 'invalid-scene')).toBe(true);
        return (e as Error).message;
      }
    };
    expect(refused([{ enabled: false }])).toBeNull();
    expect(refused(null)).toBeNull();
    expect(refused([{}, {}, {}, {}])).toMatch(/at most 3/);
    expect(refused('green')).toMatch(/array/);
    expect(refused([{ color: [2, 0, 0] }])).toMatch(/color/);
    expect(refused([{ enabled: false }, { enabled: false }, { enabled: false }])).toMatch(/no channel is enabled/);
    expect(refused([{ colour: [1, 0, 0] }])).toMatch(/unknown field "colour"/);
    expect(refused([{ transferFunction: { dimensions: '2d', widgets: [] } }])).not.toBeNull();
  });

  it('recolor puts one colour on every point and keeps values and opacities', () => {
    const tf = defaultChannels(spread([1, 1], [200, 90]))[0].transferFunction!;
    const red = recolor(tf, [1, 0, 0]) as { points: { value: number; opacity: number; color: number[] }[] };
    expect(red.points.map((p) => p.color)).toEqual(red.points.map(() => [1, 0, 0]));
    expect(red.points.map((p) => [p.value, p.opacity])).toEqual(
      (tf as typeof red).points.map((p) => [p.value, p.opacity]),
    );
  });
});
