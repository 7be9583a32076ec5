import { describe, expect, it } from 'vitest';
import { createVolume, normalizedData, validateVolume, VptError, type Volume } from '../src/index.js';
import { floatToHalf, halfToFloat } from '../src/gpu/half-float.js';
import {
  planVolumeUpload,
  volumeTextureData,
  volumeTextureSlab,
  volumeValueMapping,
} from '../src/gpu/volume-format.js';
import { downsampleVolume, fitFactors } from '../src/scene/downsample.js';

const NO_EXT = { norm16: false, float32Filterable: false };
const ALL_EXT = { norm16: true, float32Filterable: true };

/** What the shader computes for one texel (before the clamp): texel · valueScale + valueOffset. */
function decodeNormalized(
  volume: Volume,
  caps = NO_EXT,
  sampling: 'fast' | 'exact' = 'fast',
  allowHalfFloat = false,
): Float64Array {
  const upload = planVolumeUpload(volume, caps, { sampling, allowHalfFloat });
  const data = volumeTextureData(volume, upload);
  const { valueScale, valueOffset } = volumeValueMapping(volume, upload);
  const texel = (i: number): number => {
    switch (upload.format) {
      case 'r8unorm':
        return data[i] / 255;
      case 'r16unorm':
        return data[i] / 65535;
      case 'r16snorm':
        return Math.max(data[i] / 32767, -1);
      case 'r16float':
        return halfToFloat(data[i]);
      default:
        return data[i];
    }
  };
  return Float64Array.from({ length: data.length }, (_, i) =>
    Math.min(1, Math.max(0, texel(i) * valueScale + valueOffset)),
  );
}

describe('half floats', () => {
  it('round-trips every half bit pattern except NaN, and rounds to nearest even', () => {
    const wrong: number[] = [];
    for (let h = 0; h < 0x10000; h++) {
      const x = halfToFloat(h);
      if (!Number.isNaN(x) && floatToHalf(x) !== h) wrong.push(h);
    }
    expect(wrong).toEqual([]);
    expect(floatToHalf(2049)).toBe(floatToHalf(2048)); // tie → even mantissa
    expect(floatToHalf(2051)).toBe(floatToHalf(2052));
    expect(halfToFloat(floatToHalf(65519))).toBe(65504);
    expect(halfToFloat(floatToHalf(65520))).toBe(Infinity);
  });

  it('holds every 16-bit integer within the stated bound: ≤ 8 units, ≤ 1/2049 relative, exact up to 2048', () => {
    let worstAbs = 0,
      worstRel = 0;
    for (let x = -32768; x <= 32767; x++) {
      const err = Math.abs(halfToFloat(floatToHalf(x)) - x);
      if (Math.abs(x) <= 2048) expect(err).toBe(0);
      worstAbs = Math.max(worstAbs, err);
      if (x !== 0) worstRel = Math.max(worstRel, err / Math.abs(x));
    }
    expect(worstAbs).toBe(8);
    expect(worstRel).toBeCloseTo(1 / 2049, 12);
    expect(worstAbs / 65535).toBeLessThan(1.3e-4);
  });
});

describe('volume upload formats', () => {
  it('picks the compact format per type and device, r32float for exact sampling', () => {
    const v8 = createVolume([2, 2, 2], 'uint8');
    const v16 = createVolume([2, 2, 2], 'uint16');
    const s16 = createVolume([2, 2, 2], 'int16');
    const f32 = createVolume([2, 2, 2], 'float32');
    const fmt = (v: Volume, caps = NO_EXT, sampling: 'fast' | 'exact' = 'fast', half = false) => {
      const u = planVolumeUpload(v, caps, { sampling, allowHalfFloat: half });
      return `${u.format}/${u.filter}/${u.bytesPerVoxel}`;
    };
    expect(fmt(v8)).toBe('r8unorm/linear/1');
    expect(fmt(v16)).toBe('r16float/linear/2');
    expect(fmt(v16, ALL_EXT)).toBe('r16unorm/linear/2');
    expect(fmt(s16)).toBe('r16float/linear/2');
    expect(fmt(s16, ALL_EXT)).toBe('r16snorm/linear/2');
    expect(fmt(f32)).toBe('r32float/nearest/4'); // not filterable without the extension: manual trilinear
    expect(fmt(f32, ALL_EXT)).toBe('r32float/linear/4');
    expect(fmt(f32, NO_EXT, 'fast', true)).toBe('r16float/linear/2');
    for (const v of [v8, v16, s16, f32]) expect(fmt(v, ALL_EXT, 'exact')).toBe('r32float/nearest/4');
  });

  it('uploads uint8 and norm16 data without a copy', () => {
    const v8 = createVolume([2, 2, 2], 'uint8');
    // A view of the volume's own buffer, not a copy.
    const a = volumeTextureData(v8, planVolumeUpload(v8, NO_EXT, { sampling: 'fast' }));
    expect([a.buffer, a.byteOffset, a.length]).toEqual([v8.data.buffer, 0, 8]);
    const s16 = createVolume([2, 2, 2], 'int16');
    const b = volumeTextureData(s16, planVolumeUpload(s16, ALL_EXT, { sampling: 'fast' }));
    expect([b.buffer, b.byteOffset, b.length]).toEqual([s16.data.buffer, 0, 8]);
  });

  it('decodes every format to the CPU normalization, inverted ranges included', () => {
    const n = 4096;
    const cases: Volume[] = [];
    const u8 = createVolume(
      [16, 16, 16],
      'uint8',
      Uint8Array.from({ length: n }, (_, i) => (i * 37) % 256),
    );
    cases.push(u8, { ...u8, valueRange: [200, 20] });
    const u16 = createVolume(
      [16, 16, 16],
      'uint16',
      Uint16Array.from({ length: n }, (_, i) => (i * 997) % 65536),
    );
    cases.push(u16, { ...u16, valueRange: [60000, 1000] });
    const i16 = createVolume(
      [16, 16, 16],
      'int16',
      Int16Array.from({ length: n }, (_, i) => ((i * 811) % 65536) - 32768),
    );
    cases.push(i16, { ...i16, valueRange: [3071, -1024] });
    const f32 = createVolume(
      [16, 16, 16],
      'float32',
      Float32Array.from({ length: n }, (_, i) => Math.sin(i) * 1e3),
    );
    f32.data[5] = NaN;
    f32.data[6] = Infinity;
    cases.push(f32, { ...f32, valueRange: [800, -800] });
    for (const v of cases) {
      validateVolume(v);
      const want = normalizedData(v);
      for (const caps of [NO_EXT, ALL_EXT]) {
        for (const sampling of ['fast', 'exact'] as const) {
          const got = decodeNormalized(v, caps, sampling, true);
          const u = planVolumeUpload(v, caps, { sampling, allowHalfFloat: true });
          const [lo, hi] =
            v.valueRange ?? (v.type === 'uint8' ? [0, 255] : v.type === 'uint16' ? [0, 65535] : [-32768, 32767]);
          const width = v.type === 'float32' && !v.valueRange ? 2000 : Math.abs(hi - lo);
          // The stated bounds (gpu/volume-format.ts), in normalized units: float32 rounding for exact formats;
          // r16float ≤ 16 data units for uint16 (values ≥ 32768 unshifted), ≤ 8 for int16, half of 2^-11 of the
          // data's extent (≈ 2000) for float32; snorm one unit at −32768.
          const tol =
            u.format === 'r16float'
              ? v.type === 'float32'
                ? (2000 * 2 ** -12) / width
                : (v.type === 'uint16' ? 16 : 8) / width
              : u.format === 'r16snorm'
                ? 1 / width
                : 0;
          let worst = 0;
          for (let i = 0; i < n; i++) worst = Math.max(worst, Math.abs(got[i] - want[i]));
          expect(worst, `${v.type} ${JSON.stringify(v.valueRange)} ${u.format}`).toBeLessThanOrEqual(tol + 1e-6);
        }
      }
    }
  });

  it('converts slab by slab to exactly the whole-volume data', () => {
    const i16 = createVolume(
      [8, 4, 10],
      'int16',
      Int16Array.from({ length: 320 }, (_, i) => i * 97 - 15000),
    );
    const f32 = createVolume(
      [8, 4, 10],
      'float32',
      Float32Array.from({ length: 320 }, (_, i) => (i % 7 === 0 ? NaN : i * 0.37)),
    );
    for (const v of [i16, f32]) {
      for (const sampling of ['fast', 'exact'] as const) {
        const u = planVolumeUpload(v, NO_EXT, { sampling, allowHalfFloat: true });
        const whole = Array.from(volumeTextureData(v, u));
        const scratch = new ArrayBuffer(4 * 8 * 4 * 6);
        const slabs = [
          [0, 3],
          [3, 4],
          [4, 10],
        ].flatMap(([z0, z1]) => Array.from(volumeTextureSlab(v, u, z0, z1, scratch)));
        expect(slabs, `${v.type} ${sampling}`).toEqual(whole);
      }
    }
  });

  it('refuses an empty value range and accepts an inverted one', () => {
    const v = createVolume([2, 2, 2], 'int16');
    expect(() => validateVolume({ ...v, valueRange: [5, 5] })).toThrow(VptError);
    expect(() => validateVolume({ ...v, valueRange: [5, NaN] })).toThrow(/two different finite numbers/);
    expect(() => validateVolume({ ...v, valueRange: [100, -100] })).not.toThrow();
    const m = volumeValueMapping({ ...v, valueRange: [100, -100] }, { decodeScale: 1, decodeOffset: 0 });
    expect(100 * m.valueScale + m.valueOffset).toBeCloseTo(0, 12);
    expect(-100 * m.valueScale + m.valueOffset).toBeCloseTo(1, 12);
  });
});

describe('hardware filtering keeps the majorant bound', () => {
  it('a trilinear blend with quantized weights (8-bit fractions, as GPUs filter) stays within its 8 texels', () => {
    // A filtered value is Σ w_i c_i with w_i ≥ 0 and Σ w_i = 1 whatever the weights' precision,
    // so it lies in [min c_i, max c_i]: the per-cell texel range bounds it (majorant-grid.ts).
    let state = 12345;
    const rnd = () => (state = (state * 1103515245 + 12345) >>> 0) / 2 ** 32;
    for (let k = 0; k < 20000; k++) {
      const c = Array.from({ length: 8 }, () => Math.fround(rnd() * 2 - 0.5));
      const q = (t: number) => Math.round(t * 256) / 256;
      const [fx, fy, fz] = [q(rnd()), q(rnd()), q(rnd())];
      const l = (a: number, b: number, t: number) => Math.fround(a * (1 - t) + b * t);
      const v = l(l(l(c[0], c[1], fx), l(c[2], c[3], fx), fy), l(l(c[4], c[5], fx), l(c[6], c[7], fx), fy), fz);
      expect(v).toBeGreaterThanOrEqual(Math.min(...c) - 1e-6);
      expect(v).toBeLessThanOrEqual(Math.max(...c) + 1e-6);
    }
  });
});

describe('fitting a volume to the device', () => {
  it('downsamples by box averages, keeping the box and the value range', () => {
    const v = createVolume(
      [4, 2, 3],
      'int16',
      Int16Array.from({ length: 24 }, (_, i) => i * 10),
      [1, 2, 3],
    );
    v.valueRange = [300, 0];
    const d = downsampleVolume(v, [2, 2, 2]);
    expect(d.dims).toEqual([2, 1, 2]);
    expect(d.spacing).toEqual([2, 4, 6]);
    expect(d.valueRange).toEqual([300, 0]);
    // Block (0,0,0): x 0..1, y 0..1, z 0..1 → values i = x + 4y + 8z.
    const mean = (ids: number[]) => Math.round(ids.reduce((a, i) => a + i * 10, 0) / ids.length);
    expect(d.data[0]).toBe(mean([0, 1, 4, 5, 8, 9, 12, 13]));
    expect(d.data[3]).toBe(mean([18, 19, 22, 23])); // the partial block at the far z edge
  });

  it('finds the largest volume under the budget and the 3D texture limit', () => {
    expect(fitFactors([512, 512, 1024], 2, 2 ** 30, 2048)).toEqual([1, 1, 1]);
    expect(fitFactors([512, 512, 1024], 2, 2 ** 28, 2048)).toEqual([1, 1, 2]);
    expect(fitFactors([4000, 100, 100], 1, 2 ** 40, 2048)).toEqual([2, 1, 1]);
    const f = fitFactors([300, 200, 100], 4, 1e6, 2048)!;
    const out = [300, 200, 100].map((n, i) => Math.ceil(n / f[i]));
    expect(out[0] * out[1] * out[2] * 4).toBeLessThanOrEqual(1e6);
    expect(fitFactors([8, 8, 8], 4, 2, 2048)).toBeNull();
  });
});
