/**
 * Bounds checks of an environment file's header, run before Three.js' decoders see the
 * bytes. EXRLoader reads a header string until a NUL byte without looking at the buffer's
 * end, so a few KB of random bytes after the EXR magic loop for ever on the main thread;
 * both decoders allocate whatever size the header claims. This reads the header itself
 * (OpenEXR file layout, "Reading and writing OpenEXR image files", section "Header";
 * Radiance RGBE: Ward, "Real Pixels", Graphics Gems II) with every read inside the buffer,
 * and refuses a file whose size, channels or layout it cannot trust.
 */
import { LATLONG_SIDE_RULE, VptError } from '@vpt/core';

/** Largest side of a lat-long environment (core's rule: a 2D texture side). */
export const MAX_ENVIRONMENT_SIDE = LATLONG_SIDE_RULE.max ?? 16383;
/** Most pixels of an environment: 8k × 4k (a 512 MiB float RGBA image). */
export const MAX_ENVIRONMENT_PIXELS = 8192 * 4096;

const EXR_MAGIC = 20000630;
/** The attributes every OpenEXR header has (the spec's "required attributes"). */
const EXR_REQUIRED = ['channels', 'compression', 'dataWindow', 'displayWindow', 'lineOrder'] as const;
/** Scan lines per chunk by compression code (NONE, RLE, ZIPS, ZIP, PIZ, PXR24, B44, B44A, DWAA, DWAB). */
const EXR_LINES_PER_CHUNK = [1, 1, 1, 16, 32, 16, 32, 32, 32, 256];

function refuse(url: string, why: string, code: 'load-failed' | 'limit-exceeded' = 'load-failed'): never {
  throw new VptError(code, `environment: ${url} ${why}`);
}

function checkSize(url: string, width: number, height: number): void {
  if (!(width >= 1 && height >= 1)) refuse(url, `has an empty or negative size (${width} × ${height})`);
  if (width > MAX_ENVIRONMENT_SIDE || height > MAX_ENVIRONMENT_SIDE || width * height > MAX_ENVIRONMENT_PIXELS)
    refuse(
      url,
      `is ${width} × ${height} pixels; an environment may have at most ${MAX_ENVIRONMENT_SIDE} per side and ${MAX_ENVIRONMENT_PIXELS} in all`,
      'limit-exceeded',
    );
}

/** Whether the bytes start with OpenEXR's magic number. */
export function isExr(bytes: Uint8Array): boolean {
  return bytes.length >= 4 && new DataView(bytes.buffer, bytes.byteOffset, 4).getUint32(0, true) === EXR_MAGIC;
}

/** Check an OpenEXR header: attributes inside the file, the required ones present and sane, the size bounded. */
export function checkExrHeader(bytes: Uint8Array, url: string): { width: number; height: number } {
  const view = new DataView(bytes.buffer, bytes.byteOffset, bytes.byteLength);
  if (bytes.length < 8 || !isExr(bytes)) refuse(url, 'is not an OpenEXR file (no magic number)');
  const flags = view.getUint8(5);
  if (view.getUint8(4) !== 2) refuse(url, `has OpenEXR version ${view.getUint8(4)}; only version 2 is read`);
  if (flags & ~0x06) refuse(url, 'is a deep or multi-part OpenEXR file, which is not read');
  const maxName = flags & 0x04 ? 255 : 31;
  let at = 8;
  const text = (): string => {
    const end = bytes.indexOf(0, at);
    if (end < 0 || end - at > maxName)
      refuse(url, `has a broken header: no name of at most ${maxName} bytes at byte ${at}`);
    const s = new TextDecoder().decode(bytes.subarray(at, end));
    at = end + 1;
    return s;
  };
  const attributes = new Map<string, { type: string; offset: number; size: number }>();
  for (;;) {
    if (at >= bytes.length) refuse(url, 'has a header that never ends (truncated or not OpenEXR)');
    const name = text();
    if (name === '') break;
    const type = text();
    if (at + 4 > bytes.length) refuse(url, `has a broken header: attribute "${name}" is cut off`);
    const size = view.getUint32(at, true);
    at += 4;
    if (size > bytes.length - at) refuse(url, `has a broken header: attribute "${name}" claims ${size} bytes`);
    attributes.set(name, { type, offset: at, size });
    at += size;
  }
  for (const name of EXR_REQUIRED)
    if (!attributes.has(name)) refuse(url, `has no "${name}" attribute (a required OpenEXR attribute)`);
  const dataWindow = attributes.get('dataWindow')!;
  if (dataWindow.type !== 'box2i' || dataWindow.size !== 16) refuse(url, 'has a dataWindow that is not a box2i');
  const [xMin, yMin, xMax, yMax] = [0, 4, 8, 12].map((o) => view.getInt32(dataWindow.offset + o, true));
  const width = xMax - xMin + 1;
  const height = yMax - yMin + 1;
  checkSize(url, width, height);
  const compression = attributes.get('compression')!;
  const code = compression.size === 1 ? view.getUint8(compression.offset) : -1;
  if (!(code >= 0 && code < EXR_LINES_PER_CHUNK.length)) refuse(url, `has an unknown compression (${code})`);
  const channels = attributes.get('channels')!;
  if (channels.type !== 'chlist') refuse(url, 'has a channel list that is not a chlist');
  // A chlist: per channel a NUL-terminated name, pixel type, pLinear + 3 reserved bytes, x and y sampling; then one NUL.
  let c = channels.offset;
  const end = channels.offset + channels.size;
  let count = 0;
  while (c < end - 1) {
    const nul = bytes.indexOf(0, c);
    if (nul < 0 || nul + 17 > end) refuse(url, 'has a broken channel list');
    const pixelType = view.getInt32(nul + 1, true);
    if (pixelType < 0 || pixelType > 2) refuse(url, `has a channel of unknown pixel type ${pixelType}`);
    c = nul + 17;
    count++;
  }
  if (count === 0) refuse(url, 'has no channels');
  // Scan-line files start the data with one 8-byte offset per chunk: it must fit in the file.
  const chunks = Math.ceil(height / EXR_LINES_PER_CHUNK[code]);
  if (!(flags & 0x02) && at + chunks * 8 > bytes.length)
    refuse(url, `is cut off: ${chunks} chunk offsets do not fit in its ${bytes.length} bytes`);
  return { width, height };
}

/** Check a Radiance .hdr header: the magic line, a header that ends, a resolution line with a bounded size. */
export function checkHdrHeader(bytes: Uint8Array, url: string): { width: number; height: number } {
  // The header and the resolution line are short text; read at most 64 KiB of it.
  const head = new TextDecoder('latin1').decode(bytes.subarray(0, Math.min(bytes.length, 65536)));
  if (!/^#\?(RADIANCE|RGBE)/.test(head)) refuse(url, 'is not a Radiance .hdr file (no #?RADIANCE line)');
  const blank = head.indexOf('\n\n');
  if (blank < 0) refuse(url, 'has a header that never ends (no blank line in its first 64 KiB)');
  const resolution = /^([-+])Y (\d{1,9}) ([-+])X (\d{1,9})\r?\n/.exec(head.slice(blank + 2));
  if (!resolution) refuse(url, 'has no resolution line like "-Y 512 +X 1024" after its header');
  const height = Number(resolution[2]);
  const width = Number(resolution[4]);
  checkSize(url, width, height);
  return { width, height };
}
