import { LoaderError } from '../errors.js';
import type { LoadContext } from '../context.js';
import { concat } from './read-bytes.js';
import { fflate } from './deps.js';

export function isGzip(bytes: Uint8Array, at = 0): boolean {
  return bytes.length >= at + 3 && bytes[at] === 0x1f && bytes[at + 1] === 0x8b && bytes[at + 2] === 8;
}

/** What `onHead` may return: the bytes to keep, or those and the size the whole stream should have. */
export type HeadPlan = number | { keep: number; declared: number } | undefined;

export interface GunzipOptions {
  /** Stop with a 'limit' error once more than this many bytes come out (a gzip bomb, a lying header). */
  maxOutput: number;
  /**
   * Called once with the first `headBytes` inflated bytes (or all of them, if fewer): it may
   * throw (a bad header stops the work early) or return the number of bytes to keep, or
   * `{ keep, declared }` when the header declares more than is kept (the other volumes of a
   * 4D file): inflated bytes up to `declared` are then expected and not warned about.
   */
  headBytes?: number;
  onHead?: (head: Uint8Array) => HeadPlan;
  /**
   * Filled in with the most inflated bytes held at once (kept output plus the chunk in
   * flight), whether the trailer's CRC-32 and length were checked, and which inflater ran.
   */
  stats?: { peakBytes: number; checksumVerified?: boolean; inflater?: 'native' | 'fflate' };
  /** Use fflate even where DecompressionStream exists (tests of the fallback). */
  inflater?: 'auto' | 'fflate';
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
 * The kept output of an inflate, shared by both inflaters: collects chunks until the head is
 * read, then writes into one buffer of the size the header announced; enforces the cap.
 */
class InflateSink {
  cap: number;
  chunks: Uint8Array[] = [];
  out: Uint8Array | undefined; // allocated once the header told the size
  produced = 0; // bytes kept
  total = 0; // bytes inflated (kept or not)
  declared = 0; // bytes the header declares for the whole stream (≥ the kept ones)
  headDone: boolean;
  readonly headBytes: number;

  constructor(
    private readonly ctx: LoadContext,
    private readonly options: GunzipOptions,
    private readonly stats: { peakBytes: number },
  ) {
    this.cap = options.maxOutput;
    this.headDone = !options.onHead;
    this.headBytes = options.headBytes ?? 0;
  }

  accept(chunk: Uint8Array): void {
    this.stats.peakBytes = Math.max(this.stats.peakBytes, (this.out ? this.out.length : this.produced) + chunk.length);
    this.total += chunk.length;
    if (this.produced + chunk.length > this.cap) {
      if (!this.out)
        throw new LoaderError(
          'limit',
          `${this.ctx.name}: inflates to more than ${this.cap} bytes (limits.maxBytes is ${this.ctx.limits.maxBytes})`,
        );
      // The header's size is reached: keep what it announced, only check the rest.
      this.out.set(chunk.subarray(0, this.out.length - this.produced), this.produced);
      this.produced = this.out.length;
      return;
    }
    if (this.out) this.out.set(chunk, this.produced);
    else this.chunks.push(chunk);
    this.produced += chunk.length;
  }

  /** Has enough come out to read the head? */
  wantsHead(final: boolean): boolean {
    return !this.headDone && (this.produced >= this.headBytes || final);
  }

  takeHead(): void {
    this.headDone = true;
    const head = concat(this.chunks, this.produced);
    this.chunks = [head];
    const plan = this.options.onHead!(head);
    if (plan === undefined) return;
    const expected = typeof plan === 'number' ? plan : plan.keep;
    this.declared = typeof plan === 'number' ? plan : Math.max(plan.keep, plan.declared);
    if (expected > this.cap)
      throw new LoaderError(
        'limit',
        `${this.ctx.name}: its header announces ${expected} bytes, more than the ${this.cap} allowed (limits.maxBytes is ${this.ctx.limits.maxBytes})`,
      );
    this.cap = expected;
    this.out = new Uint8Array(expected);
    this.out.set(head.subarray(0, Math.min(head.length, expected)));
    this.produced = Math.min(this.produced, expected);
    this.chunks = [];
  }

  /** Kept output full and far enough past it: stop inflating (the checksum goes unverified). */
  enough(): boolean {
    return !!this.out && this.produced >= this.out.length && this.total - this.produced > MAX_DISCARD;
  }

  finish(stoppedEarly: boolean, checksumVerified: boolean): Uint8Array {
    if (!this.headDone) this.takeHead();
    if (this.out && this.produced < this.out.length) {
      throw new LoaderError(
        'truncated',
        `${this.ctx.name}: the compressed data holds ${this.produced} bytes, the header announces ${this.out.length}; the file is cut short or its header lies`,
      );
    }
    if (stoppedEarly) {
      // Past the declared size is worth a word; the rest of a 4D file is not.
      if (this.total > this.declared)
        this.ctx.warnings.push('the gzip checksum was not verified (the stream continues far past the data loaded)');
      return this.out!;
    }
    if (checksumVerified && this.out && this.total > Math.max(this.produced, this.declared))
      this.ctx.warnings.push(
        `${this.total - Math.max(this.produced, this.declared)} inflated bytes past the data the header declares are ignored`,
      );
    return this.out ?? concat(this.chunks, this.produced);
  }
}

/** A failure of the native inflater: the fflate path runs again to say exactly what is wrong. */
class NativeInflateFailed extends Error {}

/** Native gzip (DecompressionStream: zlib in Node and browsers, which checks the CRC-32 and ISIZE itself). */
function hasNativeGunzip(): boolean {
  return typeof DecompressionStream === 'function';
}

const NATIVE_STEP = 1 << 20; // input per write: progress, abort checks, and the early stop between writes

async function gunzipNative(
  input: Uint8Array,
  ctx: LoadContext,
  options: GunzipOptions,
  stats: { peakBytes: number },
): Promise<{ bytes: Uint8Array; checksumVerified: boolean }> {
  const sink = new InflateSink(ctx, options, stats);
  const stream = new DecompressionStream('gzip');
  const writer = stream.writable.getWriter();
  const reader = stream.readable.getReader();
  let stopped = false;
  // Feed the input while the chunks are read (awaiting each write before reading would stall on backpressure).
  const feeding = (async () => {
    for (let at = 0; at < input.length && !stopped; at += NATIVE_STEP) {
      const end = Math.min(input.length, at + NATIVE_STEP);
      await writer.write(input.subarray(at, end) as Uint8Array<ArrayBuffer>);
      ctx.progress('parse', end, input.length);
    }
    if (!stopped) await writer.close();
  })();
  feeding.catch(() => {}); // its failure surfaces through reader.read()
  let stoppedEarly = false;
  try {
    for (;;) {
      ctx.checkAborted();
      let result: ReadableStreamReadResult<Uint8Array>;
      try {
        result = await reader.read();
      } catch (e) {
        throw new NativeInflateFailed((e as Error)?.message ?? String(e), { cause: e });
      }
      if (result.done) break;
      sink.accept(result.value);
      if (sink.wantsHead(false)) sink.takeHead();
      if (sink.enough()) {
        stoppedEarly = true;
        break;
      }
    }
  } finally {
    stopped = true;
    void reader.cancel().catch(() => {});
    void writer.abort().catch(() => {});
  }
  return { bytes: sink.finish(stoppedEarly, !stoppedEarly), checksumVerified: !stoppedEarly };
}

/**
 * Inflate a gzip member: natively (DecompressionStream) where the platform has it, else with
 * fflate in 64 KiB steps; both report 'parse' progress and check the size cap as they go.
 * A stream the native inflater rejects is inflated again by fflate, whose checks name the
 * fault (cut short, corrupt, wrong checksum), so every platform gives the same error.
 */
export async function gunzip(input: Uint8Array, ctx: LoadContext, options: GunzipOptions): Promise<Uint8Array> {
  const stats = options.stats ?? { peakBytes: 0 };
  if ((options.inflater ?? 'auto') === 'auto' && hasNativeGunzip()) {
    const warningsBefore = ctx.warnings.length;
    try {
      const { bytes, checksumVerified } = await gunzipNative(input, ctx, options, stats);
      Object.assign(stats, { checksumVerified, inflater: 'native' });
      return bytes;
    } catch (e) {
      if (!(e instanceof NativeInflateFailed)) throw e;
      ctx.warnings.length = warningsBefore;
    }
  }
  return gunzipFflate(input, ctx, options, stats);
}

/**
 * fflate's inflate in 64 KiB steps. fflate checks neither the CRC nor ISIZE of the trailer,
 * so both are checked here: a corrupt or cut stream is an error, not garbage.
 */
async function gunzipFflate(
  input: Uint8Array,
  ctx: LoadContext,
  options: GunzipOptions,
  stats: { peakBytes: number; checksumVerified?: boolean; inflater?: 'native' | 'fflate' },
): Promise<Uint8Array> {
  const { Gunzip } = await fflate();
  const sink = new InflateSink(ctx, options, stats);
  let crc = 0;
  let ended = false;
  const inflater = new Gunzip((chunk, final) => {
    if (final) ended = true;
    crc = crc32(crc, chunk);
    sink.accept(chunk);
  });

  ctx.progress('parse', 0, input.length);
  let stoppedEarly = false;
  const STEP = gunzipStep(sink.cap);
  for (let at = 0; at < input.length; at += STEP) {
    ctx.checkAborted();
    if (sink.enough()) {
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
    if (sink.wantsHead(end === input.length)) sink.takeHead();
    ctx.progress('parse', end, input.length);
  }
  Object.assign(stats, { checksumVerified: !stoppedEarly, inflater: 'fflate' });
  if (stoppedEarly) return sink.finish(true, false);
  if (!sink.headDone) sink.takeHead();
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
  if (read32(tail + 4) !== sink.total % 0x100000000) {
    throw new LoaderError(
      'truncated',
      `${ctx.name}: the gzip trailer announces ${read32(tail + 4)} bytes but ${sink.total} came out; the file is cut short or corrupt`,
    );
  }
  if (read32(tail) !== crc)
    throw new LoaderError(
      'invalid-data',
      `${ctx.name}: the gzip checksum (CRC-32) does not match; the file is corrupt`,
    );
  return sink.finish(false, true);
}
