// Issue 28: README's "Use it from code" failed tsc (canvas never defined, the camera literal
// not a Vec3) while the consumer test ran it as JavaScript, and the renderer READMEs showed
// mangled examples. This type-checks the examples as a user's strict TypeScript would: the
// root README's block as it stands, each renderer README's block with only the canvas and
// the scene it leaves to core's README declared.
import fs from 'node:fs';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import ts from 'typescript';
import { describe, expect, it } from 'vitest';

const ROOT = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '..', '..', '..');
const RENDERERS = ['renderer-eam', 'renderer-mip', 'renderer-iso', 'renderer-mcrt'];

function tsBlocks(file: string, heading?: string): string[] {
  let text = fs.readFileSync(file, 'utf8');
  if (heading) {
    const at = text.indexOf(`## ${heading}`);
    expect(at, `${file} has a "${heading}" section`).toBeGreaterThanOrEqual(0);
    text = text.slice(at, text.indexOf('\n## ', at + 3) >>> 0 || undefined);
  }
  return [...text.matchAll(/```ts\n([\s\S]*?)```/g)].map((m) => m[1]);
}

/** Diagnostics of these modules, strict, against the workspace's package sources. */
function typecheck(files: Record<string, string>): string[] {
  const dir = fs.mkdtempSync(path.join(ROOT, 'out', '.readme-check-'));
  try {
    const names = Object.entries(files).map(([name, code]) => {
      const f = path.join(dir, name);
      fs.writeFileSync(f, `${code}\nexport {};\n`);
      return f;
    });
    const program = ts.createProgram(names, {
      target: ts.ScriptTarget.ES2022,
      module: ts.ModuleKind.ESNext,
      moduleResolution: ts.ModuleResolutionKind.Bundler,
      lib: ['lib.es2022.d.ts', 'lib.dom.d.ts', 'lib.dom.iterable.d.ts'],
      strict: true,
      noEmit: true,
      skipLibCheck: true,
      types: ['@webgpu/types'],
      typeRoots: [path.join(ROOT, 'node_modules', '@types'), path.join(ROOT, 'node_modules')],
      paths: { '@vpt/*': [path.join(ROOT, 'packages', '*', 'src', 'index.ts')] },
    });
    return ts
      .getPreEmitDiagnostics(program)
      .filter((d) => d.file && names.includes(d.file.fileName))
      .map(
        (d) => `${path.basename(d.file!.fileName)}: TS${d.code} ${ts.flattenDiagnosticMessageText(d.messageText, ' ')}`,
      );
  } finally {
    fs.rmSync(dir, { recursive: true, force: true });
  }
}

describe('README examples type-check', () => {
  it('the root README and every renderer README', () => {
    fs.mkdirSync(path.join(ROOT, 'out'), { recursive: true });
    const files: Record<string, string> = {};
    const [code] = tsBlocks(path.join(ROOT, 'README.md'), 'Use it from code');
    files['root-readme.ts'] = code;
    for (const pkg of RENDERERS) {
      const [block] = tsBlocks(path.join(ROOT, 'packages', pkg, 'README.md'));
      expect(block, `${pkg}/README.md has a ts example`).toBeDefined();
      files[`${pkg}.ts`] =
        `declare const canvas: HTMLCanvasElement;\ndeclare const scene: import('@vpt/core').Scene;\n${block}`;
    }
    expect(typecheck(files)).toEqual([]);
  }, 120_000);

  it('would catch the bugs it was written for', () => {
    const broken = typecheck({
      'broken.ts': [
        "import { RenderContext, type Camera } from '@vpt/core';",
        'const camera = { position: [0, 0, 2], target: [0, 0, 0], up: [0, 1, 0], fovy: 0.7 };',
        'const c: Camera = camera;',
        'await RenderContext.create({ canvas, width: 8, height: 8, renderer: null as never });',
      ].join('\n'),
    });
    expect(broken.join('\n')).toMatch(/TS2322/);
    expect(broken.join('\n')).toMatch(/TS18004 No value exists in scope for the shorthand property 'canvas'/);
  }, 120_000);
});
