// Every kind of URL @vpt/loaders fetches (a sidecar, the raw behind it, NRRD, NIfTI, an
// OME-Zarr store's metadata and chunks) from a server that stalls, trickles, loops or bombs:
// each load ends in a typed LoaderError within the request policy's bound (core's
// fetchWithPolicy; here with bounds of a few hundred ms so the test runs in seconds).
import { afterAll, beforeAll, describe, expect, it } from 'vitest';
import type { RequestPolicy } from '@vpt/core';
import { loadVolume, openOmeZarr, writeOmeZarr, type LoadOptions } from '../src/index.js';
import { startAbusiveServer, type AbuseFault, type AbusiveServer } from '../../../tests/helpers/abusive-server.js';
import { expectLoaderError, nrrdFile, niftiFile } from './helpers.js';

const REQUEST: Partial<RequestPolicy> = { stallTimeoutMs: 300, totalTimeoutMs: 2000, retries: 1, retryDelayMs: 10 };
/** The policy's bound plus room for timers on a loaded machine. */
const BOUND_MS = 2000 + 1500;
const SIDECAR = JSON.stringify({ file: 'v.raw', dims: [4, 4, 4], voxel_type: 'uint8' });

let server: AbusiveServer;
beforeAll(async () => {
  server = await startAbusiveServer({ trickleMs: 100, lifetimeMs: 120_000 });
});
afterAll(() => server.close());

/** Serve `files`, break `faulty` with `fault`, load `entry`; the error and how long it took. */
async function failingLoad(
  files: Record<string, Uint8Array | string>,
  faulty: string,
  fault: AbuseFault,
  entry: string,
  options: LoadOptions = {},
) {
  const prefix = `/${fault}-${Math.random().toString(36).slice(2)}`;
  for (const [name, bytes] of Object.entries(files)) server.files.set(`${prefix}/${name}`, bytes);
  server.faults.set(`${prefix}/${faulty}`, fault);
  const t0 = Date.now();
  const error = await expectLoaderError(
    loadVolume(`${server.url}${prefix.slice(1)}/${entry}`, { request: REQUEST, ...options }),
    fault.includes('bomb') || fault === 'endless' ? 'limit' : 'network',
  );
  return { error, ms: Date.now() - t0 };
}

describe('loadVolume from a misbehaving server', () => {
  const raw = { 'v.json': SIDECAR, 'v.raw': new Uint8Array(64) };
  it.each([
    ['the sidecar', 'v.json', 'no-headers'],
    ['the sidecar', 'v.json', 'trickle'],
    ['the raw behind a good sidecar', 'v.raw', 'stall-body'],
    ['the raw behind a good sidecar', 'v.raw', 'trickle'],
  ] as const)('%s (%s): %s ends in a timed-out network error', async (_what, faulty, fault) => {
    const { error, ms } = await failingLoad(raw, faulty, fault, 'v.json');
    expect(error.message).toMatch(/timed out/);
    expect(error.message).toContain(faulty);
    expect(ms).toBeLessThan(BOUND_MS);
  });

  it('NRRD and NIfTI URLs that stall or trickle end the same way', async () => {
    const nrrd = nrrdFile({ type: 'uchar', dimension: '3', sizes: '4 4 4', encoding: 'raw' }, new Uint8Array(64));
    const nifti = niftiFile({ dims: [4, 4, 4], datatype: 2, bitpix: 8, data: new Uint8Array(64) });
    for (const fault of ['no-headers', 'trickle'] as const) {
      expect((await failingLoad({ 'v.nrrd': nrrd }, 'v.nrrd', fault, 'v.nrrd')).ms).toBeLessThan(BOUND_MS);
      expect((await failingLoad({ 'v.nii': nifti }, 'v.nii', fault, 'v.nii')).ms).toBeLessThan(BOUND_MS);
    }
  });

  it('a redirect loop is a network error naming the URL', async () => {
    const { error } = await failingLoad(raw, 'v.json', 'redirect-loop', 'v.json');
    expect(error.message).toMatch(/v\.json/);
  });

  it.each(['length-bomb', 'endless', 'gzip-bomb'] as const)(
    'a raw file that is a %s is refused with limit-exceeded at the size bound',
    async (fault) => {
      const { error, ms } = await failingLoad(raw, 'v.raw', fault, 'v.json', { limits: { maxBytes: 1 << 16 } });
      expect(error.code).toBe('limit-exceeded');
      expect(error.message).toMatch(/larger than the \d+ bytes allowed/);
      expect(ms).toBeLessThan(BOUND_MS);
    },
  );

  it('a sidecar that is a bomb is refused at the text bound (16 MiB), whatever maxBytes says', async () => {
    const { error } = await failingLoad(raw, 'v.json', 'length-bomb', 'v.json', { limits: { maxBytes: 2 ** 30 } });
    expect(error.message).toMatch(/larger than the 16777216 bytes allowed/);
  });
});

describe('OME-Zarr from a misbehaving server', () => {
  let files: Record<string, Uint8Array>;
  beforeAll(async () => {
    files = {};
    await writeOmeZarr(
      (key, bytes) => void (files[key.replace(/^\/+/, '')] = bytes),
      { dims: [8, 8, 8], type: 'uint8', spacing: [1, 1, 1], images: [[new Uint8Array(512)]] },
      { version: '0.4', chunk: [4, 4, 4] },
    );
  });

  it.each([
    ['.zattrs', 'no-headers'],
    ['.zattrs', 'trickle'],
    ['0/0/0/1', 'stall-body'],
    ['0/0/1/0', 'redirect-loop'],
  ] as const)('%s: %s ends in a network error within the bound', async (key, fault) => {
    const prefix = `/z-${Math.random().toString(36).slice(2)}`;
    for (const [name, bytes] of Object.entries(files)) server.files.set(`${prefix}/s.ome.zarr/${name}`, bytes);
    server.faults.set(`${prefix}/s.ome.zarr/${key}`, fault);
    const t0 = Date.now();
    const source = openOmeZarr(`${server.url}${prefix.slice(1)}/s.ome.zarr`, { request: REQUEST }).then((s) =>
      s.readLevel(0),
    );
    await expectLoaderError(source, 'network');
    expect(Date.now() - t0).toBeLessThan(2 * BOUND_MS);
  });
});
