// vpt-render and vpt-serve answer --help from their option tables and refuse bad flags,
// naming them, before doing any work (no scene read, no server, no browser).
import { describe, expect, it } from 'vitest';
import { RENDER_CLI, SERVE_CLI } from '../src/cli/args.js';
import type { CliIO } from '../src/cli/io.js';
import { runRender } from '../src/cli/render-main.js';
import { runServe } from '../src/cli/serve-main.js';

function capture(): CliIO & { stdout: string[]; stderr: string[] } {
  const stdout: string[] = [],
    stderr: string[] = [];
  return { stdout, stderr, out: (l) => stdout.push(l), err: (l) => stderr.push(l) };
}

describe('vpt-render --help', () => {
  it('prints the usage with every option and exits 0 without reading the scene', async () => {
    const io = capture();
    // The scene does not exist: --help must win before anything reads it.
    expect(await runRender(['/nonexistent/scene.json', '-o', '/nonexistent/o.png', '--help'], io)).toBe(0);
    expect(io.stderr).toEqual([]);
    const text = io.stdout.join('\n');
    expect(text).toMatch(/^Usage: vpt-render scene\.json/);
    for (const name of Object.keys(RENDER_CLI.options)) expect(text).toContain(`--${name}`);
  });

  it('says what a scene file holds: the volume kinds, and that a light points toward the light', async () => {
    const io = capture();
    expect(await runRender(['-h'], io)).toBe(0);
    const text = io.stdout.join('\n');
    for (const kind of ['"sidecar"', '"raw"', '"zarr"', '"procedural"']) expect(text).toContain(kind);
    expect(text).toMatch(/direction points from the scene TOWARD the light/);
    expect(text).toContain('scene-description.ts');
  });

  it('refuses an unknown flag and a non-number, naming them', async () => {
    let io = capture();
    expect(await runRender(['s.json', '-o', 'o.png', '--frobnicate'], io)).toBe(1);
    expect(io.stderr).toHaveLength(1);
    expect(io.stderr[0]).toMatch(/^vpt-render: .*--frobnicate/);
    io = capture();
    expect(await runRender(['s.json', '-o', 'o.png', '--width', 'abc'], io)).toBe(1);
    expect(io.stderr[0]).toMatch(/--width must be an integer >= 1, got "abc"/);
  });
});

describe('vpt-serve --help', () => {
  it('prints the usage with every option and exits 0 without serving', async () => {
    const io = capture();
    const { code, server } = await runServe(['--help', '--port', '1'], io);
    expect(code).toBe(0);
    expect(server).toBeUndefined();
    const text = io.stdout.join('\n');
    expect(text).toMatch(/^Usage: vpt-serve/);
    for (const name of Object.keys(SERVE_CLI.options)) expect(text).toContain(`--${name}`);
  });

  it('refuses an unknown flag and a non-number, naming them', async () => {
    let io = capture();
    expect((await runServe(['--bogus'], io)).code).toBe(1);
    expect(io.stderr[0]).toMatch(/^vpt-serve: .*--bogus/);
    io = capture();
    expect((await runServe(['--port', 'eighty'], io)).code).toBe(1);
    expect(io.stderr[0]).toMatch(/--port must be an integer from 0 to 65535, got "eighty"/);
  });
});
