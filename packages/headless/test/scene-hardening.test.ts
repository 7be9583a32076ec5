import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { afterAll, beforeAll, describe, expect, it } from 'vitest';
import { EamRenderer } from '@vpt/renderer-eam';
import { MipRenderer } from '@vpt/renderer-mip';
import { IsoRenderer } from '@vpt/renderer-iso';
import { McrtRenderer } from '@vpt/renderer-mcrt';
import { mountSceneFiles, resolveSceneFiles } from '../src/scene-files.js';
import { startStaticServer, type StaticServer } from '../src/server.js';
import { validateSceneDescription } from '../src/validate-description.js';
import { thrownVptError as thrown } from '../../../tests/helpers/test-scene.js';

describe('renderer step parameters are validated where they are set', () => {
  it('EAM stepSize 1e-9, 0 and negative are refused by the constructor and by setParams', () => {
    for (const stepSize of [1e-9, 0, -0.01]) {
      expect(thrown(() => new EamRenderer({ stepSize })).message).toMatch(
        /^EAM\.stepSize: must be a number >= 0\.00001/,
      );
      const r = new EamRenderer();
      expect(thrown(() => r.setParams({ stepSize })).code).toBe('invalid-scene');
      expect(r.getParams().stepSize).toBeUndefined(); // the refused value did not stick
    }
  });
  it('MIP and ISO steps likewise; unknown keys of every renderer are refused', () => {
    expect(thrown(() => new MipRenderer({ stepSize: 0 })).message).toMatch(/MIP\.stepSize/);
    expect(thrown(() => new IsoRenderer({ stepSize: -1 })).message).toMatch(/stepSize/);
    expect(thrown(() => new EamRenderer({ stepsize: 0.01 } as never)).message).toMatch(
      /unknown key "stepsize" \(known: stepSize, cutoff, emptySpaceSkipping, sampler\)/,
    );
    expect(thrown(() => new MipRenderer({ foo: 1 } as never)).message).toMatch(/unknown key "foo"/);
    expect(thrown(() => new IsoRenderer({ foo: 1 } as never)).message).toMatch(/unknown key "foo"/);
    expect(thrown(() => new McrtRenderer({ foo: 1 } as never)).message).toMatch(/unknown key "foo"/);
    expect(thrown(() => new McrtRenderer({ maxDepth: 1e39 })).message).toMatch(
      /MCRT\.maxDepth: 1e\+39 exceeds the float32 range/,
    );
  });
});

describe('scene description validation (CLI and page)', () => {
  const cases: [string, unknown, RegExp, string?][] = [
    ['an unknown top-level key', { widht: 64 }, /scene: unknown key "widht"/],
    [
      'unknown rendererParams keys',
      { renderer: 'eam', rendererParams: { stepsize: 0.01 } },
      /EAM parameters: unknown key "stepsize"/,
    ],
    ['EAM stepSize 1e-9', { renderer: 'eam', rendererParams: { stepSize: 1e-9 } }, /EAM\.stepSize/],
    [
      'endianness "middle"',
      { volume: { raw: 'x.raw', dims: [1, 1, 1], type: 'uint16', endianness: 'middle' } },
      /volume\.endianness: must be one of "little", "big", got "middle"/,
    ],
    [
      'a light without direction',
      { lights: [{ type: 'directional', irradiance: [1, 1, 1] }] },
      /lights\[0\]\.direction: is required/,
    ],
    [
      'procedural size 100000',
      { volume: { procedural: 'sphere', size: 100000 } },
      /volume\.size: 100000 is above the limit/,
      'limit-exceeded',
    ],
    [
      'a lat-long width of 1.5',
      { environment: { type: 'latlong', width: 1.5, height: 1, data: [1, 1, 1] } },
      /environment\.width: must be an integer/,
    ],
    [
      'an environment of 1e39',
      { environment: { type: 'constant', radiance: [1e39, 1, 1] } },
      /radiance\[0\]: 1e\+39 exceeds the float32 range/,
    ],
    ['a camera at 1e39', { camera: { position: [0, 0, 1e39] } }, /position\[2\] = 1e\+39 exceeds the limit/],
    ['an unknown camera key', { camera: { fov: 1 } }, /camera: unknown key "fov"/],
    [
      'dims as strings',
      { volume: { raw: 'x.raw', dims: ['1', '1', '1'], type: 'uint8' } },
      /volume\.dims\[0\]: must be an integer/,
    ],
    [
      'an equal valueRange',
      { volume: { raw: 'x.raw', dims: [1, 1, 1], type: 'uint8', valueRange: [3, 3] } },
      /valueRange: min and max are equal/,
    ],
    ['densityScale 1e39', { densityScale: 1e39 }, /densityScale: 1e\+39 exceeds the float32 range/],
  ];
  it.each(cases)('%s', (_name, desc, pattern, code = 'invalid-scene') => {
    const e = thrown(() => validateSceneDescription(desc));
    expect(e.message).toMatch(/^Scene description: /);
    expect(e.message).toMatch(pattern);
    expect(e.code).toBe(code);
  });
  it("accepts compact's fields and an inverted valueRange (issue 12); refuses bad sampling and budgets and unknown renderers", () => {
    expect(() =>
      validateSceneDescription({
        volume: { raw: 'x.raw', dims: [1, 1, 1], type: 'int16', valueRange: [1000, -1000] },
        sampling: 'exact',
        maxGpuBytes: 1 << 20,
      }),
    ).not.toThrow();
    expect(() => validateSceneDescription({ sampling: 'fast' })).not.toThrow();
    expect(thrown(() => validateSceneDescription({ sampling: 'nearest' })).message).toMatch(
      /sampling: must be one of "fast", "exact"/,
    );
    expect(thrown(() => validateSceneDescription({ maxGpuBytes: 0 })).message).toMatch(/maxGpuBytes/);
    expect(thrown(() => validateSceneDescription({ renderer: 'pathtracer' })).message).toMatch(
      /renderer: must be one of "mip", "iso", "eam", "mcrt"/,
    );
  });
  it('accepts the gallery scenes', () => {
    for (const f of fs.readdirSync('apps/gallery/scenes').filter((n) => n.endsWith('.json'))) {
      expect(
        () => validateSceneDescription(JSON.parse(fs.readFileSync(path.join('apps/gallery/scenes', f), 'utf8'))),
        f,
      ).not.toThrow();
    }
  });
});

describe('scene files: only what the scene names is served, sizes checked from metadata first', () => {
  let dir: string, server: StaticServer;
  beforeAll(async () => {
    dir = fs.mkdtempSync(path.join(os.tmpdir(), 'vpt-files-'));
    fs.mkdirSync(path.join(dir, 'scenes'));
    fs.writeFileSync(path.join(dir, 'scenes', 'vol.raw'), Buffer.alloc(8));
    fs.writeFileSync(path.join(dir, 'scenes', 'secret.txt'), 'not for the page');
    fs.writeFileSync(path.join(dir, 'scenes', 'side.json'), JSON.stringify({ dims: [2, 2, 2], voxel_type: 'uint8' }));
    fs.writeFileSync(path.join(dir, 'scenes', 'side.raw'), Buffer.alloc(8));
    fs.writeFileSync(path.join(dir, 'outside.raw'), Buffer.alloc(8));
    server = await startStaticServer(null);
  });
  afterAll(async () => {
    await server.close();
    fs.rmSync(dir, { recursive: true, force: true });
  });

  const get = async (urlPath: string) => (await fetch(new URL(urlPath, server.url))).status;

  it('serves the named raw file, not its folder', async () => {
    const d = mountSceneFiles(
      { volume: { raw: 'vol.raw', dims: [2, 2, 2], type: 'uint8' } },
      path.join(dir, 'scenes'),
      server,
    );
    const url = (d.volume as { raw: string }).raw;
    expect(await get(url)).toBe(200);
    expect(await get(url.replace('vol.raw', 'secret.txt'))).toBe(404);
    expect(await get(url.replace('vol.raw', ''))).toBe(404);
  });
  it('serves a sidecar with its raw file and nothing else', async () => {
    const d = mountSceneFiles({ volume: { sidecar: 'side.json' } }, path.join(dir, 'scenes'), server);
    const url = (d.volume as { sidecar: string }).sidecar;
    expect(await get(url)).toBe(200);
    expect(await get(url.replace('side.json', 'side.raw'))).toBe(200);
    expect(await get(url.replace('side.json', 'vol.raw'))).toBe(404);
  });
  it('--root refuses paths outside the folder, URLs and URL paths; accepts paths inside', () => {
    const root = { root: path.join(dir, 'scenes') };
    const base = path.join(dir, 'scenes');
    expect(
      thrown(() => resolveSceneFiles({ volume: { raw: '../outside.raw', dims: [2, 2, 2], type: 'uint8' } }, base, root))
        .message,
    ).toMatch(/outside .* \(--root\)/);
    expect(
      thrown(() =>
        resolveSceneFiles({ volume: { raw: '../../../../../etc/passwd', dims: [1, 1, 1], type: 'uint8' } }, base, root),
      ).message,
    ).toMatch(/outside|not found/);
    expect(
      thrown(() =>
        resolveSceneFiles(
          { volume: { raw: 'http://example.invalid/x.raw', dims: [1, 1, 1], type: 'uint8' } },
          base,
          root,
        ),
      ).message,
    ).toMatch(/URLs are refused/);
    expect(
      thrown(() => resolveSceneFiles({ volume: { raw: '/no/such.raw', dims: [1, 1, 1], type: 'uint8' } }, base, root))
        .message,
    ).toMatch(/not found/);
    fs.symlinkSync(path.join(dir, 'outside.raw'), path.join(dir, 'scenes', 'link.raw'));
    expect(
      thrown(() => resolveSceneFiles({ volume: { raw: 'link.raw', dims: [2, 2, 2], type: 'uint8' } }, base, root))
        .message,
    ).toMatch(/outside/);
    expect(() =>
      resolveSceneFiles({ volume: { raw: 'vol.raw', dims: [2, 2, 2], type: 'uint8' } }, base, root),
    ).not.toThrow();
  });
  it('a 1.5 GiB raw file with dims [1, 1, 1] is reported from its size, without reading it', () => {
    const big = path.join(dir, 'big.raw');
    fs.writeFileSync(big, '');
    fs.truncateSync(big, 1.5 * 2 ** 30); // sparse: no 1.5 GiB is written
    const e = thrown(() => resolveSceneFiles({ volume: { raw: 'big.raw', dims: [1, 1, 1], type: 'uint8' } }, dir));
    expect(e.code).toBe('load-failed');
    expect(e.message).toMatch(/need 1 bytes, the file has 1610612736 \(1610612735 bytes past the declared size\)/);
  });
  it('a sidecar with dims as strings, an equal value_range or bad axes is refused, naming the field', () => {
    fs.writeFileSync(
      path.join(dir, 'strdims.json'),
      JSON.stringify({ dims: ['2', '2', '2'], voxel_type: 'uint8', file: 'outside.raw' }),
    );
    expect(thrown(() => resolveSceneFiles({ volume: { sidecar: 'strdims.json' } }, dir)).message).toMatch(
      /dims \["2","2","2"\] must be numbers, not strings/,
    );
    fs.writeFileSync(
      path.join(dir, 'eq.json'),
      JSON.stringify({ dims: [2, 2, 2], voxel_type: 'uint8', value_range: [5, 5], file: 'outside.raw' }),
    );
    expect(thrown(() => resolveSceneFiles({ volume: { sidecar: 'eq.json' } }, dir)).message).toMatch(
      /value_range \[5,5\] must be two different finite numbers/,
    );
    // The page's reader refuses these axes; the Node-side check, the same reader, does too.
    fs.writeFileSync(
      path.join(dir, 'axes.json'),
      JSON.stringify({ dims: [2, 2, 2], voxel_type: 'uint8', axes: 'RRS', file: 'outside.raw' }),
    );
    const e = thrown(() => resolveSceneFiles({ volume: { sidecar: 'axes.json' } }, dir));
    expect(e.code).toBe('load-failed');
    expect(e.message).toMatch(/^Sidecar .*axes\.json: sidecar axes "RRS" must be three letters/);
    // A good sidecar next to a raw file of the wrong size: the size from the file's metadata.
    fs.writeFileSync(
      path.join(dir, 'short.json'),
      JSON.stringify({ dims: [3, 2, 2], voxel_type: 'uint8', file: 'outside.raw' }),
    );
    expect(thrown(() => resolveSceneFiles({ volume: { sidecar: 'short.json' } }, dir)).message).toMatch(
      /raw file .*outside\.raw: dims \[3, 2, 2\] of uint8 need 12 bytes, the file has 8/,
    );
  });
});
