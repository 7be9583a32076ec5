import zlib from 'node:zlib';
import { describe, expect, it } from 'vitest';
import { loadVolume } from '../src/index.js';
import {
  bytesIn,
  concatBytes,
  expectLoaderError,
  fileOf,
  fixture,
  niftiFile,
  normalizedChecksum,
  sha256,
} from './helpers.js';

const ANAT = 'mri_brain_nibabel_anatomical';
const ANISO = 'mri_brain_dipy_aniso_vox';
const sidecar = (name: string) => JSON.parse(new TextDecoder().decode(fixture(`${name}.json`)));

describe('NIfTI-1: the real samples against their raw twins', () => {
  it('the big-endian nibabel anatomical.nii equals its little-endian raw twin', async () => {
    const meta = sidecar(`${ANAT}_33x41x25_int16`);
    const v = await loadVolume(fileOf(fixture(`${ANAT}.nii`), `${ANAT}.nii`));
    const twin = await loadVolume(fixture(`${ANAT}_33x41x25_int16.raw`), { raw: { dims: meta.dims, type: 'int16' } });
    expect(v.format).toBe('nifti');
    expect(v.meta?.littleEndian).toBe(false);
    expect(v.dims).toEqual(meta.dims);
    expect(v.spacing).toEqual(meta.spacing);
    expect(v.type).toBe('int16');
    expect(sha256(v.data)).toBe(meta.sha256);
    expect(normalizedChecksum(v)).toBe(normalizedChecksum(twin));
    // Orientation: the sidecar (written by nibabel) names the axis codes.
    expect(meta.orientation).toBe(`NIfTI axis codes ${v.meta?.axisCodes}`);
    expect(v.meta?.axisCodes).toBe('LAS');
    expect(v.orientation).toEqual([-1, 0, 0, 0, 1, 0, 0, 0, 1]);
  });

  it('the gzip-compressed dipy aniso_vox.nii.gz equals its raw twin, anisotropic spacing included', async () => {
    const meta = sidecar(`${ANISO}_58x58x24_int16`);
    const v = await loadVolume(fileOf(fixture(`${ANISO}.nii.gz`), `${ANISO}.nii.gz`));
    expect(v.dims).toEqual(meta.dims);
    expect(v.spacing).toEqual(meta.spacing);
    expect(sha256(v.data)).toBe(meta.sha256);
    expect(meta.orientation).toBe(`NIfTI axis codes ${v.meta?.axisCodes}`);
    // Direction cosines are unit columns, and the matrix is a rotation (up to a reflection).
    const o = v.orientation!;
    for (let c = 0; c < 3; c++) expect(Math.hypot(o[c], o[3 + c], o[6 + c])).toBeCloseTo(1, 6);
    expect(o[0] * o[1] + o[3] * o[4] + o[6] * o[7]).toBeCloseTo(0, 4);
  });

  it('is found by its magic bytes when the name says nothing', async () => {
    const v = await loadVolume(fixture(`${ANISO}.nii.gz`).buffer as ArrayBuffer);
    expect(v.format).toBe('nifti');
    expect(v.dims).toEqual([58, 58, 24]);
  });
});

describe('NIfTI-1: header features', () => {
  const values = new Int16Array([0, 10, -20, 30, 400, -500, 6000, 7]);
  const base = { dims: [2, 2, 2], datatype: 4, bitpix: 16 };

  it('applies scl_slope/scl_inter: fractional slopes give float32, integer ones keep an integer type', async () => {
    const half = await loadVolume(niftiFile({ ...base, data: bytesIn(values, true), slope: 0.5, inter: 1 }));
    expect(half.type).toBe('float32');
    expect(Array.from(half.data)).toEqual(Array.from(values, (x) => x * 0.5 + 1));
    const u = new Uint16Array([0, 100, 1024, 4095, 2, 3, 4, 5]);
    const ct = await loadVolume(
      niftiFile({ dims: [2, 2, 2], datatype: 512, bitpix: 16, data: bytesIn(u, true), slope: 1, inter: -1024 }),
    );
    expect(ct.type).toBe('int16');
    expect(Array.from(ct.data)).toEqual(Array.from(u, (x) => x - 1024));
    const none = await loadVolume(niftiFile({ ...base, data: bytesIn(values, true), slope: 0, inter: 5 }));
    expect(Array.from(none.data)).toEqual(Array.from(values)); // slope 0 means "unscaled"
  });

  it('little- and big-endian float32 files give the same volume; NaN is counted, not fatal', async () => {
    const f = new Float32Array([1.5, -2.25, NaN, 1e-3, 4, 5, 6, Infinity]);
    const le = await loadVolume(niftiFile({ dims: [2, 2, 2], datatype: 16, bitpix: 32, data: bytesIn(f, true) }));
    const be = await loadVolume(
      niftiFile({ dims: [2, 2, 2], datatype: 16, bitpix: 32, data: bytesIn(f, false), littleEndian: false }),
    );
    expect(Array.from(le.data)).toEqual(Array.from(f));
    expect(Array.from(be.data)).toEqual(Array.from(f));
    expect(le.meta?.nonFiniteCount).toBe(2);
  });

  it('converts int8, uint32 and float64 to core types exactly where they fit', async () => {
    const i8 = await loadVolume(
      niftiFile({ dims: [2, 2, 1], datatype: 256, bitpix: 8, data: new Uint8Array([0xff, 1, 0x80, 0x7f]) }),
    );
    expect(i8.type).toBe('int16');
    expect(Array.from(i8.data)).toEqual([-1, 1, -128, 127]);
    const u32 = await loadVolume(
      niftiFile({ dims: [2, 1, 1], datatype: 768, bitpix: 32, data: bytesIn(new Uint32Array([5, 100000]), true) }),
    );
    expect(u32.type).toBe('float32');
    expect(Array.from(u32.data)).toEqual([5, 100000]);
    const small32 = await loadVolume(
      niftiFile({ dims: [2, 1, 1], datatype: 8, bitpix: 32, data: bytesIn(new Int32Array([-5, 30000]), true) }),
    );
    expect(small32.type).toBe('int16');
    const f64 = await loadVolume(
      niftiFile({
        dims: [2, 1, 1],
        datatype: 64,
        bitpix: 64,
        data: bytesIn(new Float64Array([0.1, 1e300]), false),
        littleEndian: false,
      }),
    );
    expect(Array.from(f64.data)).toEqual([Math.fround(0.1), Infinity]);
    expect(f64.meta?.nonFiniteCount).toBe(1); // 1e300 does not fit a float32
  });

  it('orientation: the qform quaternion when there is no sform, the sform when there is', async () => {
    // quaternion (b, c, d) = (0, 0, sin 45°): a 90° rotation about z; qfac = -1 flips k.
    const s = Math.SQRT1_2;
    const q = await loadVolume(
      niftiFile({
        ...base,
        data: bytesIn(values, true),
        qformCode: 1,
        quatern: [0, 0, s],
        qoffset: [10, 20, 30],
        pixdim: [-1, 2, 3, 4, 1, 1, 1, 1],
      }),
    );
    expect(q.meta?.xform).toBe('qform');
    expect(q.spacing).toEqual([2, 3, 4]);
    const expected = [0, -1, 0, 1, 0, 0, 0, 0, -1];
    q.orientation!.forEach((x, i) => expect(x).toBeCloseTo(expected[i], 6));
    expect(q.origin).toEqual([10, 20, 30]);
    const both = await loadVolume(
      niftiFile({
        ...base,
        data: bytesIn(values, true),
        qformCode: 1,
        quatern: [0, 0, s],
        sformCode: 2,
        srow: [
          [0, 0, 3, -1],
          [2, 0, 0, -2],
          [0, 5, 0, -3],
        ],
      }),
    );
    expect(both.meta?.xform).toBe('sform');
    expect(both.orientation).toEqual([0, 0, 1, 1, 0, 0, 0, 1, 0]);
    expect(both.origin).toEqual([-1, -2, -3]);
    expect(both.meta?.axisCodes).toBe('ASR');
  });

  it('loads the first volume of a 4D file and says so', async () => {
    const four = new Int16Array(8).map((_, i) => i);
    const v = await loadVolume(
      niftiFile({ dims: [4, 2, 2, 1, 2, 1, 1, 1], datatype: 4, bitpix: 16, data: bytesIn(four, true) }),
    );
    expect(v.dims).toEqual([2, 2, 1]);
    expect(Array.from(v.data)).toEqual([0, 1, 2, 3]);
    expect(String(v.meta?.warnings)).toMatch(/2 volumes/);
  });
});

describe('NIfTI-1: bad input', () => {
  const good = () => niftiFile({ dims: [2, 2, 2], datatype: 4, bitpix: 16, data: new Uint8Array(16) });
  const edit = (f: (v: DataView, b: Uint8Array) => void) => {
    const b = good();
    f(new DataView(b.buffer), b);
    return b;
  };

  it('truncated data, a truncated header, a truncated or corrupt gzip', async () => {
    const cut = await expectLoaderError(loadVolume(good().subarray(0, 360), { format: 'nifti' }), 'truncated');
    expect(cut.message).toMatch(/needs 16 bytes but only 8/);
    await expectLoaderError(loadVolume(good().subarray(0, 200), { format: 'nifti' }), 'truncated');
    const gz = new Uint8Array(zlib.gzipSync(fixture('mri_brain_nibabel_anatomical.nii')));
    await expectLoaderError(loadVolume(gz.subarray(0, gz.length - 3000)), 'truncated');
    const corrupt = gz.slice();
    for (let i = 200; i < 260; i++) corrupt[i] ^= 0x5a;
    const e = await loadVolume(corrupt).catch((x) => x);
    expect(['invalid-data', 'truncated']).toContain(e.reason);
  });

  it('lying headers: zero dims, overflowing dims, unknown or unsupported types, a bad vox_offset, wrong magic, NIfTI-2', async () => {
    await expectLoaderError(loadVolume(edit((v) => v.setInt16(44, 0, true))), 'empty');
    const big = await expectLoaderError(
      loadVolume(
        edit((v) => {
          v.setInt16(42, 32767, true);
          v.setInt16(44, 32767, true);
          v.setInt16(46, 32767, true);
        }),
      ),
      'overflow',
    );
    expect(big.message).toMatch(/32767 × 32767 × 32767/);
    // Not an overflow but far more data than the file holds: the header lies about dims.
    await expectLoaderError(loadVolume(edit((v) => v.setInt16(42, 1000, true))), 'truncated');
    await expectLoaderError(loadVolume(edit((v) => v.setInt16(42, -3, true))), 'bad-header');
    // RGB24 (128) is read as 3 channels (multiaxis.test.ts): a file of too few bytes for its colours is cut short.
    await expectLoaderError(loadVolume(edit((v) => v.setInt16(70, 128, true))), 'truncated');
    await expectLoaderError(loadVolume(edit((v) => v.setInt16(70, 32, true))), 'unsupported');
    await expectLoaderError(loadVolume(edit((v) => v.setInt16(70, 3, true))), 'bad-header');
    await expectLoaderError(loadVolume(edit((v) => v.setFloat32(108, NaN, true))), 'bad-header');
    await expectLoaderError(loadVolume(edit((v) => v.setInt16(40, 9, true))), 'bad-header');
    await expectLoaderError(
      loadVolume(
        edit((_, b) => {
          b[345] = 0x69;
        }),
      ),
      'unsupported',
    ); // "ni1": a .hdr/.img pair
    await expectLoaderError(
      loadVolume(
        edit((_, b) => {
          b[344] = 0x78;
        }),
        { format: 'nifti' },
      ),
      'bad-magic',
    );
    // sizeof_hdr 540 says NIfTI-2, whose header this NIfTI-1 file does not hold.
    await expectLoaderError(
      loadVolume(
        edit((v) => v.setInt32(0, 540, true)),
        { format: 'nifti' },
      ),
      'truncated',
    );
    await expectLoaderError(
      loadVolume(
        edit((v) => v.setInt32(0, 1234, true)),
        { format: 'nifti' },
      ),
      'bad-magic',
    );
    // dims past the texture limit in a file far too short for them: the missing data is the finding.
    const lying = await expectLoaderError(
      loadVolume(
        edit((v) => {
          v.setInt16(42, 3000, true);
        }),
        { limits: { maxTextureDimension3D: 2048 } },
      ),
      'truncated',
    );
    expect(lying.message).toContain('the file is cut short, or its header gives the wrong dims or type');
  });

  it('a gzip NIfTI whose header announces more than the limits stops before inflating the rest', async () => {
    const hdr = niftiFile({ dims: [512, 512, 512], datatype: 16, bitpix: 32, data: new Uint8Array(0) });
    const gz = new Uint8Array(zlib.gzipSync(hdr));
    const e = await expectLoaderError(loadVolume(gz, { limits: { maxBytes: 1 << 20 } }), 'limit');
    expect(e.message).toContain('maxBytes = 1048576');
  });
});

/** Reference voxels from nibabel (fixtures/make_reference.py). */
const reference = JSON.parse(new TextDecoder().decode(fixture('reference.json'))) as Record<
  string,
  { dims: number[]; sha256: string; affine: number[][] }
>;

/** world = orientation · (index ∘ spacing) + origin, the LoadedVolume contract. */
function worldOf(v: { orientation?: number[]; spacing: number[]; origin?: number[] }, ijk: number[]): number[] {
  const o = v.orientation!;
  const s = ijk.map((x, i) => x * v.spacing[i]);
  return [0, 1, 2].map((r) => o[3 * r] * s[0] + o[3 * r + 1] * s[1] + o[3 * r + 2] * s[2] + v.origin![r]);
}

describe('NIfTI: what other writers produce', () => {
  const values = new Int16Array(24).map((_, i) => i - 5);
  const base = { dims: [4, 3, 2], datatype: 4, bitpix: 16, data: bytesIn(values, true) };

  it('an sform whose column lengths differ from pixdim, or that is sheared, places voxels exactly where the sform does', async () => {
    for (const srow of [
      [
        [0, 0, 3, -1],
        [2, 0, 0, -2],
        [0, 5, 0, -3],
      ],
      [
        [2, 1, 0, 4],
        [0, 2, 0.5, 5],
        [0, 0, 3, 6],
      ],
    ]) {
      // pixdim says 1 mm everywhere; the sform says otherwise, and wins (nibabel's affine).
      const v = await loadVolume(niftiFile({ ...base, sformCode: 1, srow, pixdim: [1, 1, 1, 1, 1, 1, 1, 1] }));
      for (const ijk of [
        [0, 0, 0],
        [3, 2, 1],
        [1, 2, 0],
      ]) {
        const expected = srow.map((row) => row[0] * ijk[0] + row[1] * ijk[1] + row[2] * ijk[2] + row[3]);
        worldOf(v, ijk).forEach((x, r) => expect(x).toBeCloseTo(expected[r], 5));
      }
      expect(String(v.meta?.warnings)).toMatch(/pixdim \[1, 1, 1\] differs from the sform/);
    }
    const sheared = await loadVolume(
      niftiFile({
        ...base,
        sformCode: 1,
        srow: [
          [2, 1, 0, 0],
          [0, 2, 0, 0],
          [0, 0, 3, 0],
        ],
      }),
    );
    expect(String(sheared.meta?.warnings)).toMatch(/sform is sheared/);
  });

  it('int32 and uint32 data beyond ±2^24 say that they round as float32; within 16 bits they stay exact', async () => {
    const big = new Int32Array([0, (1 << 24) + 1, -5, 7]);
    const v = await loadVolume(niftiFile({ dims: [4, 1, 1], datatype: 8, bitpix: 32, data: bytesIn(big, true) }));
    expect(v.type).toBe('float32');
    expect(Array.from(v.data)).toEqual(Array.from(big).map(Math.fround));
    expect(String(v.meta?.warnings)).toMatch(/int32 data is read as float32.*2\^24 round/);
    const u = await loadVolume(
      niftiFile({ dims: [2, 1, 1], datatype: 768, bitpix: 32, data: bytesIn(new Uint32Array([1, 2 ** 31]), true) }),
    );
    expect(String(u.meta?.warnings)).toMatch(/uint32 data is read as float32/);
    const small = await loadVolume(
      niftiFile({ dims: [2, 1, 1], datatype: 8, bitpix: 32, data: bytesIn(new Int32Array([-3, 30000]), true) }),
    );
    expect(small.type).toBe('int16');
    expect(small.meta?.warnings).toBeUndefined();
  });

  it('a NaN scl_inter with a valid scl_slope is refused (nibabel refuses it too), not read as 0', async () => {
    const e = await expectLoaderError(loadVolume(niftiFile({ ...base, slope: 2, inter: NaN })), 'bad-header');
    expect(e.message).toMatch(/scl_inter = NaN/);
  });

  it('a 4D .nii.gz says it holds several volumes, and nothing about bytes past the data', async () => {
    const two = new Int16Array(48).map((_, i) => i);
    const gz = new Uint8Array(
      zlib.gzipSync(niftiFile({ dims: [4, 4, 3, 2, 2, 1, 1, 1], datatype: 4, bitpix: 16, data: bytesIn(two, true) })),
    );
    const v = await loadVolume(fileOf(gz, 'four.nii.gz'));
    expect(Array.from(v.data)).toEqual(Array.from(two.subarray(0, 24)));
    expect(v.meta?.warnings).toEqual([
      'the file holds 2 volumes along dim[4] (time); volume 0 is loaded (LoadOptions.time picks the time step)',
    ]);
    // Bytes past the whole declared 4D data are still said.
    const padded = new Uint8Array(
      zlib.gzipSync(
        niftiFile({
          dims: [4, 4, 3, 2, 2, 1, 1, 1],
          datatype: 4,
          bitpix: 16,
          data: concatBytes([bytesIn(two, true), new Uint8Array(10)]),
        }),
      ),
    );
    const w = await loadVolume(fileOf(padded, 'padded.nii.gz'));
    expect(String(w.meta?.warnings)).toMatch(/10 inflated bytes past the data/);
  });

  it('NIfTI-2 (a gzip .nii written by nibabel) loads equal to nibabel, placed by its double-precision sform', async () => {
    const ref = reference['nibabel_nifti2.nii.gz'];
    const v = await loadVolume(fileOf(fixture('nibabel_nifti2.nii.gz'), 'nibabel_nifti2.nii.gz'));
    expect(v.meta?.niftiVersion).toBe(2);
    expect(v.dims).toEqual(ref.dims);
    expect(v.type).toBe('float32');
    expect(sha256(v.data)).toBe(ref.sha256);
    for (const ijk of [
      [0, 0, 0],
      [3, 2, 1],
    ]) {
      const expected = ref.affine
        .slice(0, 3)
        .map((row) => row[0] * ijk[0] + row[1] * ijk[1] + row[2] * ijk[2] + row[3]);
      worldOf(v, ijk).forEach((x, r) => expect(x).toBeCloseTo(expected[r], 9));
    }
    // Cut inside its 540-byte header: truncated, not misread as NIfTI-1.
    const plain = new Uint8Array(zlib.gunzipSync(fixture('nibabel_nifti2.nii.gz')));
    await expectLoaderError(loadVolume(plain.subarray(0, 500), { format: 'nifti' }), 'truncated');
  });

  it('a .hdr/.img pair written by nibabel loads as one volume, equal to nibabel voxel for voxel', async () => {
    const ref = reference['nibabel_pair.hdr'];
    const files = [
      fileOf(fixture('nibabel_pair.hdr'), 'nibabel_pair.hdr'),
      fileOf(fixture('nibabel_pair.img'), 'nibabel_pair.img'),
    ];
    for (const list of [files, [...files].reverse()]) {
      const v = await loadVolume(list);
      expect(v.format).toBe('nifti');
      expect(v.dims).toEqual(ref.dims);
      expect(sha256(v.data)).toBe(ref.sha256);
      expect(v.meta?.warnings).toBeUndefined();
      for (const ijk of [
        [0, 0, 0],
        [4, 3, 2],
      ]) {
        const expected = ref.affine
          .slice(0, 3)
          .map((row) => row[0] * ijk[0] + row[1] * ijk[1] + row[2] * ijk[2] + row[3]);
        worldOf(v, ijk).forEach((x, r) => expect(x).toBeCloseTo(expected[r], 5));
      }
    }
    // The header alone names what is missing; Analyze 7.5 (no magic) is refused by name.
    const alone = await expectLoaderError(loadVolume([files[0]]), 'not-found');
    expect(alone.message).toContain('nibabel_pair.img');
    const analyze = fixture('nibabel_pair.hdr').slice();
    analyze.fill(0, 344, 348);
    const a = await expectLoaderError(loadVolume([fileOf(analyze, 'old.hdr'), files[1]]), 'unsupported');
    expect(a.message).toMatch(/Analyze 7\.5/);
  });
});
