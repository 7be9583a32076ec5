// The packages as a user gets them: `pnpm pack` every package, install the tarballs with
// npm into a scratch app in a temp folder outside the workspace, bundle the app with
// Rollup, and open it in headless Chromium. The README's two snippets (taken from
// README.md itself, only their size shrunk for SwiftShader) and a bundled app that
// imports '@vpt/viewer' must show the head clearly (object against background, measured
// on pixels), without console errors, with one copy of three and one of lit.
// Needs the built packages (`pnpm test` builds first) and npm with registry access
// (three, lit and the loaders' parsers come from the registry; --prefer-offline uses the cache).
import { execFile } from 'node:child_process';
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { promisify } from 'node:util';
import { afterAll, beforeAll, describe, expect, it } from 'vitest';
import { rollup } from 'rollup';
import { nodeResolve } from '@rollup/plugin-node-resolve';
import commonjs from '@rollup/plugin-commonjs';
import ts from 'typescript';
import type { Browser } from 'puppeteer-core';
import { encodePNG, launchChromium, startStaticServer, type StaticServer } from '../packages/headless/src/index.js';
import { RENDERER_CATALOG } from '@vpt/core';
import { ROOT } from './helpers/viewer-page.js';

const run = promisify(execFile);
/** Package folders under packages/: every renderer package of core's catalog among them. */
const PACKAGES = [
  'core',
  'post',
  ...new Set(RENDERER_CATALOG.map((e) => e.packageName.replace(/^@vpt\//, ''))),
  'loaders',
  'three',
  'viewer',
  'headless',
  'cli-options',
];
/** What a browser app installs (headless is a Node tool with Chromium drivers: packed and checked, not installed). */
// headless and its argument parser are Node-only.
const BROWSER_PACKAGES = PACKAGES.filter((p) => p !== 'headless' && p !== 'cli-options');
const HEAD = 'mri_head_volpack_brainsmall_128x128x84_uint8';
const NO_FAVICON = '<link rel="icon" href="data:,">';

let tmp = '';
let app = '';
const tarballs: Record<string, string> = {};
let server: StaticServer | null = null;
let browser: Browser | null = null;
let bundleOutput: { fileName: string; code: string }[] = [];

/** The first fenced block of this language after a README heading. */
function readmeSnippet(heading: string, lang: string): string {
  const text = fs.readFileSync(path.join(ROOT, 'README.md'), 'utf8');
  const at = text.indexOf(`## ${heading}`);
  const m = new RegExp('```' + lang + '\\n([\\s\\S]*?)```').exec(text.slice(at));
  if (at < 0 || !m) throw new Error(`README.md has no ${lang} block under "${heading}"`);
  return m[1];
}

beforeAll(async () => {
  tmp = fs.mkdtempSync(path.join(os.tmpdir(), 'vpt-consumer-'));
  for (const p of PACKAGES) {
    const { stdout } = await run('pnpm', ['pack', '--pack-destination', tmp], { cwd: path.join(ROOT, 'packages', p) });
    tarballs[p] = stdout.trim().split('\n').pop()!.trim();
  }
  app = path.join(tmp, 'app');
  fs.mkdirSync(app);
  fs.writeFileSync(
    path.join(app, 'package.json'),
    JSON.stringify({ name: 'vpt-consumer', private: true, type: 'module' }),
  );
  await run(
    'npm',
    [
      'install',
      '--prefer-offline',
      '--no-audit',
      '--no-fund',
      '--loglevel=error',
      ...BROWSER_PACKAGES.map((p) => tarballs[p]),
    ],
    { cwd: app, timeout: 150_000 },
  );
  // The data, as a user copies it next to the page.
  fs.copyFileSync(path.join(ROOT, 'data', `${HEAD}.json`), path.join(app, 'head.json'));
  fs.copyFileSync(path.join(ROOT, 'data', `${HEAD}.raw`), path.join(app, `${HEAD}.raw`));

  // "Use it in a page": the snippet as written, a plain page, only the bundle script.
  const pageSnippet = readmeSnippet('Use it in a page', 'html').replace(
    /width: \d+px; height: \d+px/,
    'width: 96px; height: 72px',
  );
  fs.writeFileSync(
    path.join(app, 'page.html'),
    `<!doctype html><meta charset="utf-8">${NO_FAVICON}<body style="margin:0">\n${pageSnippet}</body>`,
  );

  // "Use it from code": the snippet in a module of a bundled app, TypeScript as written (it
  // type-checks: packages/core/test/readme-examples.test.ts), its types stripped here.
  const code = readmeSnippet('Use it from code', 'ts').replace('width: 512, height: 512', 'width: 64, height: 64');
  const js = ts.transpileModule(`${code}\n(window as any).__hdr = Array.from(hdr);\n`, {
    compilerOptions: { target: ts.ScriptTarget.ES2022, module: ts.ModuleKind.ESNext, verbatimModuleSyntax: true },
  }).outputText;
  fs.writeFileSync(path.join(app, 'code.js'), js);
  fs.writeFileSync(
    path.join(app, 'code.html'),
    `<!doctype html><meta charset="utf-8">${NO_FAVICON}<body><canvas></canvas><script type="module" src="dist/code.js"></script></body>`,
  );

  // "Use it in a three.js scene": the snippet in a bundled app, with the volume and TF it
  // takes from the next section made here; the canvas is read in the frame that drew it.
  const threeCode = readmeSnippet('Use it in a three.js scene', 'ts');
  fs.writeFileSync(
    path.join(app, 'three.js'),
    [
      "import { createProceduralVolume, rampTransferFunction } from '@vpt/core';",
      "const canvas = document.querySelector('canvas');",
      'const volume = createProceduralVolume("blob", 32);',
      'const transferFunction = rampTransferFunction([1, 0.8, 0.6]);',
      threeCode,
      'let frames = 0;',
      'renderer.setAnimationLoop(() => {',
      '  compositor.render(scene, camera);',
      '  if (++frames !== 8) return;',
      '  const gl = renderer.getContext();',
      '  const px = new Uint8Array(64 * 64 * 4);',
      '  gl.readPixels(0, 0, 64, 64, gl.RGBA, gl.UNSIGNED_BYTE, px);',
      '  window.__three = { ldr: Array.from(px), samples: head.sampleCount };',
      '});',
    ].join('\n'),
  );
  fs.writeFileSync(
    path.join(app, 'three.html'),
    `<!doctype html><meta charset="utf-8">${NO_FAVICON}<body><canvas width="64" height="64"></canvas><script type="module" src="dist/three.js"></script></body>`,
  );

  // The element in a bundled app, with only src set; the app uses three and lit itself too.
  fs.writeFileSync(
    path.join(app, 'element.js'),
    [
      "import '@vpt/viewer';",
      "import { LitElement } from 'lit';",
      "import { Vector3 } from 'three';",
      'window.__appDeps = [typeof LitElement, new Vector3(1, 2, 3).length()];',
    ].join('\n'),
  );
  fs.writeFileSync(
    path.join(app, 'element.html'),
    `<!doctype html><meta charset="utf-8">${NO_FAVICON}<body style="margin:0">
<script type="module" src="dist/element.js"></script><vpt-viewer src="head.json" style="width: 96px; height: 72px"></vpt-viewer></body>`,
  );

  const bundle = await rollup({
    input: {
      code: path.join(app, 'code.js'),
      element: path.join(app, 'element.js'),
      three: path.join(app, 'three.js'),
    },
    plugins: [nodeResolve({ browser: true, rootDir: app }), commonjs()],
    onwarn: (w, warn) => {
      if (w.code !== 'CIRCULAR_DEPENDENCY' && w.code !== 'THIS_IS_UNDEFINED') warn(w);
    },
  });
  const { output } = await bundle.write({ dir: path.join(app, 'dist'), format: 'es' });
  await bundle.close();
  bundleOutput = output
    .filter((o) => o.type === 'chunk')
    .map((o) => ({ fileName: o.fileName, code: (o as { code: string }).code }));
  // As the loaders' README says: a bundler that does not copy the worker gets it copied.
  fs.cpSync(path.join(app, 'node_modules/@vpt/loaders/dist/worker'), path.join(app, 'dist'), {
    recursive: true,
    filter: (f) => !/\.(d\.ts|map)$/.test(f),
  });

  server = await startStaticServer(app);
  browser = await launchChromium({ webgpu: true });
}, 240_000);

afterAll(async () => {
  await browser?.close();
  await server?.close();
  if (tmp) fs.rmSync(tmp, { recursive: true, force: true });
});

/** Open a page of the app; resolve with what `ready` returns and the console errors. */
async function open<T>(page: string, ready: string, read: string): Promise<{ value: T; errors: string[] }> {
  const p = await browser!.newPage();
  const errors: string[] = [];
  p.on('console', (m) => {
    if (m.type() === 'error') errors.push(m.text());
  });
  p.on('pageerror', (e) => errors.push(String(e)));
  try {
    await p.goto(`http://127.0.0.1:${server!.port}/${page}`);
    await p.waitForFunction(ready, { timeout: 150_000, polling: 200 });
    return { value: (await p.evaluate(read)) as T, errors };
  } finally {
    await p.close();
  }
}

/** Keep what the page showed in out/consumer/ (gitignored) for a person to look at. */
function keep(name: string, rgba: ArrayLike<number>, width: number, height: number, scale = 255): void {
  const bytes = Uint8Array.from({ length: width * height * 4 }, (_, i) =>
    i % 4 === 3 ? 255 : Math.round(255 * Math.min(1, Math.max(0, rgba[i] / scale)) ** (scale === 1 ? 1 / 2.2 : 1)),
  );
  fs.mkdirSync(path.join(ROOT, 'out/consumer'), { recursive: true });
  fs.writeFileSync(path.join(ROOT, 'out/consumer', name), encodePNG(bytes, width, height));
}

/**
 * Object against background: the background is the mean of the image's four corners
 * (the framed head leaves them empty); an object pixel differs from it by more than 0.1
 * in luminance (0..1). Returns the fraction of object pixels and their mean difference.
 */
function contrast(
  rgba: ArrayLike<number>,
  width: number,
  height: number,
  scale: number,
): { coverage: number; difference: number } {
  const lum = (i: number) => (0.2126 * rgba[4 * i] + 0.7152 * rgba[4 * i + 1] + 0.0722 * rgba[4 * i + 2]) / scale;
  const corners = [0, width - 1, (height - 1) * width, height * width - 1];
  const bg = corners.reduce((a, i) => a + lum(i), 0) / 4;
  let n = 0,
    sum = 0;
  for (let i = 0; i < width * height; i++) {
    const d = Math.abs(Math.min(1, lum(i)) - Math.min(1, bg));
    if (d > 0.1) {
      n++;
      sum += d;
    }
  }
  return { coverage: n / (width * height), difference: n ? sum / n : 0 };
}

describe('the packed packages in a fresh npm app', () => {
  it('every tarball has LICENSE and README, no workspace: ranges, and the viewer takes three and lit as peers', async () => {
    for (const p of PACKAGES) {
      const { stdout: list } = await run('tar', ['-tzf', tarballs[p]]);
      expect(list.split('\n'), p).toEqual(
        expect.arrayContaining(['package/LICENSE', 'package/README.md', 'package/package.json']),
      );
      const { stdout: json } = await run('tar', ['-xzOf', tarballs[p], 'package/package.json']);
      expect(json, p).not.toContain('workspace:');
    }
    const viewer = JSON.parse(fs.readFileSync(path.join(app, 'node_modules/@vpt/viewer/package.json'), 'utf8'));
    expect(Object.keys(viewer.peerDependencies).sort()).toEqual(['lit', 'three']);
    expect(viewer.dependencies.three).toBeUndefined();
  });

  it('installs as real packages (no links into the workspace), one three and one lit, sourcemaps inside each package', () => {
    const vpt = path.join(app, 'node_modules/@vpt');
    for (const p of BROWSER_PACKAGES) expect(fs.lstatSync(path.join(vpt, p)).isSymbolicLink(), p).toBe(false);
    const copies = (name: string) => {
      const found: string[] = [];
      const walk = (dir: string) => {
        for (const e of fs.readdirSync(dir, { withFileTypes: true })) {
          if (!e.isDirectory()) continue;
          const full = path.join(dir, e.name);
          // The npm package itself, not a scoped one of the same name (@vpt/three).
          if (e.name === name && !dir.endsWith('@vpt') && fs.existsSync(path.join(full, 'package.json')))
            found.push(full);
          if (e.name === 'node_modules' || e.name.startsWith('@') || dir.endsWith('node_modules')) walk(full);
        }
      };
      walk(path.join(app, 'node_modules'));
      return found;
    };
    expect(copies('three')).toHaveLength(1);
    expect(copies('lit')).toHaveLength(1);
    for (const p of BROWSER_PACKAGES) {
      const dir = path.join(vpt, p);
      const maps = fs
        .readdirSync(dir, { recursive: true })
        .map(String)
        .filter((f) => f.endsWith('.js.map'));
      for (const m of maps) {
        const map = JSON.parse(fs.readFileSync(path.join(dir, m), 'utf8'));
        for (const [i, s] of (map.sources as string[]).entries()) {
          const resolved = path.resolve(path.dirname(path.join(dir, m)), s);
          expect(resolved.startsWith(dir + path.sep), `${p}/${m} → ${s}`).toBe(true);
          expect(typeof map.sourcesContent?.[i], `${p}/${m}: sourcesContent`).toBe('string');
        }
      }
    }
  });

  it('the Rollup bundle of the app holds one copy of three and one of lit', () => {
    const all = bundleOutput.map((o) => o.code).join('\n');
    expect(all.match(/const REVISION\$?\d* = '\d+'/g) ?? []).toHaveLength(1);
    // Each Lit module registers its version once, in a line kept for this kind of check.
    expect(all.match(/litHtmlVersions ?\?\?= ?\[\]\)\.push/g) ?? []).toHaveLength(1);
    expect(all.match(/litElementVersions ?\?\?= ?\[\]\)\.push/g) ?? []).toHaveLength(1);
  });

  it('"Use it in a page" as written shows the head clearly, without console errors', async () => {
    const { value, errors } = await open<{ ldr: number[]; width: number; height: number; renderer: string }>(
      'page.html',
      "document.querySelector('vpt-viewer')?.samples >= 6",
      "(async () => { const el = document.querySelector('vpt-viewer'); const c = el.context; return { ldr: Array.from(await c.readLDR()), ...c.size, renderer: c.renderer.name }; })()",
    );
    expect(errors).toEqual([]);
    expect(value.renderer).toBe('mcrt');
    keep('readme-page.png', value.ldr, value.width, value.height);
    const c = contrast(value.ldr, value.width, value.height, 255);
    expect(c.coverage).toBeGreaterThan(0.04);
    expect(c.difference).toBeGreaterThan(0.2);
  });

  it('"Use it from code" as written, bundled, renders the head clearly, without console errors', async () => {
    const { value, errors } = await open<number[]>('code.html', 'Array.isArray(window.__hdr)', 'window.__hdr');
    expect(errors).toEqual([]);
    expect(value).toHaveLength(64 * 64 * 4);
    expect(value.every(Number.isFinite)).toBe(true);
    keep('readme-code.png', value, 64, 64, 1);
    const c = contrast(value, 64, 64, 1);
    expect(c.coverage).toBeGreaterThan(0.04);
    expect(c.difference).toBeGreaterThan(0.2);
  });

  it('"Use it in a three.js scene" as written, bundled, shows the volume and the mesh, without console errors', async () => {
    const { value, errors } = await open<{ ldr: number[]; samples: number }>(
      'three.html',
      'window.__three !== undefined',
      'window.__three',
    );
    keep('readme-three.png', value.ldr, 64, 64);
    expect(errors).toEqual([]);
    // The first frames make the vpt context (asynchronously); the later ones add a sample each.
    expect(value.samples).toBeGreaterThan(0);
    const c = contrast(value.ldr, 64, 64, 255);
    expect(c.coverage).toBeGreaterThan(0.04);
    expect(c.difference).toBeGreaterThan(0.2);
  });

  it('a bundled app with import "@vpt/viewer" and only src set shows the head clearly, without console errors', async () => {
    const { value, errors } = await open<{
      ldr: number[];
      width: number;
      height: number;
      deps: unknown[];
      up: number[];
    }>(
      'element.html',
      "document.querySelector('vpt-viewer')?.samples >= 6",
      "(async () => { const el = document.querySelector('vpt-viewer'); const c = el.context; return { ldr: Array.from(await c.readLDR()), ...c.size, deps: window.__appDeps, up: el.camera.up }; })()",
    );
    expect(errors).toEqual([]);
    expect(value.deps[0]).toBe('function');
    expect(value.deps[1]).toBeCloseTo(Math.hypot(1, 2, 3), 6);
    expect(value.up).toEqual([0, -1, 0]); // superior up for this head (its y runs crown → neck)
    keep('bundled-element.png', value.ldr, value.width, value.height);
    const c = contrast(value.ldr, value.width, value.height, 255);
    expect(c.coverage).toBeGreaterThan(0.04);
    expect(c.difference).toBeGreaterThan(0.2);
  });
});
