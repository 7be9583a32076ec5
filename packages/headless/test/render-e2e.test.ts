import { execFile } from 'node:child_process';
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import { promisify } from 'node:util';
import { afterAll, describe, expect, it } from 'vitest';
import { chromiumExecutable } from '../src/chromium.js';
import { decodePFM, decodePNG } from '../src/image-io.js';

// The built CLIs against the real, built packages: runs after `pnpm run build`.
const run = promisify(execFile);
const pkg = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '..');
const packages = path.resolve(pkg, '..');
const built = [
  'headless/dist/cli/render.js',
  'core/dist/index.js',
  'renderer-mip/dist/index.js',
  'renderer-eam/dist/index.js',
  'post/dist/index.js',
].every((f) => fs.existsSync(path.join(packages, f)));

describe.skipIf(!built || !fs.existsSync(chromiumExecutable()))('vpt-render end to end', () => {
  const dir = fs.mkdtempSync(path.join(os.tmpdir(), 'vpt-e2e-'));
  afterAll(() => fs.rmSync(dir, { recursive: true, force: true }));
  const scene = path.join(dir, 'scene.json');
  fs.writeFileSync(
    scene,
    JSON.stringify({
      width: 16,
      height: 12,
      renderer: 'mip',
      volume: { procedural: 'sphere', size: 16 },
      environment: { type: 'constant', radiance: [0, 0, 0] },
    }),
  );

  it.each(['webgl2', 'webgpu'])(
    'smoke: vpt-render renders a MIP sphere on %s to PNG and PFM (centre bright, corner empty)',
    async (backend) => {
      const png = path.join(dir, `${backend}.png`),
        pfm = path.join(dir, `${backend}.pfm`);
      const { stdout } = await run(
        process.execPath,
        [
          path.join(pkg, 'dist/cli/render.js'),
          scene,
          '-o',
          png,
          '--pfm',
          pfm,
          '--backend',
          backend,
          '--iterations',
          '2',
        ],
        { timeout: 180_000 },
      );
      const lines = stdout.trim().split('\n');
      expect(lines).toHaveLength(1);
      const t = JSON.parse(lines[0]);
      expect(t).toMatchObject({ iterations: 2, width: 16, height: 12, backend });
      expect(t.totalMs).toBeGreaterThan(0);
      const ldr = decodePNG(fs.readFileSync(png));
      const hdr = decodePFM(fs.readFileSync(pfm));
      expect([ldr.width, ldr.height, hdr.width, hdr.height]).toEqual([16, 12, 16, 12]);
      const centre = (6 * 16 + 8) * 4;
      expect(hdr.rgba[centre]).toBeGreaterThan(0.5); // the sphere's value 1 through the middle
      expect(hdr.rgba[0]).toBe(0); // a corner ray misses the box
      expect(ldr.rgba[centre]).toBeGreaterThan(ldr.rgba[0]);
    },
    240_000,
  );

  it('smoke: vpt-serve --check finds the headless page and everything it imports', async () => {
    const { stdout } = await run(
      process.execPath,
      [path.join(pkg, 'dist/cli/serve.js'), '--check', '--open', 'packages/headless/page/index.html'],
      { timeout: 30_000 },
    );
    expect(stdout).toMatch(/^ok http:\/\/127\.0\.0\.1:\d+\/packages\/headless\/page\/index\.html/);
  });
});
