import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import { afterAll, beforeAll, describe, expect, it } from 'vitest';
import { thrownVptError as thrown } from '../../../tests/helpers/test-scene.js';
import { chromiumExecutable } from '../src/chromium.js';
import { openVptPage, type VptPageSession } from '../src/render.js';
import { mountSceneFiles, resolveSceneFiles } from '../src/scene-files.js';
import { startStaticServer, type StaticServer } from '../src/server.js';
import { validateSceneDescription } from '../src/validate-description.js';
import { checkSceneDescription, type FileVolumeDescription, type SceneDescription } from '../src/scene-description.js';

const LOADER_FIXTURES = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '../../loaders/test/fixtures');

describe('scene descriptions name a volume file of any format', () => {
  it('accepts a file, a list, a format and a valueRange', () => {
    for (const volume of [
      { file: 'brain.nii.gz' },
      { file: ['a.nhdr', 'a.raw'], format: 'nrrd' },
      { file: 'series/', format: 'dicom', valueRange: [0, 4095] },
    ]) {
      expect(() => validateSceneDescription({ volume })).not.toThrow();
      expect(() => checkSceneDescription({ volume })).not.toThrow();
    }
  });
  it('refuses bad fields, naming them', () => {
    const bad: [Record<string, unknown>, RegExp][] = [
      [{ file: '' }, /volume\.file/],
      [{ file: [] }, /volume\.file/],
      [{ file: ['a.dcm', 3] }, /volume\.file\[1\]/],
      [{ file: 'a.nii', format: 'analyze' }, /volume\.format/],
      [{ file: 'a.nii', valueRange: [1, 1] }, /volume\.valueRange/],
      [{ file: 'a.nii', dims: [1, 1, 1] }, /dims/],
    ];
    for (const [volume, message] of bad) {
      const e = thrown(() => validateSceneDescription({ volume }));
      expect(e.code).toBe('invalid-scene');
      expect(e.message).toMatch(message);
    }
  });
});

describe('scene files: a volume file is served with exactly the files its loader reads', () => {
  let dir: string, server: StaticServer;
  const scenes = () => path.join(dir, 'scenes');
  beforeAll(async () => {
    dir = fs.mkdtempSync(path.join(os.tmpdir(), 'vpt-file-volume-'));
    fs.mkdirSync(path.join(scenes(), 'series', 'sub'), { recursive: true });
    fs.writeFileSync(path.join(scenes(), 'brain.nii.gz'), 'x');
    fs.writeFileSync(path.join(scenes(), 'pair.hdr'), 'x');
    fs.writeFileSync(path.join(scenes(), 'pair.img'), 'x');
    fs.writeFileSync(path.join(scenes(), 'ball.nhdr'), 'NRRD0004\ntype: short\ndata file: ball.raw.gz\n\n');
    fs.writeFileSync(path.join(scenes(), 'ball.raw.gz'), 'x');
    fs.writeFileSync(path.join(scenes(), 'far.nhdr'), 'NRRD0004\ndata file: ../far.raw\n\n');
    fs.writeFileSync(path.join(scenes(), 'lost.hdr'), 'x');
    fs.writeFileSync(path.join(scenes(), 'series', 'a.dcm'), 'x');
    fs.writeFileSync(path.join(scenes(), 'series', 'sub', 'b.dcm'), 'x');
    fs.writeFileSync(path.join(scenes(), 'series', '.DS_Store'), 'x');
    fs.writeFileSync(path.join(scenes(), 'secret.txt'), 'not for the page');
    fs.writeFileSync(path.join(dir, 'outside.nii'), 'x');
    server = await startStaticServer(null);
  });
  afterAll(async () => {
    await server.close();
    fs.rmSync(dir, { recursive: true, force: true });
  });
  const status = async (urlPath: string) => (await fetch(new URL(urlPath, server.url))).status;
  const mounted = (volume: FileVolumeDescription) =>
    mountSceneFiles({ volume }, scenes(), server).volume as FileVolumeDescription;

  it('a .nii.gz alone; an .hdr with its .img; an .nhdr with its data file; never their neighbours', async () => {
    for (const [file, companion] of [
      ['brain.nii.gz', undefined],
      ['pair.hdr', 'pair.img'],
      ['ball.nhdr', 'ball.raw.gz'],
    ] as const) {
      const url = mounted({ file }).file as string;
      expect(url).toMatch(new RegExp(`^/__files/\\d+/${file.replace('.', '\\.')}$`));
      expect(await status(url)).toBe(200);
      const folder = url.slice(0, url.lastIndexOf('/') + 1);
      if (companion) expect(await status(folder + companion)).toBe(200);
      expect(await status(folder + 'secret.txt')).toBe(404);
      expect(await status(folder + 'brain.nii.gz')).toBe(file === 'brain.nii.gz' ? 200 : 404);
    }
  });

  it('a folder is a DICOM series: every file under it, hidden ones skipped, as a list of URLs', async () => {
    const urls = mounted({ file: 'series' }).file as string[];
    expect(urls.map((u) => u.split('/').pop())).toEqual(['a.dcm', 'b.dcm']);
    for (const u of urls) expect(await status(u)).toBe(200);
    const folder = urls[0].slice(0, urls[0].lastIndexOf('/') + 1);
    expect(await status(folder + '.DS_Store')).toBe(404);
  });

  it('an OME-Zarr folder named by volume.file is served alone and read as ome-zarr', async () => {
    fs.mkdirSync(path.join(scenes(), 'img'), { recursive: true });
    fs.writeFileSync(path.join(scenes(), 'img', 'zarr.json'), '{}');
    const v = mounted({ file: 'img' });
    expect(v.format).toBe('ome-zarr');
    expect(v.file).toMatch(/^\/__mount\/\d+\/$/);
    expect(await status((v.file as string) + 'zarr.json')).toBe(200);
  });

  it('missing files and companions fail before a browser starts; --root confines every file served', () => {
    const resolve = (volume: FileVolumeDescription, root?: string) =>
      thrown(() => resolveSceneFiles({ volume } as SceneDescription, scenes(), { root }));
    expect(resolve({ file: 'nope.nii' })).toMatchObject({
      code: 'load-failed',
      message: expect.stringMatching(/nope\.nii/),
    });
    expect(resolve({ file: 'lost.hdr' }).message).toMatch(/lost\.img/);
    expect(resolve({ file: 'far.nhdr' })).toMatchObject({
      code: 'invalid-scene',
      message: expect.stringMatching(/another folder/),
    });
    expect(resolve({ file: '../outside.nii' }, scenes()).message).toMatch(/outside .*--root/);
    expect(resolve({ file: 'http://example.invalid/a.nii' }, scenes()).message).toMatch(/URLs are refused/);
    const inside = resolveSceneFiles({ volume: { file: 'brain.nii.gz' } }, scenes(), { root: scenes() });
    expect((inside.volume as FileVolumeDescription).file).toBe(path.join(scenes(), 'brain.nii.gz'));
  });
});

describe.skipIf(!fs.existsSync(chromiumExecutable()))('vpt-render: a scene names a .nii.gz', () => {
  let session: VptPageSession;
  beforeAll(async () => {
    session = await openVptPage({ root: null });
  }, 120_000);
  afterAll(async () => {
    await session?.close();
  });

  it('renders the gzip NIfTI exactly as its raw twin with a sidecar (same voxels, same image)', async () => {
    const scene = (volume: SceneDescription['volume']): SceneDescription => ({
      width: 16,
      height: 16,
      renderer: 'mip',
      iterations: 2,
      backend: 'webgl2',
      environment: { type: 'constant', radiance: [0, 0, 0] },
      volume,
    });
    const opts = { baseDir: LOADER_FIXTURES };
    const nifti = await session.render(scene({ file: 'mri_brain_dipy_aniso_vox.nii.gz' }), opts);
    const twin = await session.render(scene({ sidecar: 'mri_brain_dipy_aniso_vox_58x58x24_int16.json' }), opts);
    expect(nifti.volumeDims).toEqual([58, 58, 24]);
    expect(twin.volumeDims).toEqual([58, 58, 24]);
    let lit = 0;
    for (let i = 0; i < twin.hdr.length; i += 4) if (twin.hdr[i] > 0) lit++;
    expect(lit).toBeGreaterThan(16); // the brain shows, so equal images mean something
    expect(Array.from(nifti.hdr)).toEqual(Array.from(twin.hdr));
  }, 180_000);

  it('a .hdr fetches its .img, an .nhdr its detached gzip data file, both served beside it', async () => {
    const scene = (file: string): SceneDescription => ({
      width: 8,
      height: 8,
      renderer: 'mip',
      iterations: 1,
      backend: 'webgl2',
      volume: { file },
    });
    const opts = { baseDir: LOADER_FIXTURES };
    expect((await session.render(scene('nibabel_pair.hdr'), opts)).volumeDims).toEqual([5, 4, 3]);
    const ball = await session.render(scene('pynrrd/BallBinary30x30x30_byteskip_minus_one_nifti.nhdr'), opts);
    expect(ball.volumeDims).toEqual([30, 30, 30]);
  }, 180_000);
});
