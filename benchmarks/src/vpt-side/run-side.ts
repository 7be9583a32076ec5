/**
 * `pnpm bench --vpt DIR [--quick] [--size N] [--rounds R] [--volume N] [--scale X] [--pairs single,multiple,eam,mip]
 * [--mcrt-params JSON] [--eam-params JSON] [--mip-params JSON]` (the table: SIDE_CLI in bench-cli.mjs): the side-by-side
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
import { CliArgsError, cliUsage, parseCli, type CliValues } from '@vpt/cli-options';
import { SIDE_CLI } from '../bench-cli.mjs';
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

/** Parse the side-by-side suite's arguments (SIDE_CLI); prints the usage or the error and exits on --help or bad input. */
function sideArgsOrExit(argv: readonly string[]): CliValues<typeof SIDE_CLI> {
  try {
    const parsed = parseCli(SIDE_CLI, argv);
    if (!parsed.help) return parsed.values;
  } catch (e) {
    if (!(e instanceof CliArgsError)) throw e;
    console.error(`${SIDE_CLI.name}: ${e.message} (--help lists the options)`);
    process.exit(2);
  }
  console.log(cliUsage(SIDE_CLI));
  process.exit(0);
}

/** `argv`: the arguments after the script (process.argv.slice(2)). */
export async function runSide(argv: readonly string[]): Promise<void> {
  const args = sideArgsOrExit(argv);
  // Relative to where `pnpm bench` was typed (pnpm runs the script in benchmarks/ and keeps that folder in INIT_CWD).
  const given = args.vpt ?? '';
  const dir = given && path.resolve(process.env.INIT_CWD ?? process.cwd(), given);
  const build = dir ? vptBuildDir(dir) : null;
  if (!build) {
    console.log(
      `vpt-side: skipped: no VPT build at ${given ? JSON.stringify(dir) : '(no --vpt DIR given)'} ` +
        '(DIR must be a clone of terier/vpt built into DIR/build, or that build folder)',
    );
    return;
  }
  const quick = args.quick;
  const size = args.size ?? (quick ? 32 : 128);
  const volumeSide = args.volume ?? (quick ? 32 : 128);
  const rounds = args.rounds ?? (quick ? 1 : 3);
  const scale = quick ? 1 / 64 : (args.scale ?? 1);
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
      pairs: args.pairs,
      rendererParams: Object.fromEntries(
        (['mcrt', 'eam', 'mip'] as const).flatMap((r) => {
          const params = args[`${r}-params`];
          return params === undefined ? [] : [[r, params as Record<string, unknown>]];
        }),
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
