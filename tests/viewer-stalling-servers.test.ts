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
  server.files.set('/hang.exr', dwaaHang());
  server.files.set('/sky.hdr', '#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 1 +X 2\n' + '\x80\x80\x80\x80'.repeat(2));
});
afterAll(() => server?.close());

/**
 * An OpenEXR file whose header passes every check (8 × 8, RGB half, DWAA) and whose one chunk
 * holds a DWA header with a channel-rule size but no NUL to end the rule's name: Three.js'
 * EXRLoader reads that name past the buffer's end for ever (undefined != 0).
 */
function dwaaHang(): Uint8Array {
  const out: number[] = [0x76, 0x2f, 0x31, 0x01, 2, 0, 0, 0];
  const str = (t: string) => out.push(...[...t].map((c) => c.charCodeAt(0)), 0);
  const i32 = (v: number) => out.push(v & 255, (v >> 8) & 255, (v >> 16) & 255, (v >>> 24) & 255);
  const attr = (name: string, type: string, bytes: number[]) => {
    str(name);
    str(type);
    i32(bytes.length);
    out.push(...bytes);
  };
  const le = (v: number) => [v & 255, (v >> 8) & 255, (v >> 16) & 255, (v >>> 24) & 255];
  const chlist: number[] = [];
  for (const c of 'BGR') chlist.push(c.charCodeAt(0), 0, ...le(1), 0, 0, 0, 0, ...le(1), ...le(1));
  chlist.push(0);
  attr('channels', 'chlist', chlist);
  attr('compression', 'compression', [8]);
  attr('dataWindow', 'box2i', [...le(0), ...le(0), ...le(7), ...le(7)]);
  attr('displayWindow', 'box2i', [...le(0), ...le(0), ...le(7), ...le(7)]);
  attr('lineOrder', 'lineOrder', [0]);
  out.push(0);
  const chunk = out.length + 8;
  out.push(...le(chunk), 0, 0, 0, 0); // the one chunk's offset (int64)
  i32(0); // its first line
  i32(200); // its data size (< 8 lines × 48 bytes: compressed)
  for (let k = 0; k < 11; k++) out.push(...(k === 0 ? le(2) : le(0)), 0, 0, 0, 0); // DWA header: version 2
  out.push(100, 0); // channel rules: 98 bytes of names
  for (let k = 0; k < 64; k++) out.push(0x41); // a name with no NUL
  return new Uint8Array(out);
}

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

  it('environment: an EXR on which the decoder loops is stopped in its worker with a typed error; the page stays responsive', async () => {
    server.faults.clear();
    const r = await viewer().run(
      async (vt, url: string, request: Record<string, number>) => {
        const el = vt.create({ backend: 'webgl2', panels: 'none', 'max-samples': '1' });
        el.requestPolicy = request;
        el.setAttribute('src', 'procedural:blob?size=8');
        let ticks = 0;
        const timer = setInterval(() => ticks++, 50);
        const error = vt.next(el, 'error', 20_000);
        el.setAttribute('environment', JSON.stringify({ type: 'url', url }));
        const detail = await error;
        clearInterval(timer);
        el.remove();
        return { code: detail.code, message: detail.message, source: detail.source, ticks };
      },
      `${server.url}hang.exr`,
      REQUEST,
    );
    expect(r).toMatchObject({ code: 'limit-exceeded', source: 'environment' });
    expect(r.message).toMatch(/decoding .*hang\.exr took longer than 2000 ms/);
    // The main thread ran its timer while the decoder looped (a frozen thread runs none).
    expect(r.ticks).toBeGreaterThan(5);
  });
});
