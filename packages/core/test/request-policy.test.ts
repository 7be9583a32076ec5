// The one request policy (core/src/io/request.ts) against a server that stalls, trickles,
// loops and bombs: every request ends in a typed RequestError within the policy's bound.
import { afterAll, beforeAll, describe, expect, it } from 'vitest';
import { fetchWithPolicy, RequestError, resolveRequestPolicy, VptError, type RequestPolicy } from '@vpt/core';
import { startAbusiveServer, type AbuseFault, type AbusiveServer } from '../../../tests/helpers/abusive-server.js';

const POLICY: Partial<RequestPolicy> = { stallTimeoutMs: 300, totalTimeoutMs: 2500, retries: 1, retryDelayMs: 10 };
/** Timers and a loaded machine: how late past its bound a request may end. */
const SLACK_MS = 1500;

let server: AbusiveServer;
beforeAll(async () => {
  server = await startAbusiveServer({ trickleMs: 100, lifetimeMs: 120_000 });
  server.files.set('/ok.bin', new Uint8Array([1, 2, 3, 4, 5]));
});
afterAll(() => server.close());

async function outcome(fault: AbuseFault | null, options: Parameters<typeof fetchWithPolicy>[1] = {}) {
  const path = `/${fault ?? 'ok'}.bin`;
  if (fault) server.faults.set(path, fault);
  server.hits.delete(path);
  const t0 = Date.now();
  try {
    const got = await fetchWithPolicy(server.url + path.slice(1), { policy: POLICY, ...options });
    return { ms: Date.now() - t0, bytes: got.bytes, hits: server.hits.get(path) ?? 0 };
  } catch (e) {
    return { ms: Date.now() - t0, error: e as RequestError, hits: server.hits.get(path) ?? 0 };
  }
}

describe('fetchWithPolicy', () => {
  it('returns the body of a good answer', async () => {
    const r = await outcome(null);
    expect(Array.from(r.bytes!)).toEqual([1, 2, 3, 4, 5]);
  });

  it('a large answer: the same bytes, with progress as they arrive up to the length', async () => {
    // The bytes come from a native read, the progress from a clone read by script (request.ts).
    const big = new Uint8Array(3 << 20).map((_, i) => (i * 2654435761) >>> 24);
    server.files.set('/big.bin', big);
    const seen: [number, number | undefined][] = [];
    const got = await fetchWithPolicy(`${server.url}big.bin`, {
      policy: POLICY,
      onProgress: (loaded, total) => seen.push([loaded, total]),
    });
    expect(got.bytes.length).toBe(big.length);
    expect(Buffer.compare(Buffer.from(got.bytes), Buffer.from(big))).toBe(0);
    expect(seen.length).toBeGreaterThan(2);
    expect(seen.every(([, total]) => total === big.length)).toBe(true);
    expect(seen.every(([loaded], i) => i === 0 || loaded >= seen[i - 1][0])).toBe(true);
    expect(seen.at(-1)).toEqual([big.length, big.length]);
  });

  it.each([
    ['no-headers', /no answer within 300 ms/],
    ['stall-body', /stalled after 16 bytes/],
    ['trickle', /stalled after \d+ bytes \(fewer than 1024 bytes in 300 ms/],
  ] as const)('%s: a timed-out network error after every attempt, within the bound', async (fault, message) => {
    const r = await outcome(fault);
    expect(r.error).toBeInstanceOf(RequestError);
    expect(r.error).toMatchObject({ reason: 'network', code: 'load-failed', timedOut: true });
    expect(r.error!.message).toMatch(message);
    // One retry (a stall may be transient), each attempt ended by its stall window.
    expect(r.hits).toBe(2);
    expect(r.ms).toBeGreaterThanOrEqual(2 * 300 - 50);
    expect(r.ms).toBeLessThan(2500 + SLACK_MS);
  });

  it('a body that keeps coming ends at the total bound (no size bound given)', async () => {
    const r = await outcome('endless', { policy: { ...POLICY, totalTimeoutMs: 800, retries: 0 } });
    expect(r.error).toMatchObject({ reason: 'network', timedOut: true });
    expect(r.error!.message).toMatch(/request bound of 800 ms/);
    expect(r.ms).toBeLessThan(800 + SLACK_MS);
  });

  it.each(['length-bomb', 'endless', 'gzip-bomb'] as const)(
    '%s: refused with limit-exceeded once past maxBytes, not retried',
    async (fault) => {
      const r = await outcome(fault, { maxBytes: 1 << 20 });
      expect(r.error).toMatchObject({ reason: 'limit', code: 'limit-exceeded', timedOut: false });
      expect(r.error!.message).toMatch(/larger than the 1048576 bytes allowed/);
      expect(r.hits).toBe(1);
      expect(r.ms).toBeLessThan(2500 + SLACK_MS);
    },
  );

  it('a redirect loop and a 503 fail as network errors naming the URL; a 404 is not-found, not retried', async () => {
    // Twenty redirects on a loaded machine can take longer than the 300 ms stall bound: a wider one here.
    const loop = await outcome('redirect-loop', {
      policy: { ...POLICY, stallTimeoutMs: 5000, totalTimeoutMs: 10_000 },
    });
    expect(loop.error).toMatchObject({ reason: 'network', timedOut: false });
    expect(loop.error!.message).toMatch(/redirect-loop\.bin/);
    const busy = await outcome('503');
    expect(busy.error).toMatchObject({ reason: 'network', status: 503 });
    expect(busy.hits).toBe(2);
    const t0 = Date.now();
    const gone = await fetchWithPolicy(`${server.url}gone.bin`, { policy: POLICY }).catch((e) => e);
    expect(gone).toMatchObject({ reason: 'not-found', status: 404 });
    expect(server.hits.get('/gone.bin')).toBe(1);
    expect(Date.now() - t0).toBeLessThan(SLACK_MS);
  });

  it("the caller's abort ends a stalled request at once", async () => {
    server.faults.set('/abort.bin', 'no-headers');
    const abort = new AbortController();
    setTimeout(() => abort.abort(), 100);
    const t0 = Date.now();
    const e = await fetchWithPolicy(`${server.url}abort.bin`, {
      signal: abort.signal,
      policy: { stallTimeoutMs: 60_000 },
    }).catch((x) => x);
    expect(e).toMatchObject({ reason: 'aborted' });
    expect(Date.now() - t0).toBeLessThan(100 + SLACK_MS);
  });

  it('a policy with a bad or unknown field is refused with a message naming it', () => {
    expect(() => resolveRequestPolicy({ stallTimeoutMs: Infinity })).toThrow(/stallTimeoutMs must be a finite/);
    expect(() => resolveRequestPolicy({ retries: 2.5 })).toThrow(/retries must be a finite integer/);
    expect(() => resolveRequestPolicy({ stall: 1 } as never)).toThrow(VptError);
    expect(() => resolveRequestPolicy({ stall: 1 } as never)).toThrow(/unknown key stall/);
  });
});
