#!/usr/bin/env python3
"""Reference voxels for the loaders' corpus test, from the projects' own readers.

Run after `pnpm corpus:fetch`, in a Python with the pinned readers:

    python3 -m venv /tmp/refs && /tmp/refs/bin/pip install numpy nibabel==5.4.2 pydicom==3.0.2 pynrrd==1.1.3
    /tmp/refs/bin/python packages/loaders/test/corpus/make_references.py

It walks data/corpus/ and writes references.json beside this script: for every file vpt
claims (DICOM by its "DICM" preamble or a .dcm name, NIfTI by .nii / .nii.gz / .hdr, NRRD by
.nrrd / .nhdr) either

  {"load": {"dims", "sha256", "min", "max", "spacing"?, "origin"?, "rowCol"?, "direction"?}, "reader"}
or
  {"refuse": [reasons], "why", "reader", "indices"?}

("indices": for PALETTE COLOR, the stored indices' checksum, as for a load)

and, for each folder of pydicom's dicomdirtests (key "folder/"), the same for its files
loaded together as one series (its largest series, sorted along the slice normal, spacing
the mean gap of the positions), where that series is not tied with another.

Comparison rule (the test applies the same): the voxel values as float32, x (DICOM columns,
NIfTI i) fastest, then y, then z, NaN written as the one quiet NaN 0x7fc00000, hashed as
little-endian bytes. Integer outputs up to 2^24 are exact in float32, and vpt computes a
fractional rescale in float64 before rounding to float32, as numpy does here.
- DICOM: pydicom's pixel_array (BitsStored, byte order, 8-bit OW swapping) through
  pydicom's apply_modality_lut (Rescale Slope/Intercept, Modality LUT Sequence). For an
  enhanced (multi-frame) file the rescale of each frame is its Pixel Value Transformation
  functional group (per-frame over shared over the top level, PS3.3 C.7.6.16), frames are
  those of the largest stack (StackID) whose dimension indices other than StackID and
  InStackPositionNumber (time, echo…) are the lowest (else the lowest
  TemporalPositionIndex), ordered by
  position along the slice normal (row x column direction); for 4d_multiframe_test.dcm
  this is checked against nibabel's own multi-frame reader ([..., 0] of its 4D array).
  Spacing is [column, row] PixelSpacing (Pixel Measures group for enhanced) and, with
  several positioned frames, the mean gap of their positions; origin is the first
  frame's ImagePositionPatient. RT Dose: values times Dose Grid Scaling, z spacing the
  mean step of the Grid Frame Offset Vector (PS3.3 C.8.8.3).
- NIfTI: nibabel's get_fdata() (scl_slope/inter applied as nibabel does), the first volume
  of 4D data, spacing the lengths of the affine's columns (world distance per index step),
  direction those columns over their lengths (row-major 3×3), origin the affine's offset.
- NRRD: pynrrd's nrrd.read() (index order F: axis 0 fastest, as in the file). Spatial axes:
  those whose space direction is a vector, else those of kind domain/space, else all (up to
  3). A non-spatial axis longer than 1 of a list, vector or colour kind (or of no kind, before
  a spatial one) is channels: the values are listed channel fastest ("channels" in the
  reference); one of kind time/domain (or no kind, after them all) is a series whose first
  volume is taken; any other kind (tensors) is a refusal.
  Spacing is the lengths of the spatial axes' space directions (else |spacings|), direction
  those vectors over their lengths as columns (row-major 3×3, in the file's space, as vpt
  keeps it), origin the space origin.
Refusals: the reader refuses the file, or it uses a feature vpt names as unsupported
(compressed transfer syntaxes, colour, 1-bit, PALETTE COLOR, NIfTI-2, Analyze).
"""
import gzip
import hashlib
import json
import os
import sys
import warnings

import numpy as np

warnings.filterwarnings('ignore')
import nibabel as nib  # noqa: E402
import nrrd  # noqa: E402
import pydicom  # noqa: E402
from pydicom.pixels import apply_modality_lut  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.abspath(os.path.join(HERE, '..', '..', '..', '..'))
CORPUS = os.path.join(ROOT, 'data', 'corpus')
NATIVE = {'1.2.840.10008.1.2', '1.2.840.10008.1.2.1', '1.2.840.10008.1.2.1.99', '1.2.840.10008.1.2.2'}
CORRUPT = ['truncated', 'bad-header', 'invalid-data']


def checksum(values):
    a = np.ascontiguousarray(values, dtype='<f4').copy()
    bits = a.view('<u4')
    bits[np.isnan(a)] = 0x7FC00000
    return hashlib.sha256(a.tobytes()).hexdigest()


def loaded(values_xyz_flat, dims, reader, **extra):
    v = np.asarray(values_xyz_flat, dtype=np.float64)
    finite = v[np.isfinite(v)]
    out = {
        'dims': [int(d) for d in dims],
        'sha256': checksum(v),
        'min': float(finite.min()) if finite.size else None,
        'max': float(finite.max()) if finite.size else None,
    }
    for k, x in extra.items():
        if x is not None:
            out[k] = [float(y) for y in x]
    return {'load': out, 'reader': reader}


def refused(reasons, why, reader):
    return {'refuse': reasons, 'why': why, 'reader': reader}


def group(ds, frame_item, name):
    """A functional group macro's first item: the frame's own, else the shared one."""
    for src in (frame_item, (ds.get('SharedFunctionalGroupsSequence') or [None])[0]):
        if src is not None and name in src and len(src[name].value):
            return src[name].value[0]
    return None


def volume_key(fc, others):
    if fc is None:
        return ()
    if others and 'DimensionIndexValues' in fc:
        values = fc.DimensionIndexValues
        values = list(values) if isinstance(values, (list, pydicom.multival.MultiValue)) else [values]
        return tuple(int(values[i]) for i in others if i < len(values))
    return (int(fc.TemporalPositionIndex),) if 'TemporalPositionIndex' in fc else ()


def enhanced(ds, arr, rel):
    frames = ds.PerFrameFunctionalGroupsSequence
    n = len(frames)
    # Dimension indices other than the stack and the position in it (time, echo, b-value…):
    # the frames of one volume share them; the first volume has the lowest.
    pointers = [int(d.DimensionIndexPointer) for d in ds.get('DimensionIndexSequence', [])]
    others = [i for i, p in enumerate(pointers) if p not in (0x00209056, 0x00209057)]
    arr = arr.reshape(n, ds.Rows, ds.Columns)
    info = []
    for k, fr in enumerate(frames):
        fc = group(ds, fr, 'FrameContentSequence')
        pos = group(ds, fr, 'PlanePositionSequence')
        ori = group(ds, fr, 'PlaneOrientationSequence')
        pvt = group(ds, fr, 'PixelValueTransformationSequence')
        slope, inter = 1.0, 0.0
        if pvt is not None and 'RescaleSlope' in pvt:
            slope, inter = float(pvt.RescaleSlope), float(pvt.RescaleIntercept)
        elif 'RescaleSlope' in ds:
            slope, inter = float(ds.RescaleSlope), float(ds.RescaleIntercept)
        info.append({
            'k': k,
            'stack': str(fc.StackID) if fc is not None and 'StackID' in fc else '',
            'volume': volume_key(fc, others),
            'ipp': [float(x) for x in pos.ImagePositionPatient] if pos is not None else None,
            'iop': [float(x) for x in ori.ImageOrientationPatient] if ori is not None else None,
            'scale': (slope, inter),
        })
    stacks = {}
    for f in info:
        stacks.setdefault(f['stack'], []).append(f)
    chosen = max(stacks.values(), key=len)
    v0 = min(f['volume'] for f in chosen)
    chosen = [f for f in chosen if f['volume'] == v0]
    iop = chosen[0]['iop']
    normal = np.cross(iop[:3], iop[3:])
    chosen.sort(key=lambda f: float(np.dot(f['ipp'], normal)))
    out = np.stack([arr[f['k']].astype(np.float64) * f['scale'][0] + f['scale'][1] for f in chosen])
    pm = group(ds, frames[0], 'PixelMeasuresSequence')
    ps = [float(x) for x in pm.PixelSpacing] if pm is not None and 'PixelSpacing' in pm else None
    d = [float(np.dot(f['ipp'], normal)) for f in chosen]
    z = (d[-1] - d[0]) / (len(d) - 1) if len(d) > 1 else None
    spacing = [ps[1], ps[0], z] if ps and z else None
    if rel.endswith('4d_multiframe_test.dcm'):
        # nibabel's own multi-frame reader, first time point; its axes are (column, row, slice).
        from nibabel.nicom import dicomwrappers

        # nibabel orders slices the other way along the normal.
        nibdata = dicomwrappers.wrapper_from_data(ds).get_data()[..., 0]
        assert np.array_equal(np.transpose(nibdata, (2, 1, 0))[::-1], out), 'nibabel disagrees'
    return loaded(out.ravel(), (ds.Columns, ds.Rows, len(chosen)), 'pydicom 3.0.2 + functional groups',
                  spacing=spacing, origin=chosen[0]['ipp'], rowCol=iop)


def dicom(path, rel):
    reader = 'pydicom 3.0.2'
    if path.endswith('.gz'):
        return refused(['bad-magic', 'unsupported'], 'gzip-compressed DICOM (neither reader opens it as it is)', reader)
    try:
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter('always')
            ds = pydicom.dcmread(path)
            ds.get('PixelData')
        # pydicom recovered from a file that contradicts its own header (explicit VR declared,
        # implicit found): a reader that does not guess may refuse it as corrupt instead.
        malformed = [str(w.message) for w in caught if 'Expected explicit VR' in str(w.message)]
    except pydicom.errors.InvalidDicomError as e:
        return refused(['bad-magic'], f'no DICOM Part 10 preamble ({e})', reader)
    except Exception as e:  # noqa: BLE001
        return refused(CORRUPT, f'pydicom cannot read it ({type(e).__name__}: {e})', reader)
    syntax = str(ds.file_meta.get('TransferSyntaxUID', ''))
    if not syntax:
        return refused(['bad-header'], 'no Transfer Syntax UID in the file meta group', reader)
    # Nothing to render; a file cut short may also fail to parse at all.
    empty = ['empty', 'bad-header', 'truncated']
    if syntax not in NATIVE:
        also = (empty if 'PixelData' not in ds else []) + (CORRUPT if malformed else [])
        why = f'compressed transfer syntax {syntax}' + (f'; pydicom: {malformed[0]}' if malformed else '')
        return refused(['unsupported'] + [r for r in also if r != 'unsupported'], why, reader)
    if 'PixelData' not in ds:
        return refused(empty, 'no Pixel Data', reader)
    if any(k not in ds for k in ('Rows', 'Columns', 'BitsAllocated')):
        return refused(['bad-header'], 'Rows, Columns or BitsAllocated missing', reader)
    if int(ds.get('SamplesPerPixel', 1)) != 1:
        return refused(['unsupported'], f'{ds.SamplesPerPixel} samples per pixel', reader)
    if int(ds.BitsAllocated) not in (8, 16, 32):
        return refused(['unsupported'], f'{ds.BitsAllocated} bits allocated', reader)
    if str(ds.get('PhotometricInterpretation', '')) == 'PALETTE COLOR':
        res = refused(['unsupported'], 'PALETTE COLOR (indices into a colour table)', reader)
        # The stored indices too: the test relabels the file MONOCHROME2 and compares, which
        # checks the pixel decoding (OBXXXX1A_expb.dcm: 8-bit OW, big endian) on the real file.
        frames = int(ds.get('NumberOfFrames', 1) or 1)
        res['indices'] = loaded(ds.pixel_array.ravel(), (ds.Columns, ds.Rows, frames), reader)['load']
        return res
    try:
        arr = ds.pixel_array
    except Exception as e:  # noqa: BLE001
        return refused(CORRUPT, f'pydicom cannot decode the pixels ({type(e).__name__}: {e})', reader)
    if 'PerFrameFunctionalGroupsSequence' in ds:
        return enhanced(ds, arr, rel)
    values = apply_modality_lut(arr, ds).astype(np.float64)
    frames = int(ds.get('NumberOfFrames', 1) or 1)
    ps = [float(x) for x in ds.PixelSpacing] if 'PixelSpacing' in ds and len(ds.PixelSpacing) == 2 else None
    spacing = [ps[1], ps[0], None] if ps and ps[0] > 0 and ps[1] > 0 else None
    if 'DoseGridScaling' in ds:
        # RT Dose (PS3.3 C.8.8.3): stored values times Dose Grid Scaling are the dose.
        values = values * float(ds.DoseGridScaling)
        offsets = ds.get('GridFrameOffsetVector')
        if spacing and frames > 1 and offsets is not None and ds.get('FrameIncrementPointer') == 0x3004000C:
            spacing[2] = abs(float(offsets[-1]) - float(offsets[0])) / (frames - 1)
    ipp = [float(x) for x in ds.ImagePositionPatient] if 'ImagePositionPatient' in ds else None
    iop = [float(x) for x in ds.ImageOrientationPatient] if 'ImageOrientationPatient' in ds else None
    res = loaded(values.ravel(), (ds.Columns, ds.Rows, frames), reader, origin=ipp,
                 rowCol=iop if iop and len(iop) == 6 else None)
    if spacing:
        res['load']['spacing'] = spacing if spacing[2] is not None else spacing[:2]
    return res


def nifti(path, rel):
    reader = 'nibabel 5.4.2'
    if path.endswith('.hdr'):
        img_path = path[:-4] + '.img'
        with open(path, 'rb') as f:
            head = f.read(348)
        magic = head[344:348]
        if magic == b'ni1\0':
            if not os.path.exists(img_path):
                return refused(['unsupported', 'not-found'], 'a NIfTI-1 .hdr whose .img is not in the corpus', reader)
        elif len(head) >= 4 and int.from_bytes(head[:4], 'little') in (540, 540 << 24):
            return refused(['unsupported', 'bad-magic'], 'NIfTI-2 header', reader)
        else:
            return refused(['unsupported', 'bad-magic'], 'Analyze 7.5 header (no NIfTI magic)', reader)
    try:
        img = nib.load(path)
    except Exception as e:  # noqa: BLE001
        return refused(CORRUPT, f'nibabel cannot read it ({type(e).__name__}: {e})', reader)
    if not isinstance(img, nib.Nifti1Image):  # Nifti2Image is a subclass: vpt reads NIfTI-2 too
        return refused(['unsupported'], f'{type(img).__name__}, not NIfTI', reader)
    # CIFTI-2 (intent codes 3000-3099) is a NIfTI-2 file of brain-surface data, not a volume: vpt refuses it by name.
    if 3000 <= int(img.header['intent_code']) <= 3099:
        return refused(['unsupported'], 'CIFTI-2 (NIfTI intent code 3000-3099), not a volume', reader)
    data = img.get_fdata(dtype=np.float64)
    while data.ndim > 3:
        data = data[..., 0]
    while data.ndim < 3:
        data = data[..., np.newaxis]
    spacing = np.sqrt((img.affine[:3, :3] ** 2).sum(axis=0))
    # Direction cosines: the affine's columns over their lengths, row-major like vpt's orientation.
    direction = (img.affine[:3, :3] / spacing).ravel()
    return loaded(data.ravel(order='F'), data.shape, reader, spacing=spacing, origin=img.affine[:3, 3],
                  direction=direction)


def nrrd_file(path, rel):
    reader = 'pynrrd 1.1.3'
    try:
        data, header = nrrd.read(path)
    except Exception as e:  # noqa: BLE001
        return refused(CORRUPT, f'pynrrd cannot read it ({type(e).__name__}: {e})', reader)
    sizes = list(data.shape)
    n = len(sizes)
    dirs = header.get('space directions')
    kinds = header.get('kinds')
    if dirs is not None:
        dirs = np.asarray(dirs, dtype=np.float64)
        spatial = [bool(np.all(np.isfinite(dirs[i]))) for i in range(n)]
    elif kinds is not None and len(kinds) == n:
        spatial = [k.lower() in ('domain', 'space') for k in kinds]
    else:
        spatial = [True] * n
    axes = [i for i in range(n) if spatial[i]]
    if len(axes) > 3:
        return refused(['unsupported'], f'{len(axes)} spatial axes', reader)
    # A non-spatial axis longer than 1: channels when its kind is a list, vector or colour one (or it has
    # no kind and comes before a spatial axis), else a series (time, domain) whose first volume is taken.
    channel = None
    for i in range(n):
        if spatial[i] or sizes[i] == 1:
            continue
        kind = (kinds[i] if kinds is not None and len(kinds) == n else '').lower()
        unknown = kind in ('', '???', 'none')
        if kind in CHANNEL_KINDS or (unknown and i < axes[-1]):
            if channel is not None or sizes[i] > 16:
                return refused(['unsupported'], f'axis {i} (kind {kind}, size {sizes[i]}): a second channel axis or over 16 channels', reader)
            channel = i
        elif not (unknown or kind in ('time', 'domain', 'space')):
            return refused(['unsupported'], f'axis {i} (kind {kind}, size {sizes[i]}) holds values per voxel vpt does not read', reader)
    # The first volume of any series axis; length-1 axes dropped; the channel axis kept, moved first (channel fastest).
    index = tuple(slice(None) if spatial[i] or i == channel else 0 for i in range(n))
    values = np.asarray(data[index], dtype=np.float64)
    if channel is not None:
        kept = [i for i in range(n) if spatial[i] or i == channel]
        values = np.moveaxis(values, kept.index(channel), 0)
    dims = [sizes[a] for a in axes] + [1] * (3 - len(axes))
    extra = {}
    if dirs is not None:
        vecs = np.stack([dirs[a] for a in axes])
        lengths = np.sqrt((vecs ** 2).sum(axis=1))
        extra['spacing'] = lengths
        if len(axes) == 3 and vecs.shape[1] == 3:
            extra['direction'] = (vecs.T / lengths).ravel()
    elif 'spacings' in header:
        extra['spacing'] = [abs(float(header['spacings'][a])) for a in axes]
    if 'space origin' in header:
        o = [float(x) for x in header['space origin']]
        extra['origin'] = (o + [0.0, 0.0])[:3]
    ref = loaded(values.ravel(order='F'), dims, reader, **extra)
    if channel is not None:
        ref['load']['channels'] = int(sizes[channel])
    return ref


CHANNEL_KINDS = {'list', 'point', 'vector', 'covariant-vector', 'normal', '2-vector', '3-color', 'rgb-color',
                 'hsv-color', 'xyz-color', '4-color', 'rgba-color', '3-vector', '3-gradient', '3-normal', '4-vector'}


def series_folder(folder, names):
    """A folder of single-frame files loaded together: its largest series, one orientation,
    sorted along the slice normal; None when that is ambiguous (largest series tied)."""
    reader = 'pydicom 3.0.2 (a series)'
    images = []
    for name in names:
        ds = pydicom.dcmread(os.path.join(folder, name))
        if 'PixelData' in ds:
            images.append(ds)
    if len(images) < 2:
        return None
    by_series = {}
    for ds in images:
        by_series.setdefault(str(ds.SeriesInstanceUID), []).append(ds)
    sizes = sorted((len(v) for v in by_series.values()), reverse=True)
    if len(sizes) > 1 and sizes[0] == sizes[1]:
        return None
    series = max(by_series.values(), key=len)
    orientations = {tuple(round(float(x), 3) for x in ds.ImageOrientationPatient) for ds in series}
    if len(orientations) == len(series) and len(series) > 1:
        return refused(['invalid-data', 'unsupported'], f'every one of the {len(series)} slices has its own orientation (a localizer or radial series)', reader)
    if len(orientations) > 1:
        return None
    iop = [float(x) for x in series[0].ImageOrientationPatient]
    normal = np.cross(iop[:3], iop[3:])
    series.sort(key=lambda ds: float(np.dot([float(x) for x in ds.ImagePositionPatient], normal)))
    d = [float(np.dot([float(x) for x in ds.ImagePositionPatient], normal)) for ds in series]
    values = np.stack([apply_modality_lut(ds.pixel_array, ds).astype(np.float64) for ds in series])
    ps = [float(x) for x in series[0].PixelSpacing]
    return loaded(values.ravel(), (series[0].Columns, series[0].Rows, len(series)), reader,
                  spacing=[ps[1], ps[0], (d[-1] - d[0]) / (len(d) - 1)],
                  origin=[float(x) for x in series[0].ImagePositionPatient], rowCol=iop)


def is_dicom(path):
    with open(path, 'rb') as f:
        head = f.read(132)
    return len(head) == 132 and head[128:] == b'DICM'


def main():
    if not os.path.isdir(CORPUS):
        sys.exit('no data/corpus/: run `pnpm corpus:fetch` first')
    refs = {}
    for base, dirs, files in os.walk(CORPUS):
        dirs[:] = sorted(d for d in dirs if not d.startswith('.'))
        for name in sorted(files):
            path = os.path.join(base, name)
            rel = os.path.relpath(path, CORPUS)
            if name.startswith('.'):
                continue
            if name.endswith(('.nii', '.nii.gz', '.hdr')):
                refs[rel] = nifti(path, rel)
            elif name.endswith(('.nrrd', '.nhdr')):
                refs[rel] = nrrd_file(path, rel)
            elif name.endswith(('.dcm', '.dcm.gz')) or is_dicom(path):
                refs[rel] = dicom(path, rel)
        # pydicom's DICOMDIR test folders hold real series (and localizers): each folder of
        # extension-less image files is also loaded as one set of files, key "folder/".
        names = sorted(n for n in files if '.' not in n and n != 'DICOMDIR' and is_dicom(os.path.join(base, n)))
        if 'dicomdirtests' in base and len(names) > 1:
            ref = series_folder(base, names)
            if ref is not None:
                refs[os.path.relpath(base, CORPUS) + '/'] = ref
    out = os.path.join(HERE, 'references.json')
    with open(out, 'w') as f:
        json.dump({'generator': 'packages/loaders/test/corpus/make_references.py', 'files': refs}, f, indent=1)
        f.write('\n')
    n_load = sum('load' in r for r in refs.values())
    print(f'{len(refs)} files: {n_load} with reference voxels, {len(refs) - n_load} refusals -> {out}')


if __name__ == '__main__':
    main()
