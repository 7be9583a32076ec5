import fs from 'node:fs';
import http from 'node:http';
import type { AddressInfo } from 'node:net';
import path from 'node:path';
import { afterAll, beforeAll, describe, expect, it } from 'vitest';
import { LoaderError, loadVolume, openOmeZarr, parseOmeMultiscales, splitZarrLocation } from '../src/index.js';
import { FIXTURES, expectLoaderError, fixture, sha256 } from './helpers.js';
import { openZarrStore } from '../src/zarr/store.js';
import {
  headVoxels,
  pattern,
  startFaultServer,
  tempDir,
  writeHeadZarr,
  writeZarrFolder,
  type FaultServer,
} from './zarr-fixtures.js';

const TMP = tempDir();
afterAll(() => fs.rmSync(TMP, { recursive: true, force: true }));

/** The voxel at (x, y, z) of an x-fastest array. */
const at = (data: ArrayLike<number>, dims: readonly number[], x: number, y: number, z: number) =>
  data[x + dims[0] * (y + dims[1] * z)];

describe('OME-Zarr: versions and codecs', () => {
  // Odd sizes and chunks that do not divide them: edge chunks are padded, and x/y/z mix-ups change values.
  const dims: [number, number, number] = [13, 11, 7];
  for (const version of ['0.4', '0.5'] as const)
    for (const codec of ['raw', 'gzip', 'zstd', 'blosc'] as const)
      for (const type of ['uint8', 'uint16', 'int16', 'float32'] as const) {
        it(`v${version} ${codec} ${type} decodes to the voxels written`, async () => {
          const data = pattern(dims, type, 3);
          const dir = path.join(TMP, `v${version}-${codec}-${type}.ome.zarr`);
          await writeZarrFolder(
            dir,
            { dims, type, spacing: [1, 1, 1], images: [[data]] },
            { version, codec, chunk: [4, 5, 3] },
          );
          const v = await loadVolume(dir);
          expect(v.format).toBe('ome-zarr');
          expect(v.dims).toEqual(dims);
          expect(v.type).toBe(type);
          expect(Array.from(v.data)).toEqual(Array.from(data));
          const zmeta = v.meta?.zarr as { zarrFormat: number; ngffVersion: string };
          expect(zmeta.zarrFormat).toBe(version === '0.4' ? 2 : 3);
          expect(zmeta.ngffVersion).toBe(version);
        });
      }

  it('the head copy reads back voxel for voxel, with the sidecar value_range from the omero window', async () => {
    const dir = await writeHeadZarr(path.join(TMP, 'head.ome.zarr'), { codec: 'zstd' });
    const v = await loadVolume(dir);
    expect(v.dims).toEqual([128, 128, 84]);
    expect(Buffer.from(v.data.buffer, v.data.byteOffset, v.data.byteLength).equals(Buffer.from(headVoxels()))).toBe(
      true,
    );
    expect(v.meta?.value_range).toEqual([0, 202]);
  });
});

describe('OME-Zarr: levels, regions, transforms', () => {
  const dims: [number, number, number] = [20, 12, 9];
  const data = pattern(dims, 'uint16', 1);
  let dir: string;
  beforeAll(async () => {
    dir = await writeZarrFolder(
      path.join(TMP, 'aniso.ome.zarr'),
      { dims, type: 'uint16', spacing: [0.5, 0.25, 2], images: [[data]] },
      { version: '0.5', codec: 'gzip', levels: 3, chunk: [8, 8, 4], origin: [10, -3, 1] },
    );
  });

  it('level spacing and origin follow the 2× box averages (voxel centres of each block)', async () => {
    const s = await openOmeZarr(dir);
    expect(s.levels.map((l) => l.dims)).toEqual([
      [20, 12, 9],
      [10, 6, 5],
      [5, 3, 3],
    ]);
    expect(s.levels[0].spacing).toEqual([0.5, 0.25, 2]);
    expect(s.levels[0].origin).toEqual([10, -3, 1]);
    expect(s.levels[1].spacing).toEqual([1, 0.5, 4]);
    // Level 1's first voxel averages fine voxels 0 and 1: its centre is half a fine voxel further.
    expect(s.levels[1].origin).toEqual([10.25, -2.875, 2]);
    expect(s.levels[2].origin).toEqual([10.75, -2.625, 4]);
    expect(s.levels[0].chunk).toEqual([8, 8, 4]);
  });

  it('a level-2 voxel is the mean of its 4×4×4 block of level 0 (the writer) and reads back as such', async () => {
    const s = await openOmeZarr(dir);
    const v = await s.readLevel(2);
    let sum = 0,
      n = 0;
    for (let z = 4; z < 8; z++)
      for (let y = 4; y < 8; y++) for (let x = 4; x < 8; x++, n++) sum += at(data, dims, x, y, z);
    // Two rounds of rounding 2×-means differ from one 4×-mean by at most 1.
    expect(Math.abs(at(v.data, v.dims, 1, 1, 1) - sum / n)).toBeLessThanOrEqual(1);
  });

  it('readRegion returns exactly the box, x fastest', async () => {
    const s = await openOmeZarr(dir);
    const min: [number, number, number] = [3, 2, 1],
      max: [number, number, number] = [17, 11, 8];
    const box = await s.readRegion(0, min, max);
    const size = max.map((m, i) => m - min[i]);
    expect(box.length).toBe(size[0] * size[1] * size[2]);
    for (const [x, y, z] of [
      [0, 0, 0],
      [13, 8, 6],
      [5, 3, 2],
      [13, 0, 6],
    ])
      expect(at(box, size, x, y, z)).toBe(at(data, dims, x + min[0], y + min[1], z + min[2]));
    await expectLoaderError(s.readRegion(0, [0, 0, 0], [21, 1, 1]), 'bad-header');
    await expectLoaderError(s.readRegion(3, [0, 0, 0], [1, 1, 1]), 'bad-header');
  });

  it('loadVolume takes a level by option or fragment, and the coarsest', async () => {
    expect((await loadVolume(dir, { zarr: { level: 1 } })).dims).toEqual([10, 6, 5]);
    expect((await loadVolume(`${dir}#level=2`)).dims).toEqual([5, 3, 3]);
    const coarse = await loadVolume(dir, { zarr: { level: 'coarsest' } });
    expect(coarse.dims).toEqual([5, 3, 3]);
    expect(coarse.spacing).toEqual([2, 1, 8]);
    expect(coarse.origin).toEqual([10.75, -2.625, 4]);
    expect((coarse.meta?.zarr as { levels: unknown[] }).levels).toHaveLength(3);
    await expectLoaderError(loadVolume(dir, { zarr: { level: 3 } }), 'bad-header');
  });

  it('multiscale-level transforms compose after the datasets’ own, and units convert to the x axis’s', () => {
    const attrs = {
      multiscales: [
        {
          version: '0.4',
          axes: [
            { name: 'z', type: 'space', unit: 'nanometer' },
            { name: 'y', type: 'space', unit: 'micrometer' },
            { name: 'x', type: 'space', unit: 'micrometer' },
          ],
          datasets: [
            {
              path: '0',
              coordinateTransformations: [
                { type: 'scale', scale: [500, 0.2, 0.1] },
                { type: 'translation', translation: [1000, 1, 2] },
              ],
            },
          ],
          coordinateTransformations: [{ type: 'scale', scale: [2, 3, 4] }],
        },
      ],
    };
    const ms = parseOmeMultiscales(attrs, 'test');
    expect(ms.unit).toBe('micrometer');
    // x: 0.1·4; y: 0.2·3; z: 500 nm·2 = 1 µm.
    expect(ms.datasets[0].spacing.map((s) => +s.toFixed(12))).toEqual([0.4, 0.6, 1]);
    // x: 2·4; y: 1·3; z: 1000 nm·2 = 2 µm.
    expect(ms.datasets[0].origin.map((s) => +s.toFixed(12))).toEqual([8, 3, 2]);
  });
});

describe('OME-Zarr: channel and time', () => {
  it('picks the channel and time point asked for (default the first), and refuses ones that do not exist', async () => {
    const dims: [number, number, number] = [6, 5, 4];
    const images = [0, 1].map((t) => [0, 1, 2].map((c) => pattern(dims, 'uint8', 10 * t + c)));
    for (const version of ['0.4', '0.5'] as const) {
      const dir = await writeZarrFolder(
        path.join(TMP, `tc-${version}.ome.zarr`),
        { dims, type: 'uint8', spacing: [1, 1, 1], images },
        { version, codec: 'blosc', chunk: [4, 4, 4] },
      );
      expect(Array.from((await loadVolume(dir)).data)).toEqual(Array.from(images[0][0]));
      expect(Array.from((await loadVolume(dir, { zarr: { channel: 2, time: 1 } })).data)).toEqual(
        Array.from(images[1][2]),
      );
      expect(Array.from((await loadVolume(`${dir}#channel=1&time=1`)).data)).toEqual(Array.from(images[1][1]));
      const s = await openOmeZarr(dir, { channel: 1 });
      expect(s.meta.channels).toBe(3);
      expect(s.meta.times).toBe(2);
      await expectLoaderError(loadVolume(dir, { zarr: { channel: 3 } }), 'bad-header');
      await expectLoaderError(loadVolume(dir, { zarr: { time: 2 } }), 'bad-header');
    }
  });
});

describe('OME-Zarr: bad stores give typed errors', () => {
  const dims: [number, number, number] = [8, 8, 8];
  async function store(
    name: string,
    edit: (dir: string) => void,
    version: '0.4' | '0.5' = '0.4',
    codec: 'raw' | 'gzip' = 'raw',
  ) {
    const dir = await writeZarrFolder(
      path.join(TMP, `bad-${name}.ome.zarr`),
      { dims, type: 'uint16', spacing: [1, 1, 1], images: [[pattern(dims, 'uint16')]] },
      { version, codec, chunk: [4, 4, 4] },
    );
    edit(dir);
    return dir;
  }
  const editJson = (file: string, f: (j: Record<string, any>) => void) => {
    const j = JSON.parse(fs.readFileSync(file, 'utf8'));
    f(j);
    fs.writeFileSync(file, JSON.stringify(j));
  };

  it('no store, no group, no multiscales, not JSON', async () => {
    await expectLoaderError(loadVolume(path.join(TMP, 'absent.ome.zarr')), 'not-found');
    const empty = path.join(TMP, 'empty.zarr');
    fs.mkdirSync(empty, { recursive: true });
    await expectLoaderError(loadVolume(empty), 'not-found');
    await expectLoaderError(
      loadVolume(await store('nomulti', (d) => fs.writeFileSync(path.join(d, '.zattrs'), '{}'))),
      'bad-header',
    );
    await expectLoaderError(
      loadVolume(await store('notjson', (d) => fs.writeFileSync(path.join(d, '.zattrs'), '{"multi'))),
      'bad-header',
    );
  });

  it('malformed axes and transforms name the field', async () => {
    const cases: [string, (j: Record<string, any>) => void, LoaderError['reason'], RegExp][] = [
      ['axes-missing', (j) => delete j.multiscales[0].axes, 'bad-header', /axes/],
      ['axes-2d', (j) => j.multiscales[0].axes.shift(), 'unsupported', /space axes/],
      [
        'scale-length',
        (j) => (j.multiscales[0].datasets[0].coordinateTransformations[0].scale = [1, 1]),
        'bad-header',
        /scale must be 3/,
      ],
      [
        'scale-zero',
        (j) => (j.multiscales[0].datasets[0].coordinateTransformations[0].scale = [1, 0, 1]),
        'bad-header',
        /positive/,
      ],
      [
        'affine',
        (j) => (j.multiscales[0].datasets[0].coordinateTransformations[0] = { type: 'affine', affine: [] }),
        'unsupported',
        /affine/,
      ],
      ['no-datasets', (j) => (j.multiscales[0].datasets = []), 'bad-header', /datasets/],
      ['wrong-path', (j) => (j.multiscales[0].datasets[0].path = 'nope'), 'not-found', /nope/],
    ];
    for (const [name, edit, reason, message] of cases) {
      const dir = await store(name, (d) => editJson(path.join(d, '.zattrs'), edit));
      const e = await expectLoaderError(loadVolume(dir), reason);
      expect(e.message, name).toMatch(message);
    }
  });

  it('unsupported data types and codecs, and an array whose rank does not match the axes', async () => {
    let e = await expectLoaderError(
      loadVolume(await store('int64', (d) => editJson(path.join(d, '0', '.zarray'), (j) => (j.dtype = '<i8')))),
      'unsupported',
    );
    expect(e.message).toMatch(/int64/);
    e = await expectLoaderError(
      loadVolume(
        await store('codec', (d) => editJson(path.join(d, '0', '.zarray'), (j) => (j.compressor = { id: 'snappy' }))),
      ),
      'unsupported',
    );
    expect(e.message).toMatch(/snappy/);
    await expectLoaderError(
      loadVolume(
        await store(
          'codec3',
          (d) => editJson(path.join(d, '0', 'zarr.json'), (j) => j.codecs.push({ name: 'snappy' })),
          '0.5',
        ),
      ),
      'unsupported',
    );
    await expectLoaderError(
      loadVolume(
        await store('rank', (d) =>
          editJson(path.join(d, '0', '.zarray'), (j) => ((j.shape = [1, 8, 8, 8]), (j.chunks = [1, 4, 4, 4]))),
        ),
      ),
      'bad-header',
    );
  });

  it('int8 widens to int16 and float64 narrows to float32, with a warning', async () => {
    const dir = await store('float64', (d) => {
      editJson(path.join(d, '0', '.zarray'), (j) => (j.dtype = '<f8'));
      // Rewrite the chunks as float64 of the same values.
      const src = pattern(dims, 'uint16');
      for (let cz = 0; cz < 2; cz++)
        for (let cy = 0; cy < 2; cy++)
          for (let cx = 0; cx < 2; cx++) {
            const f = new Float64Array(64);
            for (let z = 0; z < 4; z++)
              for (let y = 0; y < 4; y++)
                for (let x = 0; x < 4; x++)
                  f[x + 4 * (y + 4 * z)] = at(src, dims, cx * 4 + x, cy * 4 + y, cz * 4 + z) + 0.5;
            fs.writeFileSync(path.join(d, '0', String(cz), String(cy), String(cx)), new Uint8Array(f.buffer));
          }
    });
    const v = await loadVolume(dir);
    expect(v.type).toBe('float32');
    expect(v.data[9]).toBe(pattern(dims, 'uint16')[9] + 0.5);
    expect(String(v.meta?.warnings)).toMatch(/float64 data is read as float32/);
  });

  it('a missing chunk is the fill value by default (the Zarr spec) and an error when strict', async () => {
    const dir = await store('missing', (d) => fs.rmSync(path.join(d, '0', '1', '0', '1')));
    const e = await expectLoaderError(loadVolume(dir, { zarr: { missingChunks: 'error' } }), 'not-found');
    expect(e.message).toMatch(/chunk .*1\/0\/1 is missing/);
    const v = await loadVolume(dir);
    expect(at(v.data, dims, 5, 1, 6)).toBe(0); // inside the missing chunk (x 4–7, y 0–3, z 4–7)
    expect(at(v.data, dims, 1, 1, 6)).toBe(at(pattern(dims, 'uint16'), dims, 1, 1, 6));
  });

  it('a corrupt chunk is invalid-data, a short one truncated: never wrong voxels', async () => {
    const gz = await store(
      'corrupt',
      (d) => fs.writeFileSync(path.join(d, '0', '0', '0', '0'), new Uint8Array([31, 139, 8, 0, 1, 2, 3])),
      '0.4',
      'gzip',
    );
    await expectLoaderError(loadVolume(gz), 'invalid-data');
    const raw = await store('short', (d) => {
      const f = path.join(d, '0', '0', '0', '0');
      fs.writeFileSync(f, fs.readFileSync(f).subarray(0, 50));
    });
    await expectLoaderError(loadVolume(raw), 'truncated');
  });

  it('fragments are checked', () => {
    expect(splitZarrLocation('a.zarr#level=1&channel=2').selection).toEqual({ level: 1, channel: 2 });
    expect(() => splitZarrLocation('a.zarr#level=-1')).toThrow(LoaderError);
    expect(() => splitZarrLocation('a.zarr#zoom=1')).toThrow(/unknown fragment key/);
  });
});

describe('OME-Zarr over HTTP', () => {
  let server: FaultServer;
  let root: string;
  beforeAll(async () => {
    root = tempDir('vpt-zarr-http-');
    await writeHeadZarr(path.join(root, 'head.ome.zarr'), { version: '0.5', codec: 'gzip', levels: 2 });
    server = await startFaultServer(root);
  });
  afterAll(async () => {
    await server.close();
    fs.rmSync(root, { recursive: true, force: true });
  });
  const url = () => `${server.url}head.ome.zarr`;

  it('reads every level, counting the bytes fetched', async () => {
    server.faults.clear();
    const v = await loadVolume(url());
    expect(Buffer.from(v.data.buffer, v.data.byteOffset, v.data.byteLength).equals(Buffer.from(headVoxels()))).toBe(
      true,
    );
    const bytes = (v.meta?.zarr as { bytesRead: number }).bytesRead;
    const onDisk = fs
      .readdirSync(path.join(root, 'head.ome.zarr', '0', 'c'), { recursive: true, withFileTypes: true })
      .filter((f) => f.isFile())
      .reduce((n, f) => n + fs.statSync(path.join(f.parentPath, f.name)).size, 0);
    expect(bytes).toBeGreaterThan(onDisk); // the chunks plus the metadata
    expect(bytes).toBeLessThan(onDisk + 4096);
    expect((await loadVolume(url(), { zarr: { level: 1 } })).dims).toEqual([64, 64, 42]);
  });

  it('a 404 chunk is the fill value, or not-found when strict; a one-off 500 is retried; a truncated answer is retried and then fails', async () => {
    server.faults.clear();
    server.faults.set('/0/c/1/0/1', '404');
    expect((await loadVolume(url())).dims).toEqual([128, 128, 84]);
    await expectLoaderError(loadVolume(url(), { zarr: { missingChunks: 'error' } }), 'not-found');
    server.faults.clear();
    server.faults.set('/0/c/1/0/1', '500-once');
    expect((await loadVolume(url())).dims).toEqual([128, 128, 84]);
    server.faults.clear();
    server.faults.set('/0/c/1/0/1', 'truncate');
    const e = await expectLoaderError(loadVolume(url(), { zarr: { retries: 1 } }), 'truncated');
    expect(e.message).toMatch(/1\/0\/1/);
  });

  it('range reads (as sharded v3 arrays make) get the bytes asked for, also from a server that ignores Range', async () => {
    server.faults.clear();
    const key = '/0/c/0/0/0' as const;
    const whole = new Uint8Array(fs.readFileSync(path.join(root, 'head.ome.zarr', '0', 'c', '0', '0', '0')));
    const store = await openZarrStore(url());
    expect(Array.from((await store.getRange!(key, { offset: 3, length: 7 }))!)).toEqual(
      Array.from(whole.subarray(3, 10)),
    );
    expect(Array.from((await store.getRange!(key, { suffixLength: 5 }))!)).toEqual(Array.from(whole.subarray(-5)));
    // The same cut made here when the answer is the whole object (HTTP 200).
    const plain = http.createServer((_req, res) => res.writeHead(200, { 'content-length': whole.length }).end(whole));
    await new Promise<void>((r) => plain.listen(0, '127.0.0.1', r));
    const ignoring = await openZarrStore(`http://127.0.0.1:${(plain.address() as AddressInfo).port}/s.zarr`);
    expect(Array.from((await ignoring.getRange!(key, { offset: 3, length: 7 }))!)).toEqual(
      Array.from(whole.subarray(3, 10)),
    );
    await new Promise<void>((r) => plain.close(() => r()));
  });

  it('a query string (a signed URL) is kept on every request, the fragment never sent', async () => {
    server.faults.clear();
    server.queries.length = 0;
    const v = await loadVolume(`${url()}?token=abc#level=1`);
    expect(v.dims).toEqual([64, 64, 42]);
    expect(server.queries.length).toBeGreaterThan(3);
    expect(server.queries.every((q) => q === '?token=abc')).toBe(true);
  });

  it('a stalled chunk times out (no hang), and an abort stops the load', async () => {
    server.faults.clear();
    server.faults.set('/0/c/0/1/1', 'stall');
    const e = await expectLoaderError(loadVolume(url(), { zarr: { requestTimeoutMs: 300, retries: 0 } }), 'network');
    expect(e.message).toMatch(/timed out/);
    const abort = new AbortController();
    const p = loadVolume(url(), { signal: abort.signal, zarr: { requestTimeoutMs: 60_000 } });
    setTimeout(() => abort.abort(), 100);
    await expectLoaderError(p, 'aborted');
    server.faults.clear();
  });
});

describe('OME-Zarr progress', () => {
  it('reports chunks read out of the chunks the level spans', async () => {
    const dims: [number, number, number] = [20, 12, 9];
    const dir = await writeZarrFolder(
      path.join(TMP, 'progress.ome.zarr'),
      { dims, type: 'uint8', spacing: [1, 1, 1], images: [[pattern(dims, 'uint8')]] },
      { version: '0.4', codec: 'gzip', chunk: [8, 8, 4] },
    );
    const events: { stage: string; loaded: number; total?: number }[] = [];
    await loadVolume(dir, { onProgress: (p) => events.push(p) });
    // 3 × 2 × 3 chunks; the last event says all of them.
    expect(events.at(-1)).toEqual({ stage: 'fetch', loaded: 18, total: 18 });
    const box = await (
      await openOmeZarr(dir, { onChunks: (done, total) => events.push({ stage: 'box', loaded: done, total }) })
    ).readRegion(0, [7, 0, 0], [9, 1, 1]);
    expect(box.length).toBe(2);
    expect(events.at(-1)).toEqual({ stage: 'box', loaded: 2, total: 2 }); // x 7–8 straddles chunks 0 and 1
  });
});

describe('OME-Zarr written by zarr-python', () => {
  it("a store without its all-fill chunks (zarr-python's default) loads equal to zarr-python's own read", async () => {
    const ref = JSON.parse(new TextDecoder().decode(fixture('reference.json')))['zarr_python_sparse.ome.zarr'];
    expect(ref.chunksWritten).toBeLessThan(ref.chunksTotal); // the fixture really lacks chunks
    const v = await loadVolume(path.join(FIXTURES, 'zarr_python_sparse.ome.zarr'));
    expect(v.dims).toEqual(ref.dims);
    expect(v.type).toBe('uint16');
    expect(sha256(v.data)).toBe(ref.sha256);
    expect(v.spacing).toEqual([0.5, 1, 2]); // x, y, z from the (z, y, x) scale
    await expectLoaderError(
      loadVolume(path.join(FIXTURES, 'zarr_python_sparse.ome.zarr'), { zarr: { missingChunks: 'error' } }),
      'not-found',
    );
  });
});
