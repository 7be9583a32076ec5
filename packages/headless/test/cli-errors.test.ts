// Issue 28 item 4: vpt-render's raw or unclear errors, each now refused before a browser
// starts with a message naming the option or the field (no ENOENT/EISDIR/EIO, no stack
// overflow, no "got null").
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { afterAll, beforeAll, describe, expect, it } from 'vitest';
import { runRender } from '../src/cli/render-main.js';
import type { CliIO } from '../src/cli/io.js';
import { validateSceneDescription } from '../src/validate-description.js';
import { MAX_SCENE_DEPTH } from '../src/json-shape.js';

let dir: string;
let scene: string;
beforeAll(() => {
  dir = fs.mkdtempSync(path.join(os.tmpdir(), 'vpt-cli-errors-'));
  scene = path.join(dir, 'scene.json');
  fs.writeFileSync(scene, JSON.stringify({ volume: { procedural: 'sphere', size: 8 }, width: 8, height: 8 }));
});
afterAll(() => fs.rmSync(dir, { recursive: true, force: true }));

/** Run vpt-render; no browser may start for any of these (each fails in well under a second). */
async function render(argv: string[]): Promise<{ code: number; stderr: string; ms: number }> {
  const stderr: string[] = [];
  const io: CliIO = { out: () => {}, err: (l) => stderr.push(l) };
  const t0 = Date.now();
  const code = await runRender(argv, io);
  return { code, stderr: stderr.join('\n'), ms: Date.now() - t0 };
}

const RAW = /ENOENT|EISDIR|EIO|lstat|Unexpected end of JSON|Maximum call stack/;

describe('vpt-render refuses, before rendering', () => {
  it('--root naming a missing folder or a file', async () => {
    const missing = await render([scene, '-o', path.join(dir, 'a.png'), '--root', path.join(dir, 'nope')]);
    expect(missing.code).toBe(1);
    expect(missing.stderr).toMatch(/--root .*nope: no such folder/);
    expect(missing.stderr).not.toMatch(RAW);
    const file = await render([scene, '-o', path.join(dir, 'a.png'), '--root', scene]);
    expect(file.stderr).toMatch(/--root .*scene\.json: is a file, not a folder/);
  });

  it('-o naming a folder, and --pfm naming an unwritable file, before the scene is even read', async () => {
    // The scene file does not exist: the output check must come first to be seen at all.
    const folder = await render([path.join(dir, 'missing.json'), '-o', dir]);
    expect(folder.code).toBe(1);
    expect(folder.stderr).toMatch(/-o .*: is a folder; name the image file/);
    expect(folder.stderr).not.toMatch(RAW);
    const readOnly = path.join(dir, 'read-only.pfm');
    fs.writeFileSync(readOnly, '');
    fs.chmodSync(readOnly, 0o444);
    const ro = await render([path.join(dir, 'missing.json'), '--pfm', readOnly]);
    // root may write anyway: then the scene file is what fails, never a raw error.
    expect(ro.stderr).toMatch(/--pfm .*read-only\.pfm: cannot be overwritten: permission denied|no such file/);
    expect(ro.stderr).not.toMatch(RAW);
  });

  it.skipIf(!fs.existsSync('/proc/version'))('-o /proc/version (a file that takes no writes)', async () => {
    const r = await render([path.join(dir, 'missing.json'), '-o', '/proc/version']);
    expect(r.code).toBe(1);
    expect(r.stderr).toMatch(/-o \/proc\/version: (cannot be overwritten|cannot write in \/proc)/);
    expect(r.stderr).not.toMatch(RAW);
  });

  it('an empty scene file', async () => {
    const empty = path.join(dir, 'empty.json');
    fs.writeFileSync(empty, '  \n');
    const r = await render([empty, '-o', path.join(dir, 'a.png')]);
    expect(r.stderr).toMatch(/Scene file .*empty\.json is empty; it should hold a JSON object/);
    expect(r.stderr).not.toMatch(RAW);
  });

  it('-o with an empty post chain (no LDR image to write)', async () => {
    const s = path.join(dir, 'no-post.json');
    fs.writeFileSync(s, JSON.stringify({ volume: { procedural: 'sphere', size: 8 }, post: [] }));
    const r = await render([s, '-o', path.join(dir, 'a.png')]);
    expect(r.stderr).toMatch(/post chain is empty, so there is no LDR image to write with -o/);
    expect(r.ms).toBeLessThan(5000);
  });
});

describe('scene descriptions refused with the field named', () => {
  const refused = (d: unknown): string => {
    try {
      validateSceneDescription(d);
    } catch (e) {
      return (e as Error).message;
    }
    return 'accepted';
  };

  it('a transfer function nested 5,000 levels deep', () => {
    let deep: unknown = 0;
    for (let i = 0; i < 5000; i++) deep = { x: deep };
    const message = refused({ transferFunction: { dimensions: '1d', points: [deep] } });
    expect(message).toMatch(
      new RegExp(`scene\\.transferFunction\\.points\\[0\\](\\.x)+: nested deeper than ${MAX_SCENE_DEPTH} levels`),
    );
    expect(message).not.toMatch(RAW);
  });

  it('ISO aoRadius given as 1e999 (Infinity) is named as Infinity, not null', () => {
    const d = JSON.parse('{"renderer": "iso", "rendererParams": {"aoRadius": 1e999}}');
    expect(refused(d)).toMatch(
      /scene\.rendererParams\.aoRadius: Infinity is not a finite number .*leave the field out/,
    );
  });

  it('post [tonemap, srgb, denoise]: the denoiser after display steps, named', () => {
    expect(refused({ post: [{ type: 'tonemap' }, { type: 'srgb' }, { type: 'denoise' }] })).toMatch(
      /post step 2 \("denoise"\) must come before post step 0 \("tonemap"\)/,
    );
    expect(refused({ post: [{ type: 'denoise' }, { type: 'tonemap' }, { type: 'srgb' }] })).toBe('accepted');
  });

  it('an ISO surface with an unknown key "colour"', () => {
    const d = { renderer: 'iso', rendererParams: { surfaces: [{ value: 0.5, color: [1, 1, 1], colour: [1, 0, 0] }] } };
    expect(refused(d)).toMatch(/surface 0: unknown key "colour" \(known: value, color, opacity\)/);
  });

  it('an ordinary scene with a lat-long environment passes the shape check quickly', () => {
    const data = new Array(512 * 256 * 3).fill(0.5);
    const t0 = Date.now();
    expect(refused({ environment: { type: 'latlong', width: 512, height: 256, data } })).toBe('accepted');
    expect(Date.now() - t0).toBeLessThan(3000);
  });
});
