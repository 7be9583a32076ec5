"""The peer readers' half of benchmarks/read-speed.mjs: nibabel and pynrrd, timed in Python.

Reads lines "<format> <path>" on stdin; for each, reads the file's bytes into memory once
(first time only), then parses them from memory and prints the seconds taken. The voxels
are materialised as the reader's own array (nibabel's dataobj, not get_fdata's float64
copy), so both sides do the same work: header, inflate, voxels in memory.
"""
import gzip
import io
import sys
import time

import nibabel as nib
import nrrd
import numpy as np

cache = {}


def read_nifti(data, compressed):
    fileobj = gzip.GzipFile(fileobj=io.BytesIO(data)) if compressed else io.BytesIO(data)
    holder = nib.FileHolder(fileobj=fileobj)
    img = nib.Nifti1Image.from_file_map({'header': holder, 'image': holder})
    return np.asanyarray(img.dataobj)


def read_nrrd(data):
    fh = io.BytesIO(data)
    header = nrrd.read_header(fh)
    return nrrd.read_data(header, fh, index_order='F')


for line in sys.stdin:
    fmt, path = line.split()
    if path not in cache:
        with open(path, 'rb') as f:
            cache[path] = f.read()
    data = cache[path]
    t = time.perf_counter()
    if fmt in ('nii', 'nii.gz'):
        arr = read_nifti(data, fmt == 'nii.gz')
    else:
        arr = read_nrrd(data)
    seconds = time.perf_counter() - t
    print(f'{seconds:.6f} {arr.size}', flush=True)
