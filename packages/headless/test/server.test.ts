import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { afterAll, beforeAll, describe, expect, it } from 'vitest';
import { resolveInside, startStaticServer, type StaticServer } from '../src/server.js';

let dir: string, extra: string, server: StaticServer;

beforeAll(async () => {
  dir = fs.mkdtempSync(path.join(os.tmpdir(), 'vpt-server-root-'));
  extra = fs.mkdtempSync(path.join(os.tmpdir(), 'vpt-server-extra-'));
  fs.writeFileSync(path.join(dir, 'a.html'), '<p>hi</p>');
  fs.writeFileSync(path.join(dir, 'm.mjs'), 'export {}');
  fs.writeFileSync(path.join(dir, 'v.raw'), Buffer.from([1, 2, 3]));
  fs.writeFileSync(path.join(dir, 'x.wasm'), Buffer.from([0, 97, 115, 109]));
  fs.mkdirSync(path.join(dir, 'sub'));
  fs.writeFileSync(path.join(dir, 'sub', 'index.html'), 'index');
  fs.writeFileSync(path.join(extra, 'scene volume.raw'), Buffer.from([9]));
  fs.writeFileSync(path.join(path.dirname(dir), 'outside-secret.txt'), 'secret');
  server = await startStaticServer(dir);
});

afterAll(async () => {
  await server.close();
  fs.rmSync(dir, { recursive: true, force: true });
  fs.rmSync(extra, { recursive: true, force: true });
  fs.rmSync(path.join(path.dirname(dir), 'outside-secret.txt'), { force: true });
});

const get = (p: string, init?: RequestInit) => fetch(new URL(p, server.url), init);

describe('startStaticServer', () => {
  it('listens on 127.0.0.1 with a free port', () => {
    expect(server.url).toBe(`http://127.0.0.1:${server.port}/`);
    expect(server.port).toBeGreaterThan(0);
  });

  it('serves files with their MIME type and no-store caching', async () => {
    const cases: [string, string][] = [
      ['a.html', 'text/html'],
      ['m.mjs', 'text/javascript'],
      ['v.raw', 'application/octet-stream'],
      ['x.wasm', 'application/wasm'],
    ];
    for (const [file, mime] of cases) {
      const r = await get(file);
      expect(r.status).toBe(200);
      expect(r.headers.get('content-type')).toContain(mime);
      expect(r.headers.get('cache-control')).toBe('no-store');
    }
    expect(Array.from(new Uint8Array(await (await get('v.raw')).arrayBuffer()))).toEqual([1, 2, 3]);
  });

  it("serves a folder's index.html and 404s what is missing", async () => {
    expect(await (await get('sub/')).text()).toBe('index');
    expect((await get('nope.js')).status).toBe(404);
    expect((await get('sub/nope/')).status).toBe(404);
  });

  it('never leaves the root', async () => {
    const name = 'outside-secret.txt';
    for (const p of [
      `/../${name}`,
      `/%2e%2e/${name}`,
      `/sub/%2E%2E/%2E%2E/${name}`,
      `/..%2f${name}`,
      `/%2f..%2f${name}`,
    ]) {
      const r = await fetch(`${server.url.slice(0, -1)}${p}`);
      expect(r.status, p).toBe(404);
    }
    expect(resolveInside('/a/b', '../c')).toBeNull();
    expect(resolveInside('/a/b', '/../../c')).toBeNull();
    expect(resolveInside('/a/b', 'c/../d')).toBe('/a/b/d');
  });

  it('mounts extra folders, at a given or a fresh path', async () => {
    const p = server.mount(extra);
    expect(p).toMatch(/^\/__mount\/\d+\/$/);
    expect(server.mount(extra)).toBe(p); // same folder, same path
    expect((await get(`${p}${encodeURIComponent('scene volume.raw')}`)).status).toBe(200);
    expect(server.mount(extra, 'pkg/x')).toBe('/pkg/x/');
    expect((await get('/pkg/x/scene%20volume.raw')).status).toBe(200);
    expect((await get('/pkg/x/%2e%2e/a.html')).status).toBe(404); // encoded: stays inside the mount
  });

  it('answers HEAD without a body and refuses other methods', async () => {
    const head = await get('a.html', { method: 'HEAD' });
    expect(head.status).toBe(200);
    expect(head.headers.get('content-length')).toBe('9');
    expect((await get('a.html', { method: 'POST' })).status).toBe(405);
  });

  it('serves only mounts when root is null', async () => {
    const s = await startStaticServer(null);
    try {
      expect((await fetch(new URL('a.html', s.url))).status).toBe(404);
      s.mount(dir, '/r/');
      expect((await fetch(new URL('/r/a.html', s.url))).status).toBe(200);
    } finally {
      await s.close();
    }
  });
});
