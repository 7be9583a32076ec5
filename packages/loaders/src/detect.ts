import type { LoaderFormat } from './types.js';
import { hasNiftiMagic } from './formats/nifti.js';
import { hasNrrdMagic } from './formats/nrrd.js';
import { hasDicomMagic } from './formats/dicom.js';
import { isGzip } from './io/gzip.js';

export type Format = Exclude<LoaderFormat, 'auto'> | 'sidecar';

/** The format a file name suggests, if any. */
export function formatFromName(name: string): Format | undefined {
  const n = name.toLowerCase().replace(/[?#].*$/, '');
  if (n.endsWith('.nii') || n.endsWith('.nii.gz') || n.endsWith('.hdr') || n.endsWith('.hdr.gz')) return 'nifti';
  if (n.endsWith('.nrrd') || n.endsWith('.nhdr')) return 'nrrd';
  if (n.endsWith('.dcm') || n.endsWith('.dicom') || n.endsWith('.ima')) return 'dicom';
  if (n.endsWith('.json')) return 'sidecar';
  if (n.endsWith('.raw')) return 'raw';
  return undefined;
}

/** The format the first bytes show, if any (gzip counts as NIfTI: .nii.gz is the gzip format vpt reads whole). */
export function formatFromBytes(bytes: Uint8Array): Format | undefined {
  if (hasNiftiMagic(bytes)) return 'nifti';
  if (hasNrrdMagic(bytes)) return 'nrrd';
  if (hasDicomMagic(bytes)) return 'dicom';
  if (isGzip(bytes)) return 'nifti';
  let i = 0;
  while (
    i < bytes.length &&
    i < 64 &&
    (bytes[i] === 0x20 ||
      bytes[i] === 0x0a ||
      bytes[i] === 0x0d ||
      bytes[i] === 0x09 ||
      bytes[i] === 0xef ||
      bytes[i] === 0xbb ||
      bytes[i] === 0xbf)
  )
    i++;
  if (bytes[i] === 0x7b) return 'sidecar'; // '{'
  return undefined;
}

export function baseName(path: string): string {
  const clean = path.replace(/[?#].*$/, '');
  return clean.slice(clean.lastIndexOf('/') + 1);
}
