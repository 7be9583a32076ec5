#!/usr/bin/env node
/**
 * Read speed of @vpt/loaders against the formats' own readers (issue 25 item 4): the same
 * in-memory bytes read by vpt's in-thread reader in Node and by nibabel / pynrrd in Python
 * (benchmarks/read-speed-peer.py, timed in Python), per format: raw .nii, .nii.gz, raw NRRD,
 * gzip NRRD, all a size³ int16 volume. Runs are interleaved (vpt, peer, vpt, peer…), the
 * load average is printed before and after, and the medians give the ratio vpt / peer.
 *
 *   pnpm run build && node benchmarks/read-speed.mjs [--runs 7] [--size 256] [--python python3] [--json out.json]
 *     [--loaders path/to/loaders/dist/index.js]
 *
 * Needs Python with numpy, nibabel and pynrrd (`pip install nibabel pynrrd`).
 */
import { spawn } from 'node:child_process';
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import readline from 'node:readline';
import { fileURLToPath } from 'node:url';
import { parseCliOrExit } from '@vpt/cli-options';
import zlib from 'node:zlib';

const here = path.dirname(fileURLToPath(import.meta.url));
const flags = parseCliOrExit({
  name: 'node benchmarks/read-speed.mjs',
  synopsis: '[--runs 7] [--size 256] [--python python3] [--json out.json] [--loaders FILE]',
  summary:
    'Read speed of @vpt/loaders against nibabel / pynrrd on the same size³ int16 bytes, interleaved.\n' +
    'Needs a build (pnpm run build) and Python with numpy, nibabel and pynrrd.',
  options: {
    runs: { type: 'integer', min: 1, default: 7, description: 'interleaved rounds per format' },
    size: { type: 'integer', min: 2, max: 512, default: 256, description: 'the volume side in voxels' },
    python: { type: 'string', valueName: 'CMD', description: 'the Python to run (default python3)' },
    json: { type: 'string', valueName: 'FILE', description: 'also write the results as JSON' },
    // Another build of @vpt/loaders (its dist/index.js), e.g. an older commit's, to compare.
    loaders: { type: 'string', valueName: 'FILE', description: 'the @vpt/loaders build to time (default this tree)' },
  },
});
flags.python ??= 'python3';
flags.loaders ??= path.join(here, '../packages/loaders/dist/index.js');
const runs = flags.runs;
const n = flags.size;
const { loadVolume } = await import(path.resolve(flags.loaders));

// ——— the files: one size³ int16 volume (a smooth field plus noise, so gzip has work) ———
const count = n ** 3;
const voxels = new Int16Array(count);
for (let z = 0, i = 0; z < n; z++)
  for (let y = 0; y < n; y++)
    for (let x = 0; x < n; x++, i++)
      voxels[i] =
        Math.round(1000 * Math.sin(x / 9) * Math.cos(y / 13) + 300 * Math.sin(z / 7)) + ((i * 2654435761) >>> 29);
const voxelBytes = new Uint8Array(voxels.buffer);

function niftiBytes() {
  const out = new Uint8Array(352 + voxelBytes.length);
  const v = new DataView(out.buffer);
  v.setInt32(0, 348, true);
  [3, n, n, n, 1, 1, 1, 1].forEach((d, i) => v.setInt16(40 + 2 * i, d, true));
  v.setInt16(70, 4, true); // int16
  v.setInt16(72, 16, true);
  [1, 1, 1, 1].forEach((p, i) => v.setFloat32(76 + 4 * i, p, true));
  v.setFloat32(108, 352, true); // vox_offset
  v.setUint8(123, 2); // mm
  out.set([0x6e, 0x2b, 0x31, 0], 344); // "n+1\0"
  out.set(voxelBytes, 352);
  return out;
}
function nrrdBytes(encoding, data) {
  const header = Buffer.from(
    `NRRD0004\ntype: short\ndimension: 3\nsizes: ${n} ${n} ${n}\nendian: little\nencoding: ${encoding}\nspacings: 1 1 1\n\n`,
  );
  const out = new Uint8Array(header.length + data.length);
  out.set(header);
  out.set(data, header.length);
  return out;
}
const files = {
  nii: niftiBytes(),
  'nii.gz': new Uint8Array(zlib.gzipSync(niftiBytes(), { level: 6 })),
  nrrd: nrrdBytes('raw', voxelBytes),
  'nrrd (gzip)': nrrdBytes('gzip', new Uint8Array(zlib.gzipSync(voxelBytes, { level: 6 }))),
};
const work = fs.mkdtempSync(path.join(os.tmpdir(), 'vpt-read-speed-'));
const paths = {};
for (const [name, bytes] of Object.entries(files)) {
  paths[name] = path.join(work, `volume.${name.replace(/\W+/g, '-')}`);
  fs.writeFileSync(paths[name], bytes);
}

// ——— the peer: one Python process, asked for one timed read at a time ———
const py = spawn(flags.python, [path.join(here, 'read-speed-peer.py')], { stdio: ['pipe', 'pipe', 'inherit'] });
const lines = readline.createInterface({ input: py.stdout })[Symbol.asyncIterator]();
async function peerSeconds(format) {
  const peerFormat = format === 'nrrd (gzip)' ? 'nrrd' : format;
  py.stdin.write(`${peerFormat} ${paths[format]}\n`);
  const { value, done } = await lines.next();
  if (done) throw new Error('the Python peer exited (is nibabel / pynrrd installed?)');
  const [seconds, size] = value.split(' ').map(Number);
  if (size !== count) throw new Error(`the peer read ${size} voxels of ${format}, not ${count}`);
  return seconds;
}
async function vptSeconds(format) {
  const t = performance.now();
  const v = await loadVolume(files[format], { worker: false });
  const seconds = (performance.now() - t) / 1000;
  if (v.data.length !== count || v.data[count - 1] !== voxels[count - 1]) throw new Error(`vpt misread ${format}`);
  return seconds;
}

const loadBefore = os.loadavg();
const times = Object.fromEntries(Object.keys(files).map((f) => [f, { vpt: [], peer: [] }]));
// One untimed warm-up of each (module loading, JIT, Python imports), then interleaved runs.
for (const f of Object.keys(files)) {
  await vptSeconds(f);
  await peerSeconds(f);
}
for (let r = 0; r < runs; r++) {
  for (const f of Object.keys(files)) {
    times[f].vpt.push(await vptSeconds(f));
    times[f].peer.push(await peerSeconds(f));
  }
}
py.stdin.end();
const loadAfter = os.loadavg();
fs.rmSync(work, { recursive: true });

const median = (a) => {
  const s = [...a].sort((x, y) => x - y);
  return s.length % 2 ? s[(s.length - 1) / 2] : (s[s.length / 2 - 1] + s[s.length / 2]) / 2;
};
const ms = (s) => (s * 1000).toFixed(s < 0.1 ? 1 : 0);
const cell = (a) => `${ms(median(a))} (${ms(Math.min(...a))}–${ms(Math.max(...a))})`;
const peerName = (f) => (f.startsWith('nii') ? 'nibabel' : 'pynrrd');
console.log(
  `${n}³ int16, ${runs} interleaved runs; load average ${loadBefore.map((x) => x.toFixed(2)).join(' ')} before, ${loadAfter.map((x) => x.toFixed(2)).join(' ')} after`,
);
console.log('| format | bytes | vpt ms | peer | peer ms | vpt / peer |');
console.log('|---|---|---|---|---|---|');
const result = {};
for (const [f, t] of Object.entries(times)) {
  const ratio = median(t.vpt) / median(t.peer);
  result[f] = { bytes: files[f].length, vptMs: t.vpt.map((s) => s * 1000), peerMs: t.peer.map((s) => s * 1000), ratio };
  console.log(
    `| ${f} | ${files[f].length} | ${cell(t.vpt)} | ${peerName(f)} | ${cell(t.peer)} | ${ratio.toFixed(2)} |`,
  );
}
if (flags.json)
  fs.writeFileSync(
    flags.json,
    JSON.stringify({ size: n, runs, loadBefore, loadAfter, node: process.version, result }, null, 2),
  );
