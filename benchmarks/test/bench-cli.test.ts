// `pnpm bench`'s command line: the option tables (bench-cli.mjs) against configs.ts and run.ts,
// the settings run.ts gets (a copy of the preset), and the launcher (bench.mjs), which must
// answer --help and refuse a bad flag before it builds anything.
import { spawnSync } from 'node:child_process';
import { readFileSync } from 'node:fs';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import { afterEach, describe, expect, it, vi } from 'vitest';
import { CliArgsError } from '@vpt/cli-options';
import { benchSettings, wantsSideBySide } from '../src/bench-args.js';
import { BENCH_CLI, PRESET_NAMES, SIDE_CLI, SUITE_NAMES } from '../src/bench-cli.mjs';
import { PRESETS } from '../src/configs.js';

const benchmarks = fileURLToPath(new URL('..', import.meta.url));

describe('the option tables', () => {
  it('name exactly the presets of configs.ts', () => {
    expect([...PRESET_NAMES].sort()).toEqual(Object.keys(PRESETS).sort());
  });

  it('name exactly the suites run.ts runs', () => {
    const run = readFileSync(path.join(benchmarks, 'src/run.ts'), 'utf8');
    const used = [...run.matchAll(/suites\.includes\('([a-z]+)'\)/g)].map((m) => m[1]);
    expect(used.length).toBeGreaterThan(0);
    expect([...SUITE_NAMES].sort()).toEqual([...new Set(used)].sort());
  });
});

describe('benchSettings', () => {
  it('applies the flags to a copy of the preset and leaves PRESETS as it was', () => {
    const before = structuredClone(PRESETS);
    const s = benchSettings(
      ['--preset', 'smoke', '--scenes', 'a,b', '--cost-rounds', '3', '--cost-batch', '4', '--seed', '7'],
      PRESETS,
    );
    expect(s).not.toBeNull();
    expect(s!.preset).not.toBe(PRESETS.smoke);
    expect(s!.preset).toMatchObject({
      name: 'smoke',
      errorScenes: ['a', 'b'],
      costRounds: 3,
      costBatch: 4,
      curveSeed: 7,
    });
    expect(PRESETS).toEqual(before);
    // The copy is deep: changing what run.ts got does not reach the table either.
    s!.preset.frameSizes.push(1);
    expect(PRESETS.smoke.frameSizes).toEqual(before.smoke.frameSizes);
  });

  it('defaults to the quick preset and the default suites, both backends; copies the defaults', () => {
    const s = benchSettings([], PRESETS)!;
    expect(s.preset.name).toBe('quick');
    expect(s.suites).toEqual(BENCH_CLI.options.suites.default);
    expect(s.backends).toEqual(['webgl2', 'webgpu']);
    s.suites.push('denoise');
    expect(BENCH_CLI.options.suites.default).not.toContain('denoise');
  });

  it('splits --renderers on commas and --variants on |', () => {
    const s = benchSettings(
      ['--renderers', 'mcrt single,eam', '--variants', 'delta, phase, grid|residual, mis, grid'],
      PRESETS,
    )!;
    expect(s.renderers).toEqual(['mcrt single', 'eam']);
    expect(s.variants).toEqual(['delta, phase, grid', 'residual, mis, grid']);
  });

  it('returns null for --help and refuses bad input, naming the flag', () => {
    expect(benchSettings(['--help'], PRESETS)).toBeNull();
    const refused = (argv: string[]) => {
      try {
        benchSettings(argv, PRESETS);
      } catch (e) {
        expect(e).toBeInstanceOf(CliArgsError);
        return (e as Error).message;
      }
      throw new Error(`accepted ${argv.join(' ')}`);
    };
    expect(refused(['--prest', 'quick'])).toContain('--prest');
    expect(refused(['--preset', 'huge'])).toMatch(/--preset must be one of/);
    expect(refused(['--suites', 'error,speed'])).toMatch(/--suites.*"speed"/);
    expect(refused(['--cost-rounds', 'three'])).toMatch(/--cost-rounds must be an integer >= 1, got "three"/);
    expect(refused(['--seed', 'NaN'])).toContain('--seed');
  });

  it('sends --vpt to the side-by-side suite', () => {
    expect(wantsSideBySide(['--vpt', 'x'])).toBe(true);
    expect(wantsSideBySide(['--vpt=x'])).toBe(true);
    expect(wantsSideBySide(['--preset', 'quick'])).toBe(false);
  });
});

describe('the side-by-side suite (runSide)', () => {
  afterEach(() => vi.restoreAllMocks());

  const exitOf = async (argv: string[]) => {
    const { runSide } = await import('../src/vpt-side/run-side.js');
    const lines: string[] = [];
    vi.spyOn(console, 'log').mockImplementation((l: string) => void lines.push(l));
    vi.spyOn(console, 'error').mockImplementation((l: string) => void lines.push(l));
    vi.spyOn(process, 'exit').mockImplementation((code?: number | string | null) => {
      throw new Error(`exit ${code}`);
    });
    const error = await runSide(argv).then(
      () => null,
      (e: Error) => e.message,
    );
    return { error, text: lines.join('\n') };
  };

  it('--help prints its own usage and exits 0', async () => {
    const { error, text } = await exitOf(['--vpt', '/nonexistent', '--help']);
    expect(error).toBe('exit 0');
    for (const name of Object.keys(SIDE_CLI.options)) expect(text).toContain(`--${name}`);
  });

  it('refuses an unknown flag and a non-number before looking for VPT', async () => {
    let r = await exitOf(['--vpt', '/nonexistent', '--frames', '3']);
    expect(r.error).toBe('exit 2');
    expect(r.text).toContain('--frames');
    r = await exitOf(['--vpt', '/nonexistent', '--rounds', 'x']);
    expect(r.error).toBe('exit 2');
    expect(r.text).toMatch(/--rounds must be an integer >= 1, got "x"/);
    r = await exitOf(['--vpt', '/nonexistent', '--mcrt-params', '{bad']);
    expect(r.text).toMatch(/--mcrt-params must be JSON/);
  });
});

describe('the launcher, bench.mjs', () => {
  // Without pnpm on PATH a build attempt would fail: these exits show that none was made.
  const launch = (...argv: string[]) =>
    spawnSync(process.execPath, [path.join(benchmarks, 'bench.mjs'), ...argv], {
      encoding: 'utf8',
      env: { PATH: path.dirname(process.execPath) },
      timeout: 30_000,
    });

  it('--help prints the usage and exits 0 without building', () => {
    const r = launch('--help');
    expect(r.status).toBe(0);
    expect(r.stdout).toMatch(/^Usage: pnpm bench/);
    for (const name of Object.keys(BENCH_CLI.options)) expect(r.stdout).toContain(`--${name}`);
    const side = launch('--vpt', 'DIR', '-h');
    expect(side.status).toBe(0);
    expect(side.stdout).toMatch(/^Usage: pnpm bench --vpt DIR/);
  });

  it('refuses an unknown flag and a non-number, naming them, without building', () => {
    let r = launch('--', '--preset', 'smoke', '--frob');
    expect(r.status).toBe(2);
    expect(r.stderr).toMatch(/pnpm bench: Unknown option '--frob'/);
    r = launch('--seed', 'abc');
    expect(r.status).toBe(2);
    expect(r.stderr).toMatch(/--seed must be an integer >= 0, got "abc"/);
    r = launch('--vpt', 'DIR', '--size', '1.5');
    expect(r.status).toBe(2);
    expect(r.stderr).toMatch(/--size must be an integer >= 1, got "1.5"/);
  });
});
