import fs from 'node:fs';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import { RENDERER_CATALOG } from '@vpt/core';
import type { StaticServer } from './server.js';

/**
 * The packages the headless page loads, by URL folder name under /packages/: core, post,
 * loaders and every renderer package of core's catalog (page/index.html's import map
 * names the same folders).
 */
export const PAGE_PACKAGES: Record<string, string> = {
  core: '@vpt/core',
  post: '@vpt/post',
  loaders: '@vpt/loaders',
  ...Object.fromEntries(RENDERER_CATALOG.map((e) => [e.packageName.replace(/^@vpt\//, ''), e.packageName])),
};

function readName(dir: string): string | undefined {
  try {
    return JSON.parse(fs.readFileSync(path.join(dir, 'package.json'), 'utf8')).name;
  } catch {
    return undefined;
  }
}

/** This package's folder (works from src/ under Vitest and from dist/ once built). */
export function headlessPackageDir(): string {
  let dir = path.dirname(fileURLToPath(import.meta.url));
  for (;;) {
    if (readName(dir) === '@vpt/headless') return dir;
    const up = path.dirname(dir);
    if (up === dir) throw new Error('@vpt/headless: cannot find my own package.json');
    dir = up;
  }
}

/**
 * The folder of an installed package, found the way Node resolves bare names (each
 * ancestor's node_modules) but without going through its `exports`, which expose only
 * the ESM entry. Symlinks (pnpm workspaces) are followed to the real folder.
 */
export function findPackageDir(name: string, fromDir = headlessPackageDir()): string {
  let dir = fromDir;
  for (;;) {
    const candidate = path.join(dir, 'node_modules', ...name.split('/'));
    if (fs.existsSync(path.join(candidate, 'package.json'))) return fs.realpathSync(candidate);
    const up = path.dirname(dir);
    if (up === dir)
      throw new Error(
        `Cannot find the package ${name} (looked in node_modules above ${fromDir}); install it next to @vpt/headless`,
      );
    dir = up;
  }
}

/** The pnpm workspace this package lives in (the repository root), or null when installed from npm. */
export function workspaceRoot(fromDir = headlessPackageDir()): string | null {
  let dir = fromDir;
  for (;;) {
    if (fs.existsSync(path.join(dir, 'pnpm-workspace.yaml'))) return dir;
    const up = path.dirname(dir);
    if (up === dir) return null;
    dir = up;
  }
}

/**
 * Mount this package and the packages the page imports at /packages/<name>/, the URLs
 * in page/index.html's import map. In the repository those are the workspace folders
 * (the same files the root would serve); from npm they are the installed copies.
 * `overrides` maps a folder name (e.g. `core`) to another package folder, to run
 * another build of it (a benchmark against an older version, a test double).
 */
export function mountPagePackages(server: StaticServer, overrides: Record<string, string> = {}): void {
  const self = headlessPackageDir();
  server.mount(self, '/packages/headless/');
  for (const [folder, name] of Object.entries(PAGE_PACKAGES)) {
    server.mount(overrides[folder] ?? findPackageDir(name, self), `/packages/${folder}/`);
  }
  mountThirdParty(server, overrides.loaders ?? findPackageDir('@vpt/loaders', self));
}

/**
 * Third-party modules page code may import through @vpt/loaders (its OME-Zarr reader,
 * openOmeZarr, in the page's own thread): URL folder → [package, the package that depends
 * on it, whose folder it is resolved from]. page/index.html's import map names their files.
 */
export const PAGE_THIRD_PARTY: Record<string, [string, string]> = {
  zarrita: ['zarrita', '@vpt/loaders'],
  numcodecs: ['numcodecs', '@vpt/loaders'],
  fflate: ['fflate', '@vpt/loaders'],
  'zarrita-storage': ['@zarrita/storage', 'zarrita'],
};

/**
 * Mount PAGE_THIRD_PARTY at /packages/<folder>/ (also needed when the workspace root is
 * served: these are not workspace folders); one that cannot be found is left out (its
 * import then fails alone).
 */
export function mountThirdParty(server: StaticServer, loadersDir = findPackageDir('@vpt/loaders')): void {
  const dirs: Record<string, string> = { '@vpt/loaders': loadersDir };
  for (const [folder, [name, parent]] of Object.entries(PAGE_THIRD_PARTY)) {
    try {
      dirs[name] = findPackageDir(name, dirs[parent] ?? loadersDir);
      server.mount(dirs[name], `/packages/${folder}/`);
    } catch {
      // Not installed: only OME-Zarr reading in the page's own thread needs it.
    }
  }
}

/** URL path of the headless page. */
export const PAGE_PATH = '/packages/headless/page/index.html';
