import { describe, expect, it } from 'vitest';
import {
  buildMajorantGrid,
  channelMajorantGrid,
  channelTextureData,
  channelVolume,
  createVolume,
  enabledChannels,
  interleaveChannels,
  planChannelUpload,
  rasterizeChannelTransferFunctions,
  rasterizeTransferFunction,
  scalarSceneOf,
  TF_RESOLUTION,
  validateScene,
  volumeCellRanges,
  VptError,
  type BackendCapabilities,
  type ChannelSettings,
  type Scene,
} from '../src/index.js';
import { tf1d } from '../../../tests/helpers/test-scene.js';

const N = 8;
const ramp = (k: number) => Uint8Array.from({ length: N * N * N }, (_, i) => (i * (k + 3)) % 256);
const scene = (channels: number, settings?: ChannelSettings[]): Scene => {
  const parts = Array.from({ length: channels }, (_, k) => createVolume([N, N, N], 'uint8', ramp(k)));
  return {
    volume: interleaveChannels(parts),
    transferFunction: tf1d([0, [1, 1, 1], 0], [1, [1, 1, 1], 1]),
    camera: { position: [0, 0, 2], target: [0, 0, 0], up: [0, 1, 0], fovy: 0.6 },
    lights: [],
    environment: { type: 'constant', radiance: [1, 1, 1] },
    densityScale: 4,
    seed: 1,
    ...(settings ? { channels: settings } : {}),
  };
};
const tfs = [
  tf1d([0, [1, 0, 0], 0], [1, [1, 0.5, 0], 0.8]),
  tf1d([0.2, [0, 1, 0], 0], [1, [0, 1, 0.4], 1]),
  tf1d([0, [0, 0, 1], 0.1], [0.5, [0.3, 0.3, 1], 0.9], [1, [1, 1, 1], 0.2]),
  tf1d([0, [1, 1, 0], 0], [1, [1, 1, 0], 0.5]),
  tf1d([0, [1, 0, 1], 0], [1, [1, 0, 1], 0.5]),
];
const caps = (norm16: boolean): BackendCapabilities => ({ norm16, float32Filterable: false });

describe('the multichannel volume model', () => {
  it('interleaves channels of one grid channel-fastest and takes them apart again', () => {
    const v = interleaveChannels([
      createVolume([N, N, N], 'uint8', ramp(0)),
      createVolume([N, N, N], 'uint8', ramp(1)),
    ]);
    expect(v.channels).toBe(2);
    expect(v.data.length).toBe(2 * N ** 3);
    expect(v.data[2 * 5 + 1]).toBe(ramp(1)[5]);
    expect(Array.from(channelVolume(v, 1).data)).toEqual(Array.from(ramp(1)));
  });
  it('refuses mismatched grids, types and data lengths with typed errors naming the mismatch', () => {
    const a = createVolume([N, N, N], 'uint8', ramp(0));
    expect(() => interleaveChannels([a, createVolume([N, N, 4], 'uint8')])).toThrow(/channels share one grid/);
    expect(() => interleaveChannels([a, createVolume([N, N, N], 'uint16')])).toThrow(/is uint16, channel 0 is uint8/);
    expect(() => createVolume([N, N, N], 'uint8', new Uint8Array(N ** 3), [1, 1, 1], 2)).toThrow(
      /× 2 channels need 1024 values/,
    );
    expect(() => createVolume([N, N, N], 'uint8', undefined, [1, 1, 1], 17)).toThrow(/MAX_VOLUME_CHANNELS/);
  });
  it('validates the scene channels: one per channel, at most 4 drawn, 1D TFs, colours in [0, 1]', () => {
    const err = (s: Scene) => {
      try {
        validateScene(s);
      } catch (e) {
        expect(e).toBeInstanceOf(VptError);
        return (e as Error).message;
      }
      return '';
    };
    expect(err(scene(2))).toMatch(/needs "channels"/);
    expect(err(scene(2, [{ transferFunction: tfs[0] }]))).toMatch(/1 entries for a volume of 2 channels/);
    expect(
      err(
        scene(
          5,
          tfs.map((transferFunction) => ({ transferFunction })),
        ),
      ),
    ).toMatch(/MAX_ENABLED_CHANNELS/);
    expect(
      err(
        scene(2, [
          { transferFunction: tfs[0], enabled: false },
          { transferFunction: tfs[1], enabled: false },
        ]),
      ),
    ).toMatch(/no channel is enabled/);
    expect(err(scene(2, [{ transferFunction: tfs[0] }, { transferFunction: tfs[1], color: [0, 2, 0] }]))).toMatch(
      /channels\[1\]\.color\[1\]/,
    );
    expect(err(scene(2, [{ transferFunction: tfs[0] }, { transferFunction: tfs[1], range: [3, 3] }]))).toMatch(
      /channels\[1\]\.range/,
    );
    // Five listed, four drawn: fine.
    expect(
      err(
        scene(
          5,
          tfs.map((transferFunction, k) => ({ transferFunction, enabled: k !== 2 })),
        ),
      ),
    ).toBe('');
    expect(enabledChannels(tfs.map((transferFunction, k) => ({ transferFunction, enabled: k !== 2 })))).toEqual([
      0, 1, 3, 4,
    ]);
  });
});

describe('GPU storage of the drawn channels', () => {
  it('one texture of the source type: rg8 / rgba8 unorm, 16-bit norm or half, rg32 / rgba32 float', () => {
    const v2 = scene(2).volume,
      v3 = scene(3).volume;
    const fast = { sampling: 'fast' as const };
    expect(planChannelUpload(v2, caps(true), fast, [0, 1])).toMatchObject({ format: 'rg8unorm', bytesPerVoxel: 2 });
    expect(planChannelUpload(v3, caps(true), fast, [0, 1, 2])).toMatchObject({
      format: 'rgba8unorm',
      bytesPerVoxel: 4,
    });
    expect(planChannelUpload(v2, caps(true), { sampling: 'exact' }, [0, 1]).format).toBe('rg32float');
    // One drawn channel is planned as the scalar volume holding it.
    expect(planChannelUpload(v2, caps(true), fast, [1]).format).toBe('r8unorm');
    const u16 = interleaveChannels([
      createVolume([2, 2, 2], 'uint16', Uint16Array.from([1, 2, 3, 4, 5, 6, 7, 65535])),
      createVolume([2, 2, 2], 'uint16', Uint16Array.from([8, 7, 6, 5, 4, 3, 2, 1])),
    ]);
    expect(planChannelUpload(u16, caps(true), fast, [0, 1]).format).toBe('rg16unorm');
    // Without 16-bit norm formats: half floats holding the integers, shifted when any drawn one reaches 65520.
    expect(planChannelUpload(u16, caps(false), fast, [0, 1])).toMatchObject({
      format: 'rg16float',
      decodeOffset: 32768,
    });
    expect(planChannelUpload(u16, caps(false), fast, [1, 0])).toMatchObject({ decodeOffset: 32768 });
    expect(planChannelUpload(u16, caps(false), fast, [1])).toMatchObject({ format: 'r16float', decodeOffset: 0 });
  });
  it('uploads the interleaved array as is when it is the texture, else gathers the drawn channels (3 → RGBA, last 0)', () => {
    const v2 = scene(2).volume,
      v3 = scene(3).volume;
    const up2 = planChannelUpload(v2, caps(true), { sampling: 'fast' }, [0, 1]);
    expect(channelTextureData(v2, up2, [0, 1])).toBe(v2.data);
    const swapped = channelTextureData(v2, up2, [1, 0]);
    expect([swapped[0], swapped[1], swapped[2], swapped[3]]).toEqual([v2.data[1], v2.data[0], v2.data[3], v2.data[2]]);
    const up3 = planChannelUpload(v3, caps(true), { sampling: 'fast' }, [0, 1, 2]);
    const d3 = channelTextureData(v3, up3, [0, 1, 2]);
    expect(d3.length).toBe(4 * N ** 3);
    expect([d3[4], d3[5], d3[6], d3[7]]).toEqual([v3.data[3], v3.data[4], v3.data[5], 0]);
    const exact = planChannelUpload(v3, caps(true), { sampling: 'exact' }, [2, 0]);
    const f = channelTextureData(v3, exact, [2, 0]);
    expect(f).toBeInstanceOf(Float32Array);
    expect([f[0], f[1], f[2], f[3]]).toEqual([v3.data[2], v3.data[0], v3.data[5], v3.data[3]]);
  });
  it('rasterizes one TF row per drawn channel, a colour replacing the TF colours', () => {
    const settings: ChannelSettings[] = [
      { transferFunction: tfs[0] },
      { transferFunction: tfs[1], enabled: false },
      { transferFunction: tfs[2], color: [0.1, 0.2, 0.3] },
    ];
    const rows = rasterizeChannelTransferFunctions(settings);
    expect(rows.length).toBe(2 * 4 * TF_RESOLUTION);
    const row1 = rows.subarray(4 * TF_RESOLUTION);
    const own = rasterizeTransferFunction(tfs[2]);
    for (let i = 0; i < TF_RESOLUTION; i += 37) {
      expect(Array.from(row1.subarray(4 * i, 4 * i + 3))).toEqual(Array.from(Float32Array.from([0.1, 0.2, 0.3])));
      expect(row1[4 * i + 3]).toBe(own[4 * i + 3]);
    }
  });
});

describe('the majorant grid of a channel scene bounds the sum of the channels', () => {
  it('equals the sum of the per-channel grids, and one drawn channel is the scalar scene', () => {
    const settings: ChannelSettings[] = [
      { transferFunction: tfs[0] },
      { transferFunction: tfs[1] },
      { transferFunction: tfs[2] },
    ];
    const s = scene(3, settings);
    const grid = channelMajorantGrid(s.volume, settings, s.densityScale, 4);
    const per = [0, 1, 2].map((k) =>
      buildMajorantGrid(
        volumeCellRanges(channelVolume(s.volume, k, [0, 255]), 4),
        rasterizeTransferFunction(tfs[k]),
        s.densityScale,
      ),
    );
    for (let c = 0; c < grid.data.length; c += 4) {
      const sum = per.reduce((a, g) => a + g.data[c], 0);
      expect(Math.abs(grid.data[c] - sum)).toBeLessThanOrEqual(1e-6 * sum);
      expect(grid.data[c]).toBeGreaterThanOrEqual(Math.max(...per.map((g) => g.data[c])));
    }
    const one = scalarSceneOf(
      scene(2, [
        { transferFunction: tfs[0], enabled: false },
        { transferFunction: tfs[1], color: [0, 0, 1] },
      ]),
    )!;
    expect(one.channels).toBeUndefined();
    expect(Array.from(one.volume.data)).toEqual(Array.from(ramp(1)));
    expect(one.transferFunction.dimensions === '1d' && one.transferFunction.points.every((p) => p.color[2] === 1)).toBe(
      true,
    );
  });
});
