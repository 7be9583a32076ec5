import { afterAll, beforeAll, describe, expect, it } from 'vitest';
import { startAbusiveServer, type AbuseFault, type AbusiveServer } from './helpers/abusive-server.js';
import { seededRandom } from './helpers/seeded-random.js';
import { useViewerPage } from './helpers/viewer-page.js';

/**
 * Issue 28: <vpt-viewer> with a src or environment URL whose server stalls or trickles used
 * to show 'Loading… 50%' for ever and never settle. Under the request policy (the element's
 * `requestPolicy`, a few hundred ms here) every such load ends in a typed `vpt-error`, the
 * status line clears and `whenSettled()` resolves, within the bound.
 */
const REQUEST = { stallTimeoutMs: 300, totalTimeoutMs: 2000, retries: 1, retryDelayMs: 10 };
const BOUND_MS = 2000 + 2500;
const viewer = useViewerPage();
let server: AbusiveServer;
beforeAll(async () => {
  server = await startAbusiveServer({ trickleMs: 100, lifetimeMs: 300_000 });
  server.files.set('/v.json', JSON.stringify({ file: 'v.raw', dims: [4, 4, 4], voxel_type: 'uint8' }));
  server.files.set('/v.raw', new Uint8Array(64));
  server.files.set('/v.nrrd', `NRRD0004\ntype: uchar\ndimension: 3\nsizes: 4 4 4\nencoding: raw\n\n${'\0'.repeat(64)}`);
  // 2 KB of random bytes after the EXR magic: Three.js' EXRLoader alone loops for ever on it.
  const random = seededRandom(28);
  const bomb = new Uint8Array(2048).map(() => Math.floor(random() * 256));
  bomb.set([0x76, 0x2f, 0x31, 0x01, 2, 0, 0, 0]);
  server.files.set('/bomb.exr', bomb);
  server.files.set('/sky.hdr', '#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 1 +X 2\n' + '\x80\x80\x80\x80'.repeat(2));
});
afterAll(() => server?.close());

async function settle(attribute: 'src' | 'environment', value: string) {
  return viewer().run(
    async (vt, attr: string, v: string, request: Record<string, number>) => {
      const el = vt.create({ backend: 'webgl2', panels: 'none', 'max-samples': '1' });
      el.requestPolicy = request;
      if (attr === 'environment') el.setAttribute('src', 'procedural:blob?size=8');
      const error = vt.next(el, 'error', 20_000);
      const t0 = performance.now();
      el.setAttribute(attr, v);
      const detail = await error;
      await el.whenSettled();
      const ms = performance.now() - t0;
      const status = vt.shadowText(el, '.status');
      el.remove();
      return { code: detail.code, reason: detail.reason, message: detail.message, source: detail.source, ms, status };
    },
    attribute,
    value,
    REQUEST,
  );
}

describe('<vpt-viewer> with a misbehaving server', () => {
  it.each([
    ['a sidecar', '/v.json', 'no-headers'],
    ['the raw behind a sidecar', '/v.raw', 'stall-body'],
    ['an NRRD', '/v.nrrd', 'trickle'],
  ] as const)('src: %s (%s) that %s ends in a timed-out load error and settles', async (_what, path, fault) => {
    server.faults.clear();
    server.faults.set(path, fault as AbuseFault);
    const entry = path === '/v.raw' ? '/v.json' : path;
    const r = await settle('src', `${server.url}${entry.slice(1)}`);
    expect(r).toMatchObject({ code: 'load-failed', source: 'src' });
    expect(r.message).toMatch(/timed out/);
    expect(r.message).toContain(path.slice(1));
    expect(r.status ?? '').not.toMatch(/Loading/);
    expect(r.ms).toBeLessThan(BOUND_MS);
  });

  it.each(['no-headers', 'trickle'] as const)(
    'environment: an HDR URL that %s ends in a load error and settles',
    async (fault) => {
      server.faults.clear();
      server.faults.set('/sky.hdr', fault);
      const r = await settle('environment', JSON.stringify({ type: 'url', url: `${server.url}sky.hdr` }));
      expect(r).toMatchObject({ code: 'load-failed', source: 'environment' });
      expect(r.message).toMatch(/sky\.hdr.*timed out/);
      expect(r.ms).toBeLessThan(BOUND_MS);
    },
  );

  it('environment: an EXR bomb (the magic, then random bytes) is refused at once and the page stays responsive', async () => {
    server.faults.clear();
    const r = await settle('environment', JSON.stringify({ type: 'url', url: `${server.url}bomb.exr` }));
    expect(r).toMatchObject({ code: 'load-failed', source: 'environment' });
    expect(r.message).toMatch(/bomb\.exr has a broken header/);
    expect(r.ms).toBeLessThan(BOUND_MS);
  });
});
