import fs from 'node:fs';
import path from 'node:path';
import { rendererNames } from '@vpt/core';
import { checkSceneDescription, type SceneDescription, type VolumeDescription } from './scene-description.js';
import type { StaticServer } from './server.js';

/** Read and check a scene file; errors name the file. */
export function readSceneFile(file: string): { description: SceneDescription; baseDir: string } {
  let text: string;
  try {
    text = fs.readFileSync(file, 'utf8');
  } catch (e) {
    throw new Error(`Cannot read scene file ${file}: ${(e as NodeJS.ErrnoException).code === 'ENOENT' ? 'no such file' : (e as Error).message}`);
  }
  let json: unknown;
  try {
    json = JSON.parse(text);
  } catch (e) {
    throw new Error(`Scene file ${file} is not valid JSON: ${(e as Error).message}`);
  }
  try {
    checkSceneDescription(json, rendererNames());
  } catch (e) {
    throw new Error(`${file}: ${(e as Error).message}`);
  }
  return { description: json, baseDir: path.dirname(path.resolve(file)) };
}

const HAS_SCHEME = /^[a-z][a-z0-9+.-]*:/i;

/** Apply `map` to each file reference of the description (the volume's raw or sidecar). */
function mapVolumeRefs(desc: SceneDescription, map: (ref: string) => string): SceneDescription {
  const volume = desc.volume;
  if (!volume || 'procedural' in volume) return desc;
  const mapped: VolumeDescription = 'sidecar' in volume ? { ...volume, sidecar: map(volume.sidecar) } : { ...volume, raw: map(volume.raw) };
  return { ...desc, volume: mapped };
}

/**
 * Resolve the description's file paths against baseDir to absolute paths, failing early
 * (before a browser starts) when a file is missing. URLs with a scheme are left alone,
 * and so is an absolute path that is not a file on this machine: it is taken as a URL
 * path under the server root.
 */
export function resolveSceneFiles(desc: SceneDescription, baseDir: string): SceneDescription {
  return mapVolumeRefs(desc, (ref) => {
    if (HAS_SCHEME.test(ref)) return ref;
    const file = path.resolve(baseDir, ref);
    if (fs.existsSync(file) && fs.statSync(file).isFile()) return file;
    if (ref.startsWith('/')) return ref;
    throw new Error(`Volume file not found: ${file}`);
  });
}

/**
 * Make the files a description refers to reachable from the page: each existing file's
 * folder is mounted on the server and the path replaced by its URL (see
 * resolveSceneFiles for what counts as a file).
 */
export function mountSceneFiles(desc: SceneDescription, baseDir: string, server: StaticServer): SceneDescription {
  return mapVolumeRefs(resolveSceneFiles(desc, baseDir), (ref) => {
    if (!path.isAbsolute(ref) || !fs.existsSync(ref)) return ref;
    return server.mount(path.dirname(ref)) + encodeURIComponent(path.basename(ref));
  });
}
