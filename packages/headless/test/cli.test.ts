import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { afterAll, beforeAll, describe, expect, it } from 'vitest';
import { rendererNames } from '@vpt/core';
import { parseRenderArgs, parseServeArgs } from '../src/cli/args.js';
import type { CliIO } from '../src/cli/io.js';
import { runRender } from '../src/cli/render-main.js';
import { pageDependencies, runServe } from '../src/cli/serve-main.js';

function capture(): CliIO & { stdout: string[]; stderr: string[] } {
  const stdout: string[] = [],
    stderr: string[] = [];
  return { stdout, stderr, out: (l) => stdout.push(l), err: (l) => stderr.push(l) };
}

let dir: string;
beforeAll(() => {
  dir = fs.mkdtempSync(path.join(os.tmpdir(), 'vpt-cli-'));
});
afterAll(() => fs.rmSync(dir, { recursive: true, force: true }));

describe('vpt-render arguments', () => {
  it('parses every option', () => {
    expect(
      parseRenderArgs([
        's.json',
        '-o',
        'o.png',
        '--pfm',
        'o.pfm',
        '--backend',
        'webgpu',
        '--iterations',
        '8',
        '--width',
        '16',
        '--height',
        '12',
        '--seed',
        '0',
      ]),
    ).toEqual({
      scene: 's.json',
      output: 'o.png',
      pfm: 'o.pfm',
      backend: 'webgpu',
      iterations: 8,
      width: 16,
      height: 12,
      seed: 0,
      keepAlpha: false,
      verbose: false,
      help: false,
    });
    expect(parseRenderArgs(['--pfm=x.pfm', 's.json']).pfm).toBe('x.pfm');
    expect(parseRenderArgs(['--help']).help).toBe(true);
    expect(parseRenderArgs(['s.json', '-o', 'o.png', '--keep-alpha']).keepAlpha).toBe(true);
    // Temporal reuse is off unless --temporal is given.
    expect(parseRenderArgs(['s.json', '-o', 'o.png']).temporal).toBeUndefined();
    expect(parseRenderArgs(['s.json', '-o', 'o.png', '--temporal']).temporal).toBe(true);
  });

  it('rejects bad input with a clear message', () => {
    expect(() => parseRenderArgs(['-o', 'o.png'])).toThrow(/missing the scene file/);
    expect(() => parseRenderArgs(['a.json', 'b.json', '-o', 'o.png'])).toThrow(/one scene file/);
    expect(() => parseRenderArgs(['s.json'])).toThrow(/nothing to write/);
    expect(() => parseRenderArgs(['s.json', '-o', 'o.png', '--backend', 'vulkan'])).toThrow(
      /--backend must be one of auto, webgl2, webgpu/,
    );
    for (const bad of ['0', '-3', '1.5', 'many', ''])
      expect(() => parseRenderArgs(['s.json', '-o', 'o.png', `--iterations=${bad}`])).toThrow(
        /--iterations must be an integer >= 1/,
      );
    expect(() => parseRenderArgs(['s.json', '-o', 'o.png', '--seed=-1'])).toThrow(/--seed must be an integer >= 0/);
    expect(() => parseRenderArgs(['s.json', '-o', 'o.png', '--frobnicate'])).toThrow(/frobnicate/);
  });
});

describe('vpt-render failures exit 1 with one line on stderr', () => {
  const expectFailure = async (argv: string[], pattern: RegExp) => {
    const io = capture();
    expect(await runRender(argv, io)).toBe(1);
    expect(io.stdout).toEqual([]);
    expect(io.stderr).toHaveLength(1);
    expect(io.stderr[0]).not.toContain('\n');
    expect(io.stderr[0]).toMatch(/^vpt-render: /);
    expect(io.stderr[0]).toMatch(pattern);
  };

  it('bad arguments', () => expectFailure(['--iterations', 'x'], /iterations|scene file/));
  it('a missing scene file', () =>
    expectFailure([path.join(dir, 'nope.json'), '-o', 'o.png'], /Cannot read scene file .*nope\.json: no such file/));
  it('a scene file that is not JSON', async () => {
    fs.writeFileSync(path.join(dir, 'bad.json'), '{"width": 64,');
    await expectFailure([path.join(dir, 'bad.json'), '-o', 'o.png'], /bad\.json is not valid JSON/);
  });
  it('a scene description with a bad field', async () => {
    fs.writeFileSync(path.join(dir, 'field.json'), JSON.stringify({ renderer: 'pathtracer' }));
    await expectFailure(
      [path.join(dir, 'field.json'), '-o', 'o.png'],
      // Every renderer of core's catalog, in its order.
      new RegExp(
        `renderer: must be one of ${rendererNames()
          .map((n) => `"${n}"`)
          .join(', ')}, got "pathtracer"`,
      ),
    );
  });
  it('a volume file that does not exist', async () => {
    fs.writeFileSync(
      path.join(dir, 'vol.json'),
      JSON.stringify({ volume: { raw: 'missing.raw', dims: [2, 2, 2], type: 'uint8' } }),
    );
    await expectFailure([path.join(dir, 'vol.json'), '-o', 'o.png'], /Volume file not found: .*missing\.raw/);
  });
  it('no Chromium', async () => {
    fs.writeFileSync(path.join(dir, 'ok.json'), JSON.stringify({ volume: { procedural: 'sphere', size: 8 } }));
    const saved = process.env.VPT_CHROMIUM;
    process.env.VPT_CHROMIUM = path.join(dir, 'no-such-chromium');
    try {
      await expectFailure(
        [path.join(dir, 'ok.json'), '-o', path.join(dir, 'o.png')],
        /Chromium not found .*apt-get install -y chromium/,
      );
    } finally {
      if (saved === undefined) delete process.env.VPT_CHROMIUM;
      else process.env.VPT_CHROMIUM = saved;
    }
    expect(fs.existsSync(path.join(dir, 'o.png'))).toBe(false);
  });
});

describe('vpt-serve', () => {
  it('parses its options', () => {
    expect(parseServeArgs(['--open', 'apps/gallery/index.html', '--check'])).toEqual({
      open: 'apps/gallery/index.html',
      root: undefined,
      port: 0,
      check: true,
      help: false,
    });
    expect(parseServeArgs(['--once', '-p', '8080', 'x.html'])).toMatchObject({
      open: 'x.html',
      port: 8080,
      check: true,
    });
    expect(() => parseServeArgs(['--port', '70000'])).toThrow(/65535/);
  });

  it("finds a page's local dependencies", () => {
    const html = `<script type="importmap">{"imports":{"@vpt/core":"/packages/core/dist/index.js","x":"https://cdn/x.js","three/addons/":"/three/jsm/"}}</script>
      <script type="module" src="./main.js"></script><link rel="stylesheet" href="style.css"><script src="//cdn/y.js"></script>`;
    expect(pageDependencies(html)).toEqual(['/packages/core/dist/index.js', './main.js', 'style.css']);
  });

  it('--check fetches the page and what it loads, once', async () => {
    fs.mkdirSync(path.join(dir, 'site'), { recursive: true });
    fs.writeFileSync(path.join(dir, 'site', 'good.html'), '<script type="module" src="main.js"></script>');
    fs.writeFileSync(path.join(dir, 'site', 'main.js'), '');
    fs.writeFileSync(path.join(dir, 'site', 'broken.html'), '<script type="module" src="gone.js"></script>');
    let io = capture();
    expect((await runServe(['--root', dir, '--open', 'site/good.html', '--check'], io)).code).toBe(0);
    expect(io.stdout[0]).toMatch(/^ok http:\/\/127\.0\.0\.1:\d+\/site\/good\.html$/);
    io = capture();
    expect((await runServe(['--root', dir, '--open', 'site/broken.html', '--check'], io)).code).toBe(1);
    expect(io.stderr[0]).toMatch(/gone\.js \(HTTP 404\)/);
    io = capture();
    expect((await runServe(['--root', dir, '--open', 'site/none.html', '--once'], io)).code).toBe(1);
    expect(io.stderr[0]).toMatch(/HTTP 404/);
  });

  it('without --check it keeps serving and prints the page URL', async () => {
    const io = capture();
    const { code, server } = await runServe(['--root', dir, '--open', '/site/good.html'], io);
    try {
      expect(code).toBeNull();
      expect(io.stdout[0]).toBe(`${server!.url}site/good.html`);
      expect((await fetch(io.stdout[0])).status).toBe(200);
      // Outside the workspace root the installed packages are mounted for the import maps.
      expect((await fetch(new URL('/packages/headless/page/index.html', server!.url))).status).toBe(200);
    } finally {
      await server?.close();
    }
  });
});
