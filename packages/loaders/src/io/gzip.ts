import { LoaderError } from '../errors.js';
import type { LoadContext } from '../context.js';
import { concat } from './read-bytes.js';
import { fflate } from './deps.js';

export function isGzip(bytes: Uint8Array, at = 0): boolean {
  return bytes.length >= at + 3 && bytes[at] === 0x1f && bytes[at + 1] === 0x8b && bytes[at + 2] === 8;
}

export interface GunzipOptions {
  /** Stop with a 'limit' error once more than this many bytes come out (a gzip bomb, a lying header). */
  maxOutput: number;
  /**
   * Called once with the first `headBytes` inflated bytes (or all of them, if fewer): it may
   * throw (a bad header stops the work early) or return the number of bytes to keep.
   */
  headBytes?: number;
  onHead?: (head: Uint8Array) => number | undefined;
  /** Filled in with the most inflated bytes held at once (kept output plus the chunk in flight). */
  stats?: { peakBytes: number };
}

const MAX_STEP = 1 << 16; // input per push: bounds the output of one push to ~64 MiB even for a bomb
const MIN_STEP = 64;
/** Deflate's largest expansion (a 258-byte match per ~2 bits): ~1032:1. */
const MAX_RATIO = 1032;

/**
 * Input bytes per push so one push inflates to at most ~cap/8: the peak (the kept output,
 * at most the cap, plus one chunk) then stays within 9/8 of the cap even for a bomb.
 */
export function gunzipStep(cap: number): number {
  const step = Math.floor(cap / MAX_RATIO / 8);
  return Math.max(MIN_STEP, Math.min(MAX_STEP, step));
}
const MAX_DISCARD = 64 << 20; // inflate at most this much past the kept bytes just to verify the CRC

// CRC-32 (IEEE 802.3, the gzip trailer's checksum; RFC 1952 §8), table-driven.
const CRC_TABLE = (() => {
  const t = new Int32Array(256);
  for (let n = 0; n < 256; n++) {
    let c = n;
    for (let k = 0; k < 8; k++) c = c & 1 ? 0xedb88320 ^ (c >>> 1) : c >>> 1;
    t[n] = c;
  }
  return t;
})();

function crc32(crc: number, b: Uint8Array): number {
  let c = ~crc;
  for (let i = 0; i < b.length; i++) c = CRC_TABLE[(c ^ b[i]) & 0xff] ^ (c >>> 8);
  return ~c >>> 0;
}

/**
 * Inflate a gzip member with fflate in 64 KiB steps, reporting 'parse' progress and
 * checking the size cap as it goes. fflate checks neither the CRC nor ISIZE of the
 * trailer, so both are checked here: a corrupt or cut stream is an error, not garbage.
 */
export async function gunzip(input: Uint8Array, ctx: LoadContext, options: GunzipOptions): Promise<Uint8Array> {
  const { Gunzip } = await fflate();
  let cap = options.maxOutput;
  let chunks: Uint8Array[] = [];
  let out: Uint8Array | undefined; // allocated once the header told the size
  let produced = 0; // bytes kept
  let total = 0; // bytes inflated (kept or not)
  let crc = 0;
  let ended = false;
  let headDone = !options.onHead;
  const headBytes = options.headBytes ?? 0;

  const takeHead = () => {
    headDone = true;
    const head = concat(chunks, produced);
    chunks = [head];
    const expected = options.onHead!(head);
    if (expected !== undefined) {
      if (expected > cap)
        throw new LoaderError(
          'limit',
          `${ctx.name}: its header announces ${expected} bytes, more than the ${cap} allowed (limits.maxBytes is ${ctx.limits.maxBytes})`,
        );
      cap = expected;
      out = new Uint8Array(expected);
      out.set(head.subarray(0, Math.min(head.length, expected)));
      produced = Math.min(produced, expected);
      chunks = [];
    }
  };

  const stats = options.stats ?? { peakBytes: 0 };
  const inflater = new Gunzip((chunk, final) => {
    if (final) ended = true;
    stats.peakBytes = Math.max(stats.peakBytes, (out ? out.length : produced) + chunk.length);
    crc = crc32(crc, chunk);
    total += chunk.length;
    if (produced + chunk.length > cap) {
      if (!out)
        throw new LoaderError(
          'limit',
          `${ctx.name}: inflates to more than ${cap} bytes (limits.maxBytes is ${ctx.limits.maxBytes})`,
        );
      // The header's size is reached: keep what it announced, only check the rest.
      out.set(chunk.subarray(0, out.length - produced), produced);
      produced = out.length;
      return;
    }
    if (out) out.set(chunk, produced);
    else chunks.push(chunk);
    produced += chunk.length;
  });

  ctx.progress('parse', 0, input.length);
  let stoppedEarly = false;
  const STEP = gunzipStep(cap);
  for (let at = 0; at < input.length; at += STEP) {
    ctx.checkAborted();
    if (out && produced >= out.length && total - produced > MAX_DISCARD) {
      stoppedEarly = true;
      break;
    }
    const end = Math.min(input.length, at + STEP);
    try {
      inflater.push(input.subarray(at, end), end === input.length);
    } catch (e) {
      if (e instanceof LoaderError) throw e;
      const msg = (e as Error)?.message ?? String(e);
      if (/unexpected EOF/i.test(msg))
        throw new LoaderError('truncated', `${ctx.name}: the gzip stream ends early (${msg}); the file is cut short`, {
          cause: e,
        });
      throw new LoaderError('invalid-data', `${ctx.name}: the gzip data is corrupt (${msg})`, { cause: e });
    }
    if (!headDone && (produced >= headBytes || end === input.length)) takeHead();
    ctx.progress('parse', end, input.length);
  }
  if (!headDone) takeHead();
  if (out && produced < out.length) {
    throw new LoaderError(
      'truncated',
      `${ctx.name}: the compressed data holds ${produced} bytes, the header announces ${out.length}; the file is cut short or its header lies`,
    );
  }
  if (stoppedEarly) {
    ctx.warnings.push('the gzip checksum was not verified (the stream continues far past the data loaded)');
    return out!;
  }
  if (!ended)
    throw new LoaderError(
      'truncated',
      `${ctx.name}: the gzip stream ends early (no final block); the file is cut short`,
    );
  if (input.length < 18)
    throw new LoaderError('truncated', `${ctx.name}: ${input.length} bytes is too short for a gzip stream`);
  // The trailer of the (last) member: CRC-32 then ISIZE, little-endian. Bytes after the
  // member (padding, a second member) make this check fail too: such files are rare.
  const tail = input.length - 8;
  const read32 = (i: number) => (input[i] | (input[i + 1] << 8) | (input[i + 2] << 16) | (input[i + 3] << 24)) >>> 0;
  if (read32(tail + 4) !== total % 0x100000000) {
    throw new LoaderError(
      'truncated',
      `${ctx.name}: the gzip trailer announces ${read32(tail + 4)} bytes but ${total} came out; the file is cut short or corrupt`,
    );
  }
  if (read32(tail) !== crc)
    throw new LoaderError(
      'invalid-data',
      `${ctx.name}: the gzip checksum (CRC-32) does not match; the file is corrupt`,
    );
  if (out && total > produced)
    ctx.warnings.push(`${total - produced} inflated bytes past the data the header declares are ignored`);
  return out ?? concat(chunks, produced);
}
