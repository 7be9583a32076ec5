import { PNG } from 'pngjs';

/** RGBA8, top row first → PNG file bytes. */
export function encodePNG(rgba8: Uint8Array, width: number, height: number): Buffer {
  checkSize(rgba8.length, width, height, 'encodePNG');
  const png = new PNG({ width, height });
  png.data = Buffer.from(rgba8.buffer, rgba8.byteOffset, rgba8.byteLength);
  return PNG.sync.write(png);
}

/**
 * A copy with alpha set to 255. The renderers' RGB already holds the background seen
 * through the volume (alpha is only coverage), so a PNG keeping that alpha would be
 * composited a second time by whatever displays it.
 */
export function opaque(rgba8: Uint8Array): Uint8Array {
  const out = rgba8.slice();
  for (let i = 3; i < out.length; i += 4) out[i] = 255;
  return out;
}

/** PNG file bytes → RGBA8, top row first. */
export function decodePNG(file: Uint8Array): { width: number; height: number; rgba: Uint8Array } {
  const png = PNG.sync.read(Buffer.from(file.buffer, file.byteOffset, file.byteLength));
  return {
    width: png.width,
    height: png.height,
    rgba: new Uint8Array(png.data.buffer, png.data.byteOffset, png.data.byteLength),
  };
}

/**
 * RGBA float, top row first → PFM ("PF", three channels). The alpha channel is dropped
 * (PFM has none). Little-endian, so the scale is written negative (-1.0), and rows are
 * stored bottom to top, as the format specifies.
 */
export function encodePFM(rgba: Float32Array, width: number, height: number): Buffer {
  checkSize(rgba.length, width, height, 'encodePFM');
  const header = Buffer.from(`PF\n${width} ${height}\n-1.0\n`, 'ascii');
  const body = Buffer.alloc(width * height * 12);
  for (let row = 0; row < height; row++) {
    const srcRow = height - 1 - row; // file row 0 is the image's bottom row
    for (let x = 0; x < width; x++) {
      const s = (srcRow * width + x) * 4;
      const o = (row * width + x) * 12;
      body.writeFloatLE(rgba[s], o);
      body.writeFloatLE(rgba[s + 1], o + 4);
      body.writeFloatLE(rgba[s + 2], o + 8);
    }
  }
  return Buffer.concat([header, body]);
}

export interface DecodedPFM {
  width: number;
  height: number;
  /** 3 for "PF" (colour), 1 for "Pf" (greyscale). */
  channels: 1 | 3;
  /** RGBA float, top row first; alpha = 1, grey replicated into RGB. */
  rgba: Float32Array;
}

/** PFM file bytes ("PF" or "Pf", either byte order) → RGBA float, top row first. */
export function decodePFM(file: Uint8Array): DecodedPFM {
  const buf = Buffer.from(file.buffer, file.byteOffset, file.byteLength);
  // Header: three whitespace-separated tokens, then one whitespace character, then data.
  let pos = 0;
  const token = (): string => {
    while (pos < buf.length && isSpace(buf[pos])) pos++;
    const start = pos;
    while (pos < buf.length && !isSpace(buf[pos])) pos++;
    if (start === pos) throw new Error('PFM: truncated header');
    return buf.toString('ascii', start, pos);
  };
  const magic = token();
  if (magic !== 'PF' && magic !== 'Pf') throw new Error(`PFM: bad magic "${magic.slice(0, 8)}" (expected PF or Pf)`);
  const channels = magic === 'PF' ? 3 : 1;
  const width = Number(token());
  const height = Number(token());
  const scale = Number(token());
  if (!Number.isInteger(width) || width < 1 || !Number.isInteger(height) || height < 1)
    throw new Error(`PFM: bad size ${width} x ${height}`);
  if (!Number.isFinite(scale) || scale === 0) throw new Error('PFM: bad scale');
  pos++; // the single whitespace character that ends the header
  const need = width * height * channels * 4;
  if (buf.length - pos < need)
    throw new Error(
      `PFM: ${width} x ${height} x ${channels} needs ${need} data bytes, the file has ${buf.length - pos}`,
    );
  const little = scale < 0;
  const rgba = new Float32Array(width * height * 4);
  for (let row = 0; row < height; row++) {
    const dstRow = height - 1 - row;
    for (let x = 0; x < width; x++) {
      const o = pos + (row * width + x) * channels * 4;
      const d = (dstRow * width + x) * 4;
      for (let c = 0; c < 3; c++) {
        const at = o + (channels === 3 ? c : 0) * 4;
        rgba[d + c] = little ? buf.readFloatLE(at) : buf.readFloatBE(at);
      }
      rgba[d + 3] = 1;
    }
  }
  return { width, height, channels, rgba };
}

function isSpace(b: number): boolean {
  return b === 0x20 || b === 0x0a || b === 0x0d || b === 0x09;
}

function checkSize(length: number, width: number, height: number, what: string): void {
  if (!Number.isInteger(width) || !Number.isInteger(height) || width < 1 || height < 1)
    throw new Error(`${what}: bad size ${width} x ${height}`);
  if (length !== width * height * 4)
    throw new Error(`${what}: ${width} x ${height} RGBA needs ${width * height * 4} values, got ${length}`);
}
