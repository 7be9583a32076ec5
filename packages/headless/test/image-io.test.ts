import { describe, expect, it } from 'vitest';
import { decodePFM, decodePNG, encodePFM, encodePNG, opaque } from '../src/image-io.js';

function gradient(w: number, h: number): Float32Array {
  const a = new Float32Array(w * h * 4);
  for (let y = 0; y < h; y++)
    for (let x = 0; x < w; x++) {
      const i = (y * w + x) * 4;
      a.set([x + 0.25, y * 10 + 0.5, -(x * y) - 1e-3, 0.5], i);
    }
  return a;
}

describe('PFM', () => {
  it('round-trips RGB exactly (alpha becomes 1)', () => {
    const w = 5,
      h = 3;
    const src = gradient(w, h);
    src[0] = 1e30;
    src[1] = 1e-30;
    src[2] = 65504.125;
    const back = decodePFM(encodePFM(src, w, h));
    expect(back).toMatchObject({ width: w, height: h, channels: 3 });
    for (let i = 0; i < w * h; i++) {
      expect(Array.from(back.rgba.subarray(i * 4, i * 4 + 3))).toEqual(Array.from(src.subarray(i * 4, i * 4 + 3)));
      expect(back.rgba[i * 4 + 3]).toBe(1);
    }
  });

  it('writes the header "PF\\nW H\\n-1.0\\n" and little-endian rows bottom to top', () => {
    const w = 2,
      h = 2;
    // top row: red, green; bottom row: blue, white
    const src = new Float32Array([1, 0, 0, 1, 0, 1, 0, 1, 0, 0, 1, 1, 1, 1, 1, 1]);
    const file = encodePFM(src, w, h);
    const header = 'PF\n2 2\n-1.0\n';
    expect(file.subarray(0, header.length).toString('ascii')).toBe(header);
    expect(file.length).toBe(header.length + w * h * 12);
    const body = file.subarray(header.length);
    const px = (i: number) => [0, 1, 2].map((c) => body.readFloatLE(i * 12 + c * 4));
    expect(px(0)).toEqual([0, 0, 1]); // first stored pixel: bottom-left = blue
    expect(px(1)).toEqual([1, 1, 1]);
    expect(px(2)).toEqual([1, 0, 0]); // last stored row: the image's top row
    expect(px(3)).toEqual([0, 1, 0]);
  });

  it('reads big-endian (positive scale) and greyscale "Pf" files', () => {
    const header = Buffer.from('Pf\n1 2\n1.0\n', 'ascii');
    const body = Buffer.alloc(8);
    body.writeFloatBE(0.5, 0); // bottom
    body.writeFloatBE(2, 4); // top
    const img = decodePFM(Buffer.concat([header, body]));
    expect(img.channels).toBe(1);
    expect(Array.from(img.rgba)).toEqual([2, 2, 2, 1, 0.5, 0.5, 0.5, 1]);
  });

  it('rejects bad magic, bad sizes and truncated data', () => {
    expect(() => decodePFM(Buffer.from('P6\n1 1\n255\n'))).toThrow(/magic/);
    expect(() => decodePFM(Buffer.from('PF\n0 1\n-1.0\n'))).toThrow(/size/);
    expect(() => decodePFM(Buffer.from('PF\n2 2\n-1.0\n' + 'x'.repeat(10)))).toThrow(/needs 48/);
    expect(() => encodePFM(new Float32Array(3), 1, 1)).toThrow(/needs 4/);
  });
});

describe('PNG', () => {
  it('round-trips RGBA8, top row first', () => {
    const w = 3,
      h = 2;
    const src = new Uint8Array(w * h * 4).map((_, i) => (i * 37) & 255);
    const file = encodePNG(src, w, h);
    expect(file.subarray(1, 4).toString('ascii')).toBe('PNG');
    const back = decodePNG(file);
    expect([back.width, back.height]).toEqual([w, h]);
    expect(Array.from(back.rgba)).toEqual(Array.from(src));
  });

  it('accepts a view into a larger buffer', () => {
    const big = new Uint8Array(100).fill(7);
    const view = big.subarray(10, 14);
    expect(Array.from(decodePNG(encodePNG(view, 1, 1)).rgba)).toEqual([7, 7, 7, 7]);
  });

  it('opaque() sets alpha to 255 on a copy', () => {
    const src = new Uint8Array([1, 2, 3, 0, 4, 5, 6, 128]);
    expect(Array.from(opaque(src))).toEqual([1, 2, 3, 255, 4, 5, 6, 255]);
    expect(src[3]).toBe(0);
  });
});
