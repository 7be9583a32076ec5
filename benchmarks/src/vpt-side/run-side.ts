/**
 * `pnpm bench --vpt DIR [--quick] [--size N] [--rounds R] [--volume N] [--pairs single,multiple,eam,mip]
 * [--mcrt-params JSON] [--eam-params JSON] [--mip-params JSON]`: the side-by-side
 * suite against a build of the original VPT (DIR = a clone holding build/, or the build
 * folder itself; never stored in this repository). Serves that build read-only under /vpt/
 * from the same static server as vpt's page, so both run in one page of one Chromium.
 * Without DIR's build it says so and exits 0, so nothing depends on VPT being present.
 */
import { existsSync, mkdirSync, mkdtempSync, writeFileSync } from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import { openVptPage, encodePNG, CHROMIUM_FLAGS } from '@vpt/headless';
import { machineRecord } from '../environment.js';
import { sideMarkdown, vptSide } from '../suites/vpt-side.js';
import { anchorVolume } from './anchor-scene.js';
import { installSidePage } from './side-page.js';

/** DIR's VPT build folder (DIR/build or DIR), or null when neither holds VPT's js/renderers. */
export function vptBuildDir(dir: string): string | null {
  for (const candidate of [path.join(dir, 'build'), dir])
    if (
      existsSync(path.join(candidate, 'js', 'renderers', 'RendererFactory.js')) &&
      existsSync(path.join(candidate, 'shaders.json'))
    )
      return path.resolve(candidate);
  return null;
}

export async function runSide(argv: readonly string[]): Promise<void> {
  const arg = (name: string, fallback: string) => {
    const i = argv.indexOf(`--${name}`);
    return i >= 0 && argv[i + 1] && !argv[i + 1].startsWith('--') ? argv[i + 1] : fallback;
  };
  // Relative to where `pnpm bench` was typed (pnpm runs the script in benchmarks/ and keeps that folder in INIT_CWD).
  const given = arg('vpt', '');
  const dir = given && path.resolve(process.env.INIT_CWD ?? process.cwd(), given);
  const build = dir ? vptBuildDir(dir) : null;
  if (!build) {
    console.log(
      `vpt-side: skipped: no VPT build at ${given ? JSON.stringify(dir) : '(no --vpt DIR given)'} ` +
        '(DIR must be a clone of terier/vpt built into DIR/build, or that build folder)',
    );
    return;
  }
  const quick = argv.includes('--quick');
  const size = Number(arg('size', quick ? '32' : '128'));
  const volumeSide = Number(arg('volume', quick ? '32' : '128'));
  const rounds = Number(arg('rounds', quick ? '1' : '3'));
  const scale = quick ? 1 / 64 : Number(arg('scale', '1'));
  const started = Date.now();
  const log = (line: string) => console.log(`[${((Date.now() - started) / 1000).toFixed(0).padStart(5)} s] ${line}`);

  const volumeDir = mkdtempSync(path.join(os.tmpdir(), 'vpt-anchor-'));
  writeFileSync(path.join(volumeDir, `anchor-${volumeSide}.raw`), anchorVolume(volumeSide));
  const out = path.join(
    fileURLToPath(new URL('../..', import.meta.url)),
    'results',
    `${new Date().toISOString().replace(/[:.]/g, '-')}-vpt-side`,
  );
  mkdirSync(out, { recursive: true });
  const session = await openVptPage();
  try {
    const vptBase = session.mount(build, '/vpt/');
    const volumeBase = session.mount(volumeDir);
    await session.page.evaluate(installSidePage);
    const results = await vptSide(session.page, {
      vptBase,
      volumeUrl: `${volumeBase}anchor-${volumeSide}.raw`,
      volumeSide,
      size,
      rounds,
      scale,
      budgetMs: quick ? 5_000 : 300_000,
      pairs: arg('pairs', '') ? arg('pairs', '').split(',') : undefined,
      rendererParams: Object.fromEntries(
        ['mcrt', 'eam', 'mip'].flatMap((r) =>
          arg(`${r}-params`, '') ? [[r, JSON.parse(arg(`${r}-params`, ''))]] : [],
        ),
      ),
      log,
      saveImage: (name, rgba, side) =>
        writeFileSync(
          path.join(out, `${name}.png`),
          encodePNG(new Uint8Array(Buffer.from(rgba, 'base64')), side, side),
        ),
    });
    const markdown = sideMarkdown(results);
    console.log(markdown);
    const machine = machineRecord(await session.browser.version(), CHROMIUM_FLAGS);
    writeFileSync(path.join(out, 'results.json'), JSON.stringify({ machine, vptBuild: build, ...results }, null, 2));
    writeFileSync(path.join(out, 'results.md'), markdown + '\n');
    log(`wrote ${out}`);
  } finally {
    await session.close();
  }
}
