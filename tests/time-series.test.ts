import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { afterAll, describe, expect, it } from 'vitest';
import { rendererNames } from '../packages/core/src/index.js';
import { decodePNG, opaque } from '../packages/headless/src/image-io.js';
import { openVptPage, renderScene } from '../packages/headless/src/render.js';
import { runRender } from '../packages/headless/src/cli/render-main.js';
import { BACKENDS, usePage } from './helpers/session.js';
import { writeZarrFolder } from '../packages/loaders/test/zarr-fixtures.js';

const page = usePage();

// A time series' steps swap the context's volume: a step of the same grid and format is
// written into the texture there is (stats.volumeRewrites), and must render what that step
// alone renders in a fresh context, bit for bit, for every renderer on both backends.
describe.each(BACKENDS)('time steps on %s', (backend) => {
  it('each step renders what its volume renders alone; the volume texture is rewritten, not reallocated', async () => {
    const r = await page.run(
      async ({ core, t }, backend, names) => {
        const S = 12;
        // Step k: a blob whose values are scaled and shifted by k (different images per step).
        const base = core.createProceduralVolume('blob', S);
        const step = (k: number) => {
          const data = new Float32Array(base.data.length);
          for (let i = 0; i < data.length; i++)
            data[i] = (base.data as Float32Array)[(i + 7 * k * S) % data.length] * (1 - 0.25 * k);
          return { ...base, data, valueRange: [0, 1] as [number, number] };
        };
        const steps = [0, 1, 2].map(step);
        const scene = (v: any) =>
          t.scene({ volume: v, densityScale: 6, environment: { type: 'constant', radiance: [0.3, 0.3, 0.3] } });
        const out: Record<string, unknown> = {};
        for (const name of names) {
          const canvas = document.createElement('canvas');
          const ctx = await t.context({ backend, canvas, renderer: name, width: 12, height: 12 });
          const played: number[][] = [];
          const bytes: number[] = [];
          for (const v of steps) {
            ctx.setScene(scene(v));
            await ctx.renderIterations(2);
            played.push(Array.from(await ctx.readHDR()));
            bytes.push(ctx.stats.gpuBytes.volume);
          }
          const rewrites = ctx.stats.volumeRewrites;
          ctx.dispose();
          const alone: number[][] = [];
          for (const v of steps) {
            const c = await t.context({
              backend,
              canvas: document.createElement('canvas'),
              renderer: name,
              width: 12,
              height: 12,
            });
            c.setScene(scene(v));
            alone.push(await t.finalHDR(c, 2));
          }
          const differing = played.map((p, i) => t.sameBits(new Float32Array(p), new Float32Array(alone[i])));
          const stepsDiffer = t.sameBits(new Float32Array(alone[0]), new Float32Array(alone[1])) > 0;
          out[name] = { differing, rewrites, bytes, stepsDiffer, finite: !played.some((p) => t.hasNonFinite(p)) };
        }
        return out;
      },
      backend,
      rendererNames(),
    );
    for (const name of rendererNames()) {
      const x = r[name] as {
        differing: number[];
        rewrites: number;
        bytes: number[];
        stepsDiffer: boolean;
        finite: boolean;
      };
      expect(x.differing, name).toEqual([0, 0, 0]);
      expect(x.rewrites, name).toBe(2);
      expect(new Set(x.bytes).size, name).toBe(1);
      expect(x.finite, name).toBe(true);
    }
    // The steps are different volumes, so an equality above could fail (the slice renderer included).
    expect(rendererNames().filter((n) => (r[n] as { stepsDiffer: boolean }).stepsDiffer)).toEqual(rendererNames());
  });
});

// A 4D NIfTI and its steps as single files: vpt-render --time A:B writes one image per step,
// each the image of that step's own file.
const dir = fs.mkdtempSync(path.join(os.tmpdir(), 'vpt-time-'));
afterAll(() => fs.rmSync(dir, { recursive: true, force: true }));

const D = 10;
function stepVoxels(k: number): Uint8Array {
  const v = new Uint8Array(D * D * D);
  // A ball whose centre moves along x with the step.
  const c = [3 + 2 * k, 5, 5];
  for (let z = 0; z < D; z++)
    for (let y = 0; y < D; y++)
      for (let x = 0; x < D; x++) {
        const r = Math.hypot(x - c[0], y - c[1], z - c[2]);
        v[x + D * (y + D * z)] = Math.max(0, Math.round(255 * (1 - r / 3.5)));
      }
  return v;
}

/** A NIfTI-1 file (uint8) of these volumes along dim[4]. */
function nifti(volumes: Uint8Array[]): Uint8Array {
  const out = new Uint8Array(352 + volumes.length * D ** 3);
  const v = new DataView(out.buffer);
  v.setInt32(0, 348, true);
  [4, D, D, D, volumes.length, 1, 1, 1].forEach((d, i) => v.setInt16(40 + 2 * i, d, true));
  v.setInt16(70, 2, true); // uint8
  v.setInt16(72, 8, true);
  [1, 1, 1, 1, 0.5, 1, 1, 1].forEach((p, i) => v.setFloat32(76 + 4 * i, p, true));
  v.setFloat32(108, 352, true);
  out[123] = 2 | 8; // mm, s
  out.set([0x6e, 0x2b, 0x31, 0], 344);
  volumes.forEach((vol, k) => out.set(vol, 352 + k * D ** 3));
  return out;
}

describe('vpt-render --time', () => {
  it('--time 0:2 writes three numbered images, each the image of that step rendered alone (and of an OME-Zarr t step)', async () => {
    const steps = [0, 1, 2].map(stepVoxels);
    fs.writeFileSync(path.join(dir, 'four.nii'), nifti(steps));
    steps.forEach((s, k) => fs.writeFileSync(path.join(dir, `s${k}.raw`), s));
    const common = {
      renderer: 'mip',
      width: 24,
      height: 24,
      iterations: 2,
      backend: 'webgl2',
      transferFunction: {
        points: [
          { value: 0, color: [1, 1, 1], opacity: 0 },
          { value: 1, color: [1, 1, 1], opacity: 1 },
        ],
      },
    };
    fs.writeFileSync(path.join(dir, 'scene.json'), JSON.stringify({ ...common, volume: { file: 'four.nii' } }));
    const stdout: string[] = [],
      stderr: string[] = [];
    const code = await runRender(
      [path.join(dir, 'scene.json'), '--time', '0:2', '-o', path.join(dir, 'out', 'frame-%03d.png')],
      {
        out: (l) => stdout.push(l),
        err: (l) => stderr.push(l),
      },
    );
    expect(stderr).toEqual([]);
    expect(code).toBe(0);
    expect(fs.readdirSync(path.join(dir, 'out')).sort()).toEqual(['frame-000.png', 'frame-001.png', 'frame-002.png']);
    const line = JSON.parse(stdout[0]);
    expect(line.steps.map((s: { time: number }) => s.time)).toEqual([0, 1, 2]);
    // Each frame against the step's own raw file, and against the scene's "time" on a list of files.
    steps.forEach((_, k) =>
      fs.writeFileSync(
        path.join(dir, `s${k}.json`),
        JSON.stringify({ dims: [D, D, D], voxel_type: 'uint8', spacing: [1, 1, 1], file: `s${k}.raw` }),
      ),
    );
    // The same steps as an OME-Zarr store's t axis.
    await writeZarrFolder(path.join(dir, 't.ome.zarr'), {
      dims: [D, D, D],
      type: 'uint8',
      spacing: [1, 1, 1],
      images: steps.map((s) => [s]),
    });
    const session = await openVptPage({ root: null });
    try {
      const frames = [0, 1, 2].map((k) => decodePNG(fs.readFileSync(path.join(dir, 'out', `frame-00${k}.png`))).rgba);
      for (let k = 0; k < 3; k++) {
        const alone = await renderScene(
          { ...common, volume: { raw: `s${k}.raw`, dims: [D, D, D], type: 'uint8' } } as never,
          { baseDir: dir, session },
        );
        const listed = await renderScene(
          { ...common, time: k, volume: { timeSeries: ['s0.json', 's1.json', 's2.json'] } } as never,
          { baseDir: dir, session },
        );
        expect(Buffer.compare(Buffer.from(frames[k]), Buffer.from(opaque(alone.ldr!))), `step ${k}`).toBe(0);
        expect(Buffer.compare(Buffer.from(frames[k]), Buffer.from(opaque(listed.ldr!))), `listed step ${k}`).toBe(0);
        const zarr = await renderScene({ ...common, time: k, volume: { zarr: 't.ome.zarr' } } as never, {
          baseDir: dir,
          session,
        });
        expect(Buffer.compare(Buffer.from(frames[k]), Buffer.from(opaque(zarr.ldr!))), `zarr step ${k}`).toBe(0);
      }
      expect(Buffer.compare(Buffer.from(frames[0]), Buffer.from(frames[1]))).not.toBe(0);
    } finally {
      await session.close();
    }
    // A step past the end of the file is refused, naming it.
    const bad: string[] = [];
    expect(
      await runRender([path.join(dir, 'scene.json'), '--time', '3', '-o', path.join(dir, 'bad.png')], {
        out: () => {},
        err: (l) => bad.push(l),
      }),
    ).toBe(1);
    expect(bad.join('\n')).toMatch(/time step 3 does not exist/);
  });
});
