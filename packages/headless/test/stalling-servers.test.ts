// vpt-render and the headless page against servers that stall, trickle, loop and bomb: a
// scene naming such a URL (sidecar, raw, OME-Zarr) ends in a typed error within the
// request policy's bound (VPT_REQUEST_POLICY here: a few hundred ms, so this runs in seconds).
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { afterAll, beforeAll, describe, expect, it } from 'vitest';
import { runRender } from '../src/cli/render-main.js';
import type { CliIO } from '../src/cli/io.js';
import { openVptPage, type VptPageSession } from '../src/render.js';
import { REQUEST_POLICY_ENV, requestPolicyFromEnv } from '../src/request-policy-env.js';
import { startAbusiveServer, type AbusiveServer } from '../../../tests/helpers/abusive-server.js';

const REQUEST = { stallTimeoutMs: 300, totalTimeoutMs: 2000, retries: 1, retryDelayMs: 10 };
/** The policy's bound plus room for timers on a loaded machine. */
const BOUND_MS = 2000 + 2000;
const SIDECAR = JSON.stringify({ file: 'v.raw', dims: [4, 4, 4], voxel_type: 'uint8' });

let server: AbusiveServer;
let dir: string;
let session: VptPageSession;
beforeAll(async () => {
  server = await startAbusiveServer({ trickleMs: 100, lifetimeMs: 300_000 });
  dir = fs.mkdtempSync(path.join(os.tmpdir(), 'vpt-stall-'));
  session = await openVptPage({ root: null });
}, 120_000);
afterAll(async () => {
  await session?.close();
  await server.close();
  fs.rmSync(dir, { recursive: true, force: true });
});

/** A sidecar and its raw under a fresh prefix; returns the sidecar's URL. */
function serveSidecar(): { prefix: string; sidecar: string } {
  const prefix = `/s-${Math.random().toString(36).slice(2)}`;
  server.files.set(`${prefix}/v.json`, SIDECAR);
  server.files.set(`${prefix}/v.raw`, new Uint8Array(64));
  return { prefix, sidecar: `${server.url}${prefix.slice(1)}/v.json` };
}

async function renderError(volume: Record<string, unknown>) {
  const t0 = Date.now();
  const error = await session
    .render({ volume: volume as never, width: 8, height: 8, iterations: 1 }, { request: REQUEST })
    .then(() => null)
    .catch((e: Error & { code?: string }) => e);
  return { error, ms: Date.now() - t0 };
}

describe('vpt-render with a stalled URL', () => {
  it('a sidecar whose server never answers: exit 1 and a timed-out message within the bound', async () => {
    const { prefix, sidecar } = serveSidecar();
    server.faults.set(`${prefix}/v.json`, 'no-headers');
    const scene = path.join(dir, 'stalled.json');
    fs.writeFileSync(scene, JSON.stringify({ volume: { sidecar }, width: 8, height: 8, iterations: 1 }));
    const stderr: string[] = [];
    const io: CliIO = { out: () => {}, err: (l) => stderr.push(l) };
    const before = process.env[REQUEST_POLICY_ENV];
    process.env[REQUEST_POLICY_ENV] = JSON.stringify(REQUEST);
    const t0 = Date.now();
    try {
      expect(await runRender([scene, '-o', path.join(dir, 'never.png')], io)).toBe(1);
    } finally {
      if (before === undefined) delete process.env[REQUEST_POLICY_ENV];
      else process.env[REQUEST_POLICY_ENV] = before;
    }
    // The browser's start and close are in this time too.
    expect(Date.now() - t0).toBeLessThan(BOUND_MS + 30_000);
    expect(stderr.join('\n')).toMatch(/v\.json: no answer within 300 ms \(timed out\)/);
  }, 120_000);

  it('a bad VPT_REQUEST_POLICY is refused with a message naming it', () => {
    expect(() => requestPolicyFromEnv({ [REQUEST_POLICY_ENV]: '{"stallTimeoutMs": 0}' })).toThrow(
      /VPT_REQUEST_POLICY: request policy: stallTimeoutMs must be a finite number ≥ 1, got 0/,
    );
    expect(() => requestPolicyFromEnv({ [REQUEST_POLICY_ENV]: 'fast' })).toThrow(/VPT_REQUEST_POLICY: not valid JSON/);
    expect(requestPolicyFromEnv({})).toEqual({});
  });
});

describe('the headless page with misbehaving servers', () => {
  it.each([
    ['the sidecar', 'v.json', 'trickle'],
    ['the raw behind a good sidecar', 'v.raw', 'stall-body'],
    ['the raw behind a good sidecar', 'v.raw', 'redirect-loop'],
  ] as const)('%s (%s): %s is a load-failed error within the bound', async (_what, file, fault) => {
    const { prefix, sidecar } = serveSidecar();
    server.faults.set(`${prefix}/${file}`, fault);
    const { error, ms } = await renderError({ sidecar });
    expect(error).toMatchObject({ code: 'load-failed' });
    expect(error!.message).toContain(file);
    if (fault !== 'redirect-loop') expect(error!.message).toMatch(/timed out/);
    expect(ms).toBeLessThan(BOUND_MS);
  });

  it.each(['length-bomb', 'endless', 'gzip-bomb'] as const)(
    'a raw file that is a %s is refused at its dims × type bytes (limit-exceeded)',
    async (fault) => {
      const { prefix, sidecar } = serveSidecar();
      server.faults.set(`${prefix}/v.raw`, fault);
      const { error, ms } = await renderError({ sidecar });
      expect(error).toMatchObject({ code: 'limit-exceeded' });
      expect(error!.message).toMatch(/larger than the 64 bytes allowed/);
      expect(ms).toBeLessThan(BOUND_MS);
    },
  );

  it('an OME-Zarr store whose metadata stalls fails within the bound', async () => {
    const prefix = `/z-${Math.random().toString(36).slice(2)}`;
    server.faults.set(`${prefix}/s.ome.zarr/.zattrs`, 'no-headers');
    server.faults.set(`${prefix}/s.ome.zarr/zarr.json`, 'no-headers');
    const { error, ms } = await renderError({ zarr: `${server.url}${prefix.slice(1)}/s.ome.zarr`, level: 0 });
    expect(error).toMatchObject({ code: 'load-failed' });
    expect(error!.message).toMatch(/timed out/);
    expect(ms).toBeLessThan(2 * BOUND_MS);
  });
});
