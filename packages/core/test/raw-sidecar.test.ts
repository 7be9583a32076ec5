import { describe, expect, it } from 'vitest';
import {
  RawReadError,
  isAxisCodes,
  parseRawSidecar,
  rawFileBeside,
  rawHeaderFromName,
  rawVoxels,
} from '../src/index.js';

// core's one raw + sidecar reader (scene/raw-sidecar.ts), which @vpt/loaders, the viewer's
// fallback loader and the headless page call.
function reason(fn: () => unknown): string {
  try {
    fn();
  } catch (e) {
    expect(e).toBeInstanceOf(RawReadError);
    expect((e as RawReadError).code).toBe('load-failed');
    return (e as RawReadError).reason;
  }
  throw new Error('no error');
}

describe('raw sidecar reader', () => {
  it('reads header fields, keeps an inverted value_range, and turns axes into axis codes', () => {
    const s = parseRawSidecar(
      JSON.stringify({
        dims: [2, 3, 4],
        voxel_type: 'int16',
        spacing: [1, 2, 0.5],
        endianness: 'big',
        value_range: [1000, -1000],
        axes: 'pir',
        title: 'T',
      }),
      'v.json',
    );
    expect(s).toMatchObject({
      dims: [2, 3, 4],
      type: 'int16',
      spacing: [1, 2, 0.5],
      endianness: 'big',
      valueRange: [1000, -1000],
      axisCodes: 'PIR',
    });
    expect(s.meta).toMatchObject({ title: 'T', value_range: [1000, -1000], axisCodes: 'PIR', space: 'RAS' });
    expect(parseRawSidecar('{"dims":[1,1,1],"voxel_type":"uint8"}', 'd.json')).toMatchObject({
      spacing: [1, 1, 1],
      endianness: 'little',
    });
  });

  it("names what is wrong, with the loaders' reasons", () => {
    expect(reason(() => parseRawSidecar('{ nope', 'a.json'))).toBe('bad-header');
    expect(reason(() => parseRawSidecar('{"dims":["2",2,2],"voxel_type":"uint8"}', 'a.json'))).toBe('bad-header');
    expect(reason(() => parseRawSidecar('{"dims":[2,0,2],"voxel_type":"uint8"}', 'a.json'))).toBe('empty');
    expect(reason(() => parseRawSidecar('{"dims":[65536,65536,2],"voxel_type":"uint8"}', 'a.json'))).toBe('overflow');
    expect(reason(() => parseRawSidecar('{"dims":[2,2,2],"voxel_type":"uint8","value_range":[3,3]}', 'a.json'))).toBe(
      'bad-header',
    );
    expect(reason(() => parseRawSidecar('{"dims":[2,2,2],"voxel_type":"uint8","axes":"RRS"}', 'a.json'))).toBe(
      'bad-header',
    );
    expect(reason(() => parseRawSidecar('{"dims":[2,2,2],"voxel_type":"uint8","layout":"z fastest"}', 'a.json'))).toBe(
      'unsupported',
    );
  });

  it('finds the raw file beside its sidecar, and dims and type in a file name', () => {
    expect(rawFileBeside('http://h/data/head.json?x=1', {})).toBe('http://h/data/head.raw');
    expect(rawFileBeside('http://h/data/head.json', { file: 'other.raw' })).toBe('http://h/data/other.raw');
    expect(rawFileBeside('http://h/data/head.json', { file: '../up.raw' })).toBe('http://h/data/head.raw');
    expect(rawHeaderFromName('ct_256x128x64_int16.raw')).toEqual({ dims: [256, 128, 64], type: 'int16' });
    expect(rawHeaderFromName('ct.raw')).toBeUndefined();
    expect(isAxisCodes('LPS')).toBe(true);
    expect(isAxisCodes('LLS')).toBe(false);
  });

  it('reads voxels of the exact size, swapping big-endian bytes', () => {
    const be = new Uint8Array([0x01, 0x02, 0xff, 0xfe]);
    expect(Array.from(rawVoxels(be.slice(), { dims: [2, 1, 1], type: 'int16', endianness: 'big' }, 'b.raw'))).toEqual([
      0x0102, -2,
    ]);
    expect(Array.from(rawVoxels(be.slice(), { dims: [2, 1, 1], type: 'uint16' }, 'l.raw'))).toEqual([0x0201, 0xfeff]);
    expect(reason(() => rawVoxels(new Uint8Array(3), { dims: [2, 1, 1], type: 'int16' }, 's.raw'))).toBe('truncated');
    expect(reason(() => rawVoxels(new Uint8Array(6), { dims: [2, 1, 1], type: 'int16' }, 'l.raw'))).toBe('bad-header');
    // A view at an odd offset is copied rather than refused.
    const odd = new Uint8Array(5).subarray(1);
    odd.set([1, 0, 2, 0]);
    expect(Array.from(rawVoxels(odd, { dims: [2, 1, 1], type: 'uint16' }, 'o.raw'))).toEqual([1, 2]);
  });
});
