import fs from 'node:fs';
import path from 'node:path';
import { pathToFileURL, fileURLToPath } from 'node:url';
import { checkRawByteLength, parseRawSidecar, rawFileBeside, VptError } from '@vpt/core';
import {
  isChannelFiles,
  type FileVolumeDescription,
  type RawVolumeDescription,
  type SceneDescription,
  type SingleVolumeDescription,
  type VolumeDescription,
} from './scene-description.js';
import { selectTimeStep } from './scene-description.js';
import type { StaticServer } from './server.js';
import { validateSceneDescription } from './validate-description.js';
import { isZarrFolder, servedPaths, volumeFileSet, type VolumeFileSet } from './volume-file-set.js';

/** Largest scene or sidecar file read (a lat-long environment inline in JSON can be large). */
const MAX_SCENE_FILE_BYTES = 256 * 1024 * 1024;
const MAX_SIDECAR_BYTES = 1024 * 1024;

export interface SceneFileOptions {
  /**
   * Confine every file the scene names to this folder (after following symlinks): paths that
   * leave it, URLs with a scheme and server URL paths are refused. For services that render
   * untrusted scene files (`vpt-render --root DIR`).
   */
  root?: string;
}

/** Read and check a scene file; errors name the file. */
export function readSceneFile(file: string): { description: SceneDescription; baseDir: string } {
  let text: string;
  try {
    const size = fs.statSync(file).size;
    if (size > MAX_SCENE_FILE_BYTES)
      throw new VptError(
        'limit-exceeded',
        `${size} bytes exceed the limit of ${MAX_SCENE_FILE_BYTES} for a scene file`,
      );
    text = fs.readFileSync(file, 'utf8');
  } catch (e) {
    if (e instanceof VptError) throw new VptError(e.code, `Scene file ${file}: ${e.message}`);
    throw new Error(
      `Cannot read scene file ${file}: ${(e as NodeJS.ErrnoException).code === 'ENOENT' ? 'no such file' : (e as Error).message}`,
    );
  }
  if (text.trim() === '')
    throw new VptError('invalid-scene', `Scene file ${file} is empty; it should hold a JSON object describing a scene`);
  let json: unknown;
  try {
    json = JSON.parse(text);
  } catch (e) {
    throw new VptError('invalid-scene', `Scene file ${file} is not valid JSON: ${(e as Error).message}`);
  }
  try {
    validateSceneDescription(json);
  } catch (e) {
    if (e instanceof VptError) throw new VptError(e.code, `${file}: ${e.message}`, { cause: e });
    throw new Error(`${file}: ${(e as Error).message}`);
  }
  return { description: json as SceneDescription, baseDir: path.dirname(path.resolve(file)) };
}

const HAS_SCHEME = /^[a-z][a-z0-9+.-]*:/i;

/** Apply `map` to each file reference of the description (the volume's raw or sidecar). */
function mapVolumeRefs(
  desc: SceneDescription,
  map: (ref: string, volume: VolumeDescription) => string,
): SceneDescription {
  const volume = desc.volume;
  // A timeSeries list is one `file` once selectTimeStep has picked the step.
  if (!volume || isChannelFiles(volume) || 'procedural' in volume || 'file' in volume || 'timeSeries' in volume)
    return desc;
  const mapped: VolumeDescription =
    'zarr' in volume
      ? { ...volume, zarr: map(volume.zarr, volume) }
      : 'sidecar' in volume
        ? { ...volume, sidecar: map(volume.sidecar, volume) }
        : { ...volume, raw: map(volume.raw, volume) };
  return { ...desc, volume: mapped };
}

function insideRoot(file: string, root: string): boolean {
  const real = fs.realpathSync(file),
    base = fs.realpathSync(root);
  return real === base || real.startsWith(base + path.sep);
}

function statFile(file: string): fs.Stats | null {
  try {
    const st = fs.statSync(file);
    return st.isFile() ? st : null;
  } catch {
    return null;
  }
}

/**
 * A sidecar as the page reads it, checked in Node before a browser starts by the same reader
 * (core's parseRawSidecar: dims, voxel_type, spacing, value_range, endianness, axes, layout);
 * returns the raw file beside it (rawFileBeside), whose size is checked against the dims from
 * its metadata, nothing read.
 */
export function checkSidecarFile(sidecar: string): { rawFile: string } {
  const name = `Sidecar ${sidecar}`;
  const size = statFile(sidecar)?.size ?? 0;
  if (size > MAX_SIDECAR_BYTES)
    throw new VptError(
      'limit-exceeded',
      `${name}: ${size} bytes exceed the limit of ${MAX_SIDECAR_BYTES} for a sidecar`,
    );
  let text: string;
  try {
    text = fs.readFileSync(sidecar, 'utf8');
  } catch (e) {
    throw new VptError('load-failed', `${name}: cannot be read (${(e as Error).message})`, { cause: e });
  }
  const header = parseRawSidecar(text, name);
  const rawFile = fileURLToPath(rawFileBeside(pathToFileURL(sidecar).href, header));
  const st = statFile(rawFile);
  if (!st) throw new VptError('load-failed', `${name}: its raw file ${rawFile} was not found`);
  checkRawByteLength(st.size, header, `${name}: raw file ${rawFile}`);
  return { rawFile };
}

/**
 * Resolve the description's file paths against baseDir to absolute paths, failing early
 * (before a browser starts) when a file is missing or its size from the file's metadata
 * does not match the declared dims. Without `options.root`, URLs with a scheme are left
 * alone, and so is an absolute path that is not a file on this machine (a URL path for the
 * page's server). With `root`, every reference must be a file inside it.
 */
export function resolveSceneFiles(
  desc: SceneDescription,
  baseDir: string,
  options: SceneFileOptions = {},
): SceneDescription {
  if (options.root !== undefined) checkRootFolder(options.root);
  // A label volume's files are resolved as a volume of their own.
  if (desc.labels) {
    const { labels, ...rest } = desc;
    const volume = resolveSceneFiles({ ...rest, volume: labels.volume }, baseDir, options).volume;
    return {
      ...resolveSceneFiles(rest, baseDir, options),
      labels: { ...labels, volume: volume as SingleVolumeDescription },
    };
  }
  // The step of a time series: its one file or store is what is checked and served.
  try {
    desc = selectTimeStep(desc);
  } catch (e) {
    throw new VptError('invalid-scene', (e as Error).message, { cause: e });
  }
  if (desc.volume && isChannelFiles(desc.volume)) {
    // One volume per channel: each resolved as a volume of its own.
    const channels = desc.volume.channels.map(
      (v) => resolveSceneFiles({ ...desc, volume: v }, baseDir, options).volume as SingleVolumeDescription,
    );
    return { ...desc, volume: { channels } };
  }
  if (desc.volume && 'file' in desc.volume)
    return { ...desc, volume: resolveFileVolume(desc.volume, baseDir, options) };
  return mapVolumeRefs(desc, (ref, volume) => {
    const confined = options.root !== undefined;
    if (HAS_SCHEME.test(ref)) {
      if (confined)
        throw new VptError(
          'invalid-scene',
          `Volume reference ${ref}: URLs are refused when scene paths are confined to ${options.root}`,
        );
      return ref;
    }
    const file = path.resolve(baseDir, ref);
    if ('zarr' in volume) return resolveZarrFolder(ref, file, options);
    const st = statFile(file);
    if (!st) {
      if (ref.startsWith('/') && !confined) return ref;
      throw new VptError('load-failed', `Volume file not found: ${file}`);
    }
    if (confined && !insideRoot(file, options.root!)) {
      throw new VptError(
        'invalid-scene',
        `Volume file ${file} is outside ${path.resolve(options.root!)}, the folder scene paths are confined to (--root)`,
      );
    }
    if ('sidecar' in volume) {
      const { rawFile } = checkSidecarFile(file);
      if (confined && !insideRoot(rawFile, options.root!))
        throw new VptError(
          'invalid-scene',
          `Raw file ${rawFile} of sidecar ${file} is outside ${path.resolve(options.root!)} (--root)`,
        );
    } else {
      const v = volume as RawVolumeDescription;
      checkRawByteLength(st.size, v, file);
    }
    return file;
  });
}

/** The folder scene paths are confined to must exist and be a folder (else every path check would fail obscurely). */
function checkRootFolder(root: string): void {
  let st: fs.Stats;
  try {
    st = fs.statSync(root);
  } catch {
    throw new VptError('invalid-scene', `--root ${root}: no such folder`);
  }
  if (!st.isDirectory()) throw new VptError('invalid-scene', `--root ${root}: is a file, not a folder`);
}

/** A scene's `volume.zarr` path: an OME-Zarr folder (inside `root` when confined), as an absolute path. */
function resolveZarrFolder(ref: string, dir: string, options: SceneFileOptions): string {
  const confined = options.root !== undefined;
  if (!isZarrFolder(dir)) {
    if (ref.startsWith('/') && !confined && !fs.existsSync(dir)) return ref; // a URL path on the page's server
    throw new VptError(
      'load-failed',
      `OME-Zarr store not found: ${dir} is not a folder holding zarr.json, .zattrs or .zgroup`,
    );
  }
  if (confined && !insideRoot(dir, options.root!)) {
    throw new VptError(
      'invalid-scene',
      `OME-Zarr store ${dir} is outside ${path.resolve(options.root!)}, the folder scene paths are confined to (--root)`,
    );
  }
  return dir;
}

/**
 * Make the files a description refers to reachable from the page: exactly those files (a
 * sidecar with its raw file), each set under its own `/__files/<n>/`, never their folders;
 * the path is replaced by its URL (see resolveSceneFiles for what counts as a file).
 */
export function mountSceneFiles(
  desc: SceneDescription,
  baseDir: string,
  server: StaticServer,
  options: SceneFileOptions = {},
): SceneDescription {
  if (desc.labels) {
    const { labels, ...rest } = desc;
    const volume = mountSceneFiles({ ...rest, volume: labels.volume }, baseDir, server, options).volume;
    return {
      ...mountSceneFiles(rest, baseDir, server, options),
      labels: { ...labels, volume: volume as SingleVolumeDescription },
    };
  }
  if (desc.volume && isChannelFiles(desc.volume)) {
    const channels = desc.volume.channels.map(
      (v) => mountSceneFiles({ ...desc, volume: v }, baseDir, server, options).volume as SingleVolumeDescription,
    );
    return { ...desc, volume: { channels } };
  }
  const resolved = resolveSceneFiles(desc, baseDir, options);
  if (resolved.volume && 'file' in resolved.volume)
    return { ...resolved, volume: mountFileVolume(resolved.volume, server) };
  return mapVolumeRefs(resolved, (ref, volume) => {
    if ('zarr' in volume) {
      // A store is a folder of many files: that folder alone is served (symlinks that leave it refused).
      if (!path.isAbsolute(ref) || !isZarrFolder(ref)) return ref;
      return server.mount(ref, undefined, { confine: true });
    }
    if (!path.isAbsolute(ref) || !statFile(ref)) return ref;
    const files = 'sidecar' in volume ? [ref, checkSidecarFile(ref).rawFile] : [ref];
    return server.mountFiles(files) + encodeURIComponent(path.basename(ref));
  });
}

/** The refs of a `volume.file`, each a URL (left alone), or a path made absolute against baseDir. */
function fileRefs(volume: FileVolumeDescription): string[] {
  return Array.isArray(volume.file) ? volume.file : [volume.file];
}

/**
 * `volume.file` (any format the loaders read): paths made absolute and checked to exist,
 * with the companions the loader will fetch beside them (volume-file-set.ts), all inside
 * `root` when confined; URLs pass only when not confined. An OME-Zarr folder gets
 * `format: 'ome-zarr'`, since its name need not end in .zarr.
 */
function resolveFileVolume(
  volume: FileVolumeDescription,
  baseDir: string,
  options: SceneFileOptions,
): FileVolumeDescription {
  const refs = fileRefs(volume);
  const confined = options.root !== undefined;
  const urls = refs.filter((r) => HAS_SCHEME.test(r));
  if (urls.length) {
    if (confined)
      throw new VptError(
        'invalid-scene',
        `Volume reference ${urls[0]}: URLs are refused when scene paths are confined to ${options.root}`,
      );
    if (urls.length !== refs.length)
      throw new VptError('invalid-scene', 'volume.file: a list mixes URLs and paths; give all of one kind');
    return volume;
  }
  const files = refs.map((r) => path.resolve(baseDir, r));
  // Without --root, an absolute path that is nothing on this machine is a URL path on the page's server.
  if (!confined && refs.every((r) => r.startsWith('/')) && files.every((f) => !fs.existsSync(f))) return volume;
  const set = volumeFileSet(files, (sidecar) => checkSidecarFile(sidecar).rawFile);
  if (confined)
    for (const f of servedPaths(set))
      if (!insideRoot(f, options.root!))
        throw new VptError(
          'invalid-scene',
          `Volume file ${f} is outside ${path.resolve(options.root!)}, the folder scene paths are confined to (--root)`,
        );
  const file = Array.isArray(volume.file) ? files : files[0];
  return set.kind === 'zarr' && !volume.format ? { ...volume, file, format: 'ome-zarr' } : { ...volume, file };
}

/** Serve exactly the files of a resolved `volume.file` and put their URLs in its place. */
function mountFileVolume(volume: FileVolumeDescription, server: StaticServer): FileVolumeDescription {
  const refs = fileRefs(volume);
  if (!refs.every((r) => path.isAbsolute(r) && fs.existsSync(r))) return volume; // URLs, URL paths
  const set: VolumeFileSet = volumeFileSet(refs, (sidecar) => checkSidecarFile(sidecar).rawFile);
  if (set.kind === 'zarr') return { ...volume, file: server.mount(set.dir, undefined, { confine: true }) };
  const files = servedPaths(set);
  const prefix = server.mountFiles(files);
  const url = (f: string) => prefix + encodeURIComponent(path.basename(f));
  return { ...volume, file: set.kind === 'file' ? url(set.main) : set.files.map(url) };
}
