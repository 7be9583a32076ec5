import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { afterAll, beforeAll, describe, expect, it } from 'vitest';
import { startStaticServer, type StaticServer } from '../../headless/src/index.js';
import { fallbackLoadVolume, ViewerLoadError } from '../src/loading/fallback-loader.js';

// The viewer's own sidecar loader (used when @vpt/loaders is not installed).
let dir: string;
let server: StaticServer;
beforeAll(async () => {
  dir = fs.mkdtempSync(path.join(os.tmpdir(), 'vpt-fallback-'));
  const sidecar = (name: string, extra: object) =>
    fs.writeFileSync(
      path.join(dir, `${name}.json`),
      JSON.stringify({ dims: [2, 2, 2], voxel_type: 'uint16', ...extra }),
    );
  sidecar('ok', { endianness: 'big', spacing: [1, 2, 3], value_range: [0, 1000] });
  fs.writeFileSync(path.join(dir, 'ok.raw'), Buffer.from([0, 1, 0, 2, 0, 3, 0, 4, 0, 5, 0, 6, 0, 7, 1, 0]));
  sidecar('inverted', { value_range: [1000, 0] });
  fs.writeFileSync(path.join(dir, 'inverted.raw'), Buffer.alloc(16));
  sidecar('short', {});
  fs.writeFileSync(path.join(dir, 'short.raw'), Buffer.alloc(10));
  sidecar('nodims', { dims: [2, 2] });
  fs.writeFileSync(path.join(dir, 'bad.json'), '{ not json');
  server = await startStaticServer(dir);
});
afterAll(async () => {
  await server.close();
  fs.rmSync(dir, { recursive: true, force: true });
});

async function reason(url: string): Promise<{ reason: string; message: string }> {
  try {
    await fallbackLoadVolume(new URL(url, server.url).href);
  } catch (e) {
    expect(e).toBeInstanceOf(ViewerLoadError);
    return { reason: (e as ViewerLoadError).reason, message: (e as Error).message };
  }
  throw new Error('loaded');
}

describe('fallback sidecar loader', () => {
  it('loads a sidecar and its raw file: dims, spacing, byte order, value range', async () => {
    const progress: number[] = [];
    const v = await fallbackLoadVolume(new URL('ok.json', server.url).href, {
      onProgress: (p) => progress.push(p.loaded),
    });
    expect(v.dims).toEqual([2, 2, 2]);
    expect(v.spacing).toEqual([1, 2, 3]);
    expect(Array.from(v.data)).toEqual([1, 2, 3, 4, 5, 6, 7, 256]);
    expect(v.valueRange).toEqual([0, 1000]);
    expect(v.format).toBe('raw');
    expect(progress[progress.length - 1]).toBe(16);
  });

  it('keeps an inverted value range (LO > HI: dense matter stored dark)', async () => {
    const v = await fallbackLoadVolume(new URL('inverted.json', server.url).href);
    expect(v.valueRange).toEqual([1000, 0]);
  });

  it('names what is wrong: missing file, short raw, bad sidecar, other formats', async () => {
    expect(await reason('missing.json')).toMatchObject({
      reason: 'not-found',
      message: expect.stringMatching(/missing\.json was not found \(HTTP 404\)/),
    });
    expect(await reason('short.json')).toMatchObject({
      reason: 'truncated',
      message: expect.stringMatching(/need 16 bytes, the file has 10/),
    });
    expect(await reason('nodims.json')).toMatchObject({
      reason: 'bad-header',
      message: expect.stringMatching(/gives dims \[2 × 2\]; they must be three whole numbers/),
    });
    expect(await reason('bad.json')).toMatchObject({
      reason: 'bad-header',
      message: expect.stringMatching(/not valid JSON/),
    });
    expect(await reason('head.nrrd')).toMatchObject({
      reason: 'unsupported',
      message: expect.stringMatching(/needs @vpt\/loaders/),
    });
  });
});
