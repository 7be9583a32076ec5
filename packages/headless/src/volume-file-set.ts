import fs from 'node:fs';
import path from 'node:path';
import { VptError } from '@vpt/core';

/**
 * What a scene's `volume.file` names, resolved in Node before a browser starts: the files the
 * page's loader (@vpt/loaders) will read, so exactly those are served. The loader finds a
 * detached file beside the one it is given (a sidecar's raw file, an `.nhdr`'s data file, an
 * `.hdr`'s `.img`), so those come along; a folder that is not an OME-Zarr store is a DICOM
 * series, every file in it.
 */
export type VolumeFileSet =
  /** One file to load by URL, served with the companions the loader fetches beside it. */
  | { kind: 'file'; main: string; companions: string[] }
  /** Files loaded together (a DICOM folder or an explicit list), each by its base name. */
  | { kind: 'list'; files: string[] }
  /** An OME-Zarr store: the folder is served (confined), read with format 'ome-zarr'. */
  | { kind: 'zarr'; dir: string };

/** Most files a DICOM folder may hold (a series is hundreds to a few thousand slices). */
export const MAX_FOLDER_FILES = 20_000;
const HEADER_PEEK_BYTES = 64 * 1024;

export function isZarrFolder(dir: string): boolean {
  try {
    if (!fs.statSync(dir).isDirectory()) return false;
  } catch {
    return false;
  }
  return ['zarr.json', '.zattrs', '.zgroup'].some((f) => isFile(path.join(dir, f)));
}

function isFile(f: string): boolean {
  try {
    return fs.statSync(f).isFile();
  } catch {
    return false;
  }
}

/** The file beside `file` called `name`, which must exist: the loader will ask for it. */
function beside(file: string, name: string, what: string): string {
  if (name.includes('/') || name.includes('\\'))
    throw new VptError(
      'invalid-scene',
      `${file}: its ${what} "${name}" is in another folder; vpt-render serves only files beside the one the scene names (list them in volume.file)`,
    );
  const f = path.join(path.dirname(file), name);
  if (!isFile(f)) throw new VptError('load-failed', `${file}: its ${what} ${f} was not found`);
  return f;
}

/** An NRRD header's detached data file (`data file:` / `datafile:`), if it names one file. */
function nrrdDataFile(file: string): string | undefined {
  const fd = fs.openSync(file, 'r');
  let text: string;
  try {
    const buf = Buffer.alloc(HEADER_PEEK_BYTES);
    const n = fs.readSync(fd, buf, 0, buf.length, 0);
    text = buf.subarray(0, n).toString('latin1');
  } finally {
    fs.closeSync(fd);
  }
  const end = text.search(/\r?\n\r?\n/);
  const header = end >= 0 ? text.slice(0, end) : text;
  const m = /^data ?file: *(.*?) *$/im.exec(header);
  // A LIST or a %d pattern names many files: the loader refuses it with a typed error.
  if (!m || /^LIST\b/.test(m[1]) || /%/.test(m[1]) || /\s/.test(m[1])) return undefined;
  return m[1];
}

/** The files a single volume file brings along (see VolumeFileSet). */
export function companionsOf(file: string, sidecarRawFile: (sidecar: string) => string): string[] {
  const lower = file.toLowerCase();
  if (lower.endsWith('.json')) return [sidecarRawFile(file)];
  if (lower.endsWith('.raw')) {
    const sidecar = file.replace(/\.raw$/i, '.json');
    return isFile(sidecar) ? [sidecar, sidecarRawFile(sidecar)].filter((f) => f !== file) : [];
  }
  if (lower.endsWith('.nhdr') || lower.endsWith('.nrrd')) {
    const data = nrrdDataFile(file);
    return data === undefined ? [] : [beside(file, data, 'data file')];
  }
  if (lower.endsWith('.hdr') || lower.endsWith('.hdr.gz')) {
    const img = path.basename(file).replace(/\.hdr(\.gz)?$/i, '.img$1');
    const imgGz = img.endsWith('.gz') ? img : `${img}.gz`;
    return [beside(file, isFile(path.join(path.dirname(file), img)) ? img : imgGz, '.img file')];
  }
  return [];
}

/** Every regular file under a folder (hidden ones skipped), at most MAX_FOLDER_FILES. */
export function folderFiles(dir: string): string[] {
  const out: string[] = [];
  const walk = (d: string) => {
    for (const e of fs.readdirSync(d, { withFileTypes: true }).sort((a, b) => a.name.localeCompare(b.name))) {
      if (e.name.startsWith('.')) continue;
      const f = path.join(d, e.name);
      if (e.isDirectory()) walk(f);
      else if (e.isFile() || (e.isSymbolicLink() && isFile(f))) {
        out.push(f);
        if (out.length > MAX_FOLDER_FILES)
          throw new VptError(
            'limit-exceeded',
            `Volume folder ${dir} holds more than ${MAX_FOLDER_FILES} files; name the series' files in volume.file`,
          );
      }
    }
  };
  walk(dir);
  if (!out.length) throw new VptError('load-failed', `Volume folder ${dir} holds no files`);
  return out;
}

/** Resolve `volume.file` (absolute paths) into the set of files to serve. */
export function volumeFileSet(files: readonly string[], sidecarRawFile: (sidecar: string) => string): VolumeFileSet {
  if (files.length === 1) {
    const f = files[0];
    if (isZarrFolder(f)) return { kind: 'zarr', dir: f };
    let st: fs.Stats;
    try {
      st = fs.statSync(f);
    } catch {
      throw new VptError('load-failed', `Volume file not found: ${f}`);
    }
    if (st.isDirectory()) return { kind: 'list', files: distinctNames(folderFiles(f)) };
    return { kind: 'file', main: f, companions: companionsOf(f, sidecarRawFile) };
  }
  for (const f of files) if (!isFile(f)) throw new VptError('load-failed', `Volume file not found: ${f}`);
  return { kind: 'list', files: distinctNames(files) };
}

/** The page's loader tells the files of a list apart by base name: two alike are refused. */
function distinctNames(files: readonly string[]): string[] {
  const names = new Map<string, string>();
  for (const f of files) {
    const other = names.get(path.basename(f));
    if (other && other !== f)
      throw new VptError(
        'invalid-scene',
        `volume.file names two files called ${path.basename(f)} (${other}, ${f}); the loader tells files apart by name`,
      );
    names.set(path.basename(f), f);
  }
  return [...files];
}

/** Every path a set serves (for --root confinement). */
export function servedPaths(set: VolumeFileSet): string[] {
  if (set.kind === 'zarr') return [set.dir];
  if (set.kind === 'list') return set.files;
  return [set.main, ...set.companions];
}
