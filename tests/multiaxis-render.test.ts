import fs from 'node:fs';
import path from 'node:path';
import { afterAll, beforeAll, describe, expect, it } from 'vitest';
import type { SceneDescription } from '../packages/headless/src/index.js';
import { decodePNG, opaque } from '../packages/headless/src/image-io.js';
import { runRender } from '../packages/headless/src/cli/render-main.js';
import { tempDir } from '../packages/loaders/test/zarr-fixtures.js';
import { niftiFile, nrrdFile } from '../packages/loaders/test/helpers.js';
import { usePage } from './helpers/session.js';

// vpt-render's scene files with a volume "file" that has a channel axis (NRRD list/vector
// kinds in either order, NIfTI dim[5]) or a time axis (NRRD kinds time): the channel scene
// renders the bits of the same channels given as a list of raw files, and `time` picks the
// step that a raw file of that step renders.
const page = usePage();
const TMP = tempDir('vpt-multiaxis-render-');
afterAll(() => fs.rmSync(TMP, { recursive: true, force: true }));

const N = 12;
function blob(cx: number, cy: number, cz: number, r: number): Uint8Array {
  const d = new Uint8Array(N * N * N);
  for (let z = 0; z < N; z++)
    for (let y = 0; y < N; y++)
      for (let x = 0; x < N; x++) {
        const q = ((x + 0.5) / N - cx) ** 2 + ((y + 0.5) / N - cy) ** 2 + ((z + 0.5) / N - cz) ** 2;
        d[x + N * (y + N * z)] = Math.round(255 * Math.exp(-q / (r * r)));
      }
  return d;
}
const C0 = blob(0.4, 0.5, 0.5, 0.22),
  C1 = blob(0.62, 0.42, 0.55, 0.18);

const tf = (color: [number, number, number], opacity: number) => ({
  points: [
    { value: 0.1, color, opacity: 0 },
    { value: 1, color, opacity },
  ],
});
const red = tf([1, 0.3, 0.2], 0.8),
  green = tf([0.2, 1, 0.3], 0.9);
const twoChannels = [{ transferFunction: red }, { transferFunction: green }];

const scene = (volume: SceneDescription['volume'], extra: Partial<SceneDescription> = {}) =>
  ({
    width: 20,
    height: 16,
    renderer: 'eam',
    iterations: 2,
    backend: 'webgl2',
    sampling: 'exact',
    densityScale: 10,
    camera: { position: [0.9, 0.5, 1.6], target: [0, 0, 0], up: [0, 1, 0], fovy: 0.5 },
    volume,
    ...extra,
  }) as SceneDescription;

function bitsDiffer(a: ArrayLike<number>, b: ArrayLike<number>): number {
  const u = new Uint32Array(Float32Array.from(a).buffer),
    v = new Uint32Array(Float32Array.from(b).buffer);
  let n = 0;
  for (let i = 0; i < u.length; i++) if (u[i] !== v[i]) n++;
  return u.length === v.length ? n : -1;
}

describe('vpt-render: a volume file with a channel or time axis', () => {
  beforeAll(() => {
    fs.writeFileSync(path.join(TMP, 'c0.raw'), C0);
    fs.writeFileSync(path.join(TMP, 'c1.raw'), C1);
    const interleaved = new Uint8Array(2 * C0.length);
    for (let i = 0; i < C0.length; i++) {
      interleaved[2 * i] = C0[i];
      interleaved[2 * i + 1] = C1[i];
    }
    const planar = new Uint8Array(2 * C0.length);
    planar.set(C0);
    planar.set(C1, C0.length);
    const base = { type: 'uint8', dimension: '4', encoding: 'raw' };
    fs.writeFileSync(
      path.join(TMP, 'first.nrrd'),
      nrrdFile({ ...base, sizes: `2 ${N} ${N} ${N}`, kinds: 'vector domain domain domain' }, interleaved),
    );
    fs.writeFileSync(
      path.join(TMP, 'last.nrrd'),
      nrrdFile({ ...base, sizes: `${N} ${N} ${N} 2`, kinds: 'domain domain domain list' }, planar),
    );
    fs.writeFileSync(
      path.join(TMP, 'time.nrrd'),
      nrrdFile({ ...base, sizes: `${N} ${N} ${N} 2`, kinds: 'domain domain domain time' }, planar),
    );
    // NIfTI dim[5] = 2 components (stored planar after the one time step).
    fs.writeFileSync(
      path.join(TMP, 'vector.nii'),
      niftiFile({ dims: [5, N, N, N, 1, 2, 1, 1], datatype: 2, bitpix: 8, data: planar }),
    );
  });
  const opts = { baseDir: TMP, warmup: false };
  const raw = (f: string) => ({ raw: f, dims: [N, N, N], type: 'uint8' }) as SceneDescription['volume'];
  const rawList = { channels: [raw('c0.raw'), raw('c1.raw')] } as SceneDescription['volume'];

  it('NRRD channel first or last and NIfTI dim[5] render the bits of the raw channel list', async () => {
    const want = await page().render(scene(rawList, { channels: twoChannels }), opts);
    expect(Array.from(want.hdr).every(Number.isFinite)).toBe(true);
    for (const f of ['first.nrrd', 'last.nrrd', 'vector.nii']) {
      const got = await page().render(scene({ file: f }, { channels: twoChannels }), opts);
      expect(bitsDiffer(got.hdr, want.hdr), f).toBe(0);
      expect(got.gpuBytes.volume, f).toBe(N * N * N * 8);
    }
    // The check can fail: the channels swapped (green on channel 0) render differently.
    const swapped = await page().render(
      scene({ file: 'first.nrrd' }, { channels: [{ transferFunction: green }, { transferFunction: red }] }),
      opts,
    );
    expect(bitsDiffer(swapped.hdr, want.hdr)).toBeGreaterThan(10);
  });

  it('a channel file without channel settings is refused (typed)', async () => {
    await expect(page().render(scene({ file: 'first.nrrd' }), opts)).rejects.toThrow(/needs "channels"/);
  });

  // A translucent grey TF, so the two steps' blobs give different images.
  const grey = { transferFunction: tf([0.8, 0.8, 0.8], 0.3), densityScale: 1 };
  it('a time-axis NRRD: "time" picks the step a raw file of that step renders', async () => {
    const hdr: ArrayLike<number>[] = [];
    for (const [t, f] of [
      [0, 'c0.raw'],
      [1, 'c1.raw'],
    ] as const) {
      const got = await page().render(scene({ file: 'time.nrrd' }, { ...grey, time: t }), opts);
      const want = await page().render(scene(raw(f), grey), opts);
      expect(bitsDiffer(got.hdr, want.hdr), `step ${t}`).toBe(0);
      hdr.push(got.hdr);
    }
    expect(bitsDiffer(hdr[0], hdr[1])).toBeGreaterThan(10);
    await expect(page().render(scene({ file: 'time.nrrd' }, { time: 2 }), opts)).rejects.toThrow(
      /time step 2 does not exist/,
    );
  });

  it('vpt-render --time 0:1 on a time-axis NRRD writes each step, equal to the step rendered with "time"', async () => {
    const common = scene({ file: 'time.nrrd' }, grey);
    fs.writeFileSync(path.join(TMP, 'time-scene.json'), JSON.stringify(common));
    const stderr: string[] = [];
    const code = await runRender(
      [path.join(TMP, 'time-scene.json'), '--time', '0:1', '-o', path.join(TMP, 'out', 'step-%03d.png')],
      { out: () => {}, err: (l) => stderr.push(l) },
    );
    expect(stderr).toEqual([]);
    expect(code).toBe(0);
    const frames = [0, 1].map((k) => decodePNG(fs.readFileSync(path.join(TMP, 'out', `step-00${k}.png`))).rgba);
    for (const k of [0, 1]) {
      const alone = await page().render(scene({ file: 'time.nrrd' }, { ...grey, time: k }), opts);
      expect(Buffer.from(frames[k]).equals(Buffer.from(opaque(alone.ldr!))), `step ${k}`).toBe(true);
    }
    expect(Buffer.from(frames[0]).equals(Buffer.from(frames[1]))).toBe(false);
  });
});
