// Every script of the repository (scripts/, tools/, benchmarks/, apps/*) parses its command
// line with this package: --help prints its usage and exits 0, an unknown flag and a
// non-number are refused with exit 2 and a message naming them. All of it before any work:
// the scripts run with only node on PATH (no pnpm to build with) and, where they need a
// built package, they import it only after parsing, so this passes on an unbuilt tree.
// (vpt-render, vpt-serve and pnpm bench have their own tests: packages/headless/test/cli-help.test.ts,
// benchmarks/test/bench-cli.test.ts.)
import { spawnSync } from 'node:child_process';
import fs from 'node:fs';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import { afterEach, describe, expect, it, vi } from 'vitest';

const ROOT = fileURLToPath(new URL('../../..', import.meta.url));

/** Each script, with arguments whose only fault is a non-number where a number belongs. */
const SCRIPTS: Record<string, { notANumber?: { argv: string[]; names: string } }> = {
  'scripts/fetch-corpus.mjs': {},
  'scripts/fetch-data.mjs': {},
  'scripts/gen-renderers.mjs': {},
  'scripts/mutations.mjs': {},
  'scripts/raw-to-ome-zarr.mjs': { notANumber: { argv: ['a.json', 'b.zarr', '--levels', 'abc'], names: '--levels' } },
  'tools/dev-browser.mjs': { notANumber: { argv: ['page.html', 'soon'], names: 'TIMEOUT' } },
  'tools/screenshot.mjs': { notANumber: { argv: ['http://x/', 'o.png', 'NaN'], names: 'WAIT_MS' } },
  'tools/viewer-screenshots.mjs': {},
  'benchmarks/bricking.mjs': { notANumber: { argv: ['--size', 'abc'], names: '--size' } },
  'benchmarks/bricking-channels.mjs': { notANumber: { argv: ['--size', 'abc'], names: '--size' } },
  'benchmarks/time-series-read.mjs': { notANumber: { argv: ['--steps', 'many'], names: '--steps' } },
  'benchmarks/clip-cost.mjs': { notANumber: { argv: ['--rounds', 'many'], names: '--rounds' } },
  'benchmarks/denoise-error.mjs': { notANumber: { argv: ['--seeds', 'few'], names: '--seeds' } },
  'benchmarks/blue-noise.mjs': { notANumber: { argv: ['--rounds', 'few'], names: '--rounds' } },
  'benchmarks/three-cost.mjs': { notANumber: { argv: ['--batch', 'many'], names: '--batch' } },
  'benchmarks/channel-cost.mjs': { notANumber: { argv: ['--rounds', 'many'], names: '--rounds' } },
  'benchmarks/label-cost.mjs': { notANumber: { argv: ['--rounds', 'many'], names: '--rounds' } },
  'benchmarks/bundle-size.mjs': { notANumber: { argv: ['--budget', 'small'], names: '--budget' } },
  'benchmarks/first-image.mjs': { notANumber: { argv: ['--rounds', 'few'], names: '--rounds' } },
  'benchmarks/orbit.mjs': { notANumber: { argv: ['--rounds', 'few'], names: '--rounds' } },
  'benchmarks/temporal-reprojection.mjs': { notANumber: { argv: ['--steps', 'few'], names: '--steps' } },
  'benchmarks/read-speed.mjs': { notANumber: { argv: ['--runs', 'many'], names: '--runs' } },
  'benchmarks/mcrt-fetches.mjs': { notANumber: { argv: ['--iterations', '1.5'], names: '--iterations' } },
  'benchmarks/slice-plane-cost.mjs': { notANumber: { argv: ['--rounds', 'many'], names: '--rounds' } },
  'benchmarks/single-variants.mjs': { notANumber: { argv: ['{}', 'five'], names: 'ROUNDS' } },
  'benchmarks/zarr-streaming.mjs': { notANumber: { argv: ['--mbit', 'fast'], names: '--mbit' } },
  'apps/gallery/build.mjs': {},
};
/** Shell scripts: no options, but --help and a refusal all the same. */
const SHELL_SCRIPTS = ['scripts/setup.sh'];
/** Scripts with their own test (see above), and modules that are not commands. */
const ELSEWHERE = ['benchmarks/bench.mjs', 'scripts/renderer-plumbing.mjs', 'tools/tool-browser.mjs'];

function run(script: string, argv: string[]) {
  return spawnSync(process.execPath, [path.join(ROOT, script), ...argv], {
    cwd: ROOT,
    encoding: 'utf8',
    env: { PATH: path.dirname(process.execPath) },
    timeout: 30_000,
  });
}

describe('the repository scripts', () => {
  it('are all in this test', () => {
    const found = ['scripts', 'tools', 'benchmarks', ...fs.readdirSync(path.join(ROOT, 'apps')).map((a) => `apps/${a}`)]
      .flatMap((dir) =>
        fs
          .readdirSync(path.join(ROOT, dir))
          .filter((f) => f.endsWith('.mjs') || f.endsWith('.sh'))
          .map((f) => `${dir}/${f}`),
      )
      .sort();
    expect(found).toEqual([...Object.keys(SCRIPTS), ...SHELL_SCRIPTS, ...ELSEWHERE].sort());
  });

  for (const [script, { notANumber }] of Object.entries(SCRIPTS)) {
    describe(script, () => {
      it('--help prints the usage and exits 0', () => {
        const r = run(script, ['--help']);
        expect(r.stderr).toBe('');
        expect(r.status).toBe(0);
        expect(r.stdout).toMatch(/^Usage: /);
        expect(r.stdout).toContain('--help');
      });

      it('refuses an unknown flag, naming it', () => {
        const r = run(script, ['--no-such-flag']);
        expect(r.status).toBe(2);
        expect(r.stdout).toBe('');
        expect(r.stderr).toMatch(/Unknown option '--no-such-flag'/);
      });

      if (notANumber)
        it(`refuses a non-number for ${notANumber.names}`, () => {
          const r = run(script, notANumber.argv);
          expect(r.status).toBe(2);
          expect(r.stderr).toMatch(new RegExp(`${notANumber.names} must be (an integer|a number)`));
        });
    });
  }
});

describe.each(SHELL_SCRIPTS)('%s', (script) => {
  const sh = (...argv: string[]) =>
    spawnSync('bash', [path.join(ROOT, script), ...argv], { encoding: 'utf8', timeout: 30_000 });

  it('--help says what it does and exits 0; an argument is refused with exit 2, naming it', () => {
    const help = sh('--help');
    expect(help.status).toBe(0);
    expect(help.stdout).toMatch(/^Usage: /);
    const bad = sh('--no-such-flag');
    expect(bad.status).toBe(2);
    expect(bad.stderr).toContain("'--no-such-flag'");
  });
});

describe('the TypeScript scripts of benchmarks/ (run from dist/, tested here from source)', () => {
  afterEach(() => vi.restoreAllMocks());

  /** Import the script with argv as its command line; resolves with how it exited and what it printed. */
  async function exitOf(file: string, argv: string[]) {
    const lines: string[] = [];
    vi.spyOn(console, 'log').mockImplementation((l: string) => void lines.push(l));
    vi.spyOn(console, 'error').mockImplementation((l: string) => void lines.push(l));
    vi.spyOn(process, 'exit').mockImplementation((code?: number | string | null) => {
      throw new Error(`exit ${code}`);
    });
    const saved = process.argv;
    // estimator-table.ts runs only as the main script: argv[1] names it.
    process.argv = [process.execPath, path.join(ROOT, file), ...argv];
    try {
      vi.resetModules();
      await import(/* @vite-ignore */ path.join(ROOT, file));
      return { exit: 'none', text: lines.join('\n') };
    } catch (e) {
      return { exit: (e as Error).message, text: lines.join('\n') };
    } finally {
      process.argv = saved;
    }
  }

  for (const file of ['benchmarks/src/publish-report.ts', 'benchmarks/src/estimator-table.ts']) {
    it(`${file}: --help exits 0 with the usage; an unknown flag and a missing file exit 2`, async () => {
      const help = await exitOf(file, ['--help']);
      expect(help.exit).toBe('exit 0');
      expect(help.text).toMatch(/^Usage: node benchmarks\/dist\//);
      const unknown = await exitOf(file, ['--bogus']);
      expect(unknown.exit).toBe('exit 2');
      expect(unknown.text).toContain("Unknown option '--bogus'");
      const missing = await exitOf(file, []);
      expect(missing.exit).toBe('exit 2');
      expect(missing.text).toMatch(/missing RESULTS\.json/);
    });
  }
});
