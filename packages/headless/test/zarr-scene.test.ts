import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { afterAll, beforeAll, describe, expect, it } from 'vitest';
import { thrownVptError as thrown } from '../../../tests/helpers/test-scene.js';
import { mountSceneFiles, resolveSceneFiles } from '../src/scene-files.js';
import { startStaticServer, type StaticServer } from '../src/server.js';
import { validateSceneDescription } from '../src/validate-description.js';
import { checkSceneDescription } from '../src/scene-description.js';

describe('scene descriptions name OME-Zarr volumes', () => {
  it('accepts zarr with level, channel, time, valueRange and missingChunks', () => {
    const volume = { zarr: 'a.ome.zarr', level: 2, channel: 1, time: 0, valueRange: [0, 202], missingChunks: 'fill' };
    expect(() => validateSceneDescription({ volume })).not.toThrow();
    expect(() => checkSceneDescription({ volume })).not.toThrow();
  });
  it('refuses bad fields, naming them', () => {
    const bad: [Record<string, unknown>, RegExp][] = [
      [{ zarr: 'a.zarr', level: -1 }, /volume\.level/],
      [{ zarr: 'a.zarr', channel: 0.5 }, /volume\.channel/],
      [{ zarr: 'a.zarr', time: 'first' }, /volume\.time/],
      [{ zarr: 'a.zarr', valueRange: [3, 3] }, /volume\.valueRange/],
      [{ zarr: 'a.zarr', missingChunks: 'skip' }, /volume\.missingChunks/],
      [{ zarr: 'a.zarr', dims: [1, 1, 1] }, /dims/],
      [{ zarr: 3 }, /volume\.zarr/],
    ];
    for (const [volume, message] of bad) {
      const e = thrown(() => validateSceneDescription({ volume }));
      expect(e.code).toBe('invalid-scene');
      expect(e.message).toMatch(message);
    }
  });
});

describe('scene files: an OME-Zarr folder is served alone, confined', () => {
  let dir: string, server: StaticServer;
  const store = () => path.join(dir, 'scenes', 'img.ome.zarr');
  beforeAll(async () => {
    dir = fs.mkdtempSync(path.join(os.tmpdir(), 'vpt-zarr-files-'));
    fs.mkdirSync(path.join(store(), '0', 'c', '0', '0'), { recursive: true });
    fs.writeFileSync(path.join(store(), 'zarr.json'), '{"zarr_format":3,"node_type":"group","attributes":{}}');
    fs.writeFileSync(path.join(store(), '0', 'c', '0', '0', '0'), Buffer.alloc(8));
    fs.writeFileSync(path.join(dir, 'scenes', 'secret.txt'), 'not for the page');
    fs.writeFileSync(path.join(dir, 'outside.txt'), 'not for the page either');
    fs.symlinkSync(path.join(dir, 'outside.txt'), path.join(store(), 'escape'));
    fs.mkdirSync(path.join(dir, 'plain-folder.zarr'));
    fs.mkdirSync(path.join(dir, 'elsewhere'));
    server = await startStaticServer(null);
  });
  afterAll(async () => {
    await server.close();
    fs.rmSync(dir, { recursive: true, force: true });
  });
  const get = async (urlPath: string) => (await fetch(new URL(urlPath, server.url))).status;

  it('serves the store’s files, not its neighbours, and no symlink that leaves it', async () => {
    const d = mountSceneFiles({ volume: { zarr: 'img.ome.zarr' } }, path.join(dir, 'scenes'), server);
    const url = (d.volume as { zarr: string }).zarr;
    expect(url).toMatch(/^\/__mount\/\d+\/$/);
    expect(await get(url + 'zarr.json')).toBe(200);
    expect(await get(url + '0/c/0/0/0')).toBe(200);
    expect(await get(url + 'escape')).toBe(404);
    expect(await get(url + '../secret.txt')).toBe(404);
    expect(await get(url + '%2e%2e/secret.txt')).toBe(404);
  });

  it('refuses a folder that is not a store, and with --root stores outside it and URLs', () => {
    const scenes = path.join(dir, 'scenes');
    let e = thrown(() => resolveSceneFiles({ volume: { zarr: '../plain-folder.zarr' } }, scenes));
    expect(e.code).toBe('load-failed');
    expect(e.message).toMatch(/not a folder holding zarr\.json/);
    e = thrown(() =>
      resolveSceneFiles({ volume: { zarr: 'img.ome.zarr' } }, scenes, { root: path.join(dir, 'elsewhere') }),
    );
    expect(e.code).toBe('invalid-scene');
    expect(e.message).toMatch(/outside .* \(--root\)/);
    e = thrown(() =>
      resolveSceneFiles({ volume: { zarr: 'http://example.invalid/a.zarr' } }, scenes, { root: scenes }),
    );
    expect(e.message).toMatch(/URLs are refused/);
    const ok = resolveSceneFiles({ volume: { zarr: 'img.ome.zarr' } }, scenes, { root: scenes });
    expect((ok.volume as { zarr: string }).zarr).toBe(store());
    // Without --root a URL is left for the page to fetch.
    expect(
      (resolveSceneFiles({ volume: { zarr: 'https://x.test/a.zarr' } }, scenes).volume as { zarr: string }).zarr,
    ).toBe('https://x.test/a.zarr');
  });
});
