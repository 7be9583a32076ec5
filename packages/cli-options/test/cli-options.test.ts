import { describe, expect, it } from 'vitest';
import { CliArgsError, cliUsage, parseCli, type CliSpec } from '../src/index.js';

const SPEC = {
  name: 'demo',
  synopsis: 'IN [options]',
  summary: 'A demo command.',
  options: {
    size: { type: 'integer', min: 1, default: 64, description: 'image side' },
    scale: { type: 'number', min: 0, max: 2, description: 'a factor' },
    backend: { type: 'string', choices: ['webgl2', 'webgpu'], default: 'webgl2' },
    suites: { type: 'list', choices: ['error', 'frame'], default: ['error', 'frame'] },
    params: { type: 'json' },
    verbose: { type: 'boolean', short: 'v' },
    output: { type: 'string', short: 'o', valueName: 'FILE' },
  },
  positionals: [
    { key: 'input', name: 'IN', type: 'string', required: true },
    { key: 'rounds', name: 'ROUNDS', type: 'integer', min: 1, default: 5 },
  ],
} as const satisfies CliSpec;

function error(argv: string[]): CliArgsError {
  try {
    parseCli(SPEC, argv);
  } catch (e) {
    if (e instanceof CliArgsError) return e;
    throw e;
  }
  throw new Error(`accepted ${argv.join(' ')}`);
}

describe('parseCli', () => {
  it('returns typed values, defaults and positionals', () => {
    const r = parseCli(SPEC, ['in.json', '7', '--size=32', '--scale', '0.5', '-v', '--params', '{"a":1}', '-o', 'x']);
    expect(r.help).toBe(false);
    if (r.help) return;
    expect(r.values).toEqual({
      input: 'in.json',
      rounds: 7,
      size: 32,
      scale: 0.5,
      backend: 'webgl2',
      suites: ['error', 'frame'],
      params: { a: 1 },
      verbose: true,
      output: 'x',
    });
    const d = parseCli(SPEC, ['in.json']);
    if (d.help) throw new Error('help');
    expect(d.values.rounds).toBe(5);
    expect(d.values.verbose).toBe(false);
    expect(d.values.scale).toBeUndefined();
  });

  it('lets --help and -h win over bad or unknown flags', () => {
    expect(parseCli(SPEC, ['--help']).help).toBe(true);
    expect(parseCli(SPEC, ['--frobnicate', '-h']).help).toBe(true);
    expect(parseCli(SPEC, ['--size', 'abc', '--help']).help).toBe(true);
  });

  it('refuses unknown flags, naming them', () => {
    const e = error(['in.json', '--frobnicate']);
    expect(e.code).toBe('unknown-option');
    expect(e.message).toContain('--frobnicate');
    expect(error(['in.json', '-q']).message).toContain('-q');
  });

  it('refuses non-numbers, non-integers and values out of range, naming the flag', () => {
    for (const bad of ['abc', 'NaN', 'Infinity', '1.5', '', '0', '1e400', '0x10']) {
      const e = error(['in.json', `--size=${bad}`]);
      expect(e.code, bad).toBe('bad-value');
      expect(e.message, bad).toContain('--size');
    }
    for (const bad of ['-0.1', '2.5', 'two', '1,5'])
      expect(error(['in.json', `--scale=${bad}`]).message).toContain('--scale');
    expect(error(['in.json', 'many']).message).toContain('ROUNDS');
  });

  it('accepts the decimal forms of a number', () => {
    for (const [text, value] of [
      ['1', 1],
      ['.5', 0.5],
      ['1.', 1],
      ['2e-1', 0.2],
      [' 1.25 ', 1.25],
    ] as const) {
      const r = parseCli(SPEC, ['in.json', `--scale=${text}`]);
      if (r.help) throw new Error('help');
      expect(r.values.scale, text).toBe(value);
    }
  });

  it('checks choices, list items and JSON', () => {
    expect(error(['in.json', '--backend', 'vulkan']).message).toMatch(/--backend must be one of webgl2, webgpu/);
    expect(error(['in.json', '--suites', 'error,eror']).message).toMatch(/--suites.*"eror"/);
    expect(error(['in.json', '--params', '{a:1}']).message).toMatch(/--params must be JSON/);
  });

  it('refuses a missing value, a missing positional and extra positionals', () => {
    expect(error(['in.json', '--size']).code).toBe('missing-value');
    expect(error(['in.json', '--size']).message).toContain('--size');
    expect(error(['in.json', '--output', '--size', '3']).code).toBe('missing-value');
    const flagWithValue = error(['in.json', '--verbose=yes']);
    expect(flagWithValue.code).toBe('bad-value');
    expect(flagWithValue.message).toContain('--verbose');
    expect(error([]).code).toBe('missing-argument');
    expect(error([]).message).toContain('IN');
    const extra = error(['a', '1', 'b']);
    expect(extra.code).toBe('unexpected-argument');
    expect(extra.message).toContain('b');
  });

  it('drops the bare -- that pnpm forwards', () => {
    const r = parseCli(SPEC, ['--', 'in.json', '--size', '8']);
    if (r.help) throw new Error('help');
    expect(r.values.size).toBe(8);
  });

  it('hands out copies of array defaults, so a caller cannot change the table', () => {
    const a = parseCli(SPEC, ['in.json']);
    if (a.help) throw new Error('help');
    a.values.suites.push('error');
    expect(SPEC.options.suites.default).toEqual(['error', 'frame']);
    const b = parseCli(SPEC, ['in.json']);
    if (b.help) throw new Error('help');
    expect(b.values.suites).toEqual(['error', 'frame']);
  });

  it('refuses every positional for a command that takes none', () => {
    const e = (() => {
      try {
        parseCli({ name: 'none', options: {} }, ['stray']);
      } catch (err) {
        return err as CliArgsError;
      }
    })();
    expect(e?.code).toBe('unexpected-argument');
    expect(e?.message).toContain('stray');
  });
});

describe('cliUsage', () => {
  it('lists every option of the table, its value name, default and description, and --help', () => {
    const text = cliUsage(SPEC);
    expect(text.split('\n')[0]).toBe('Usage: demo IN [options]');
    for (const name of Object.keys(SPEC.options)) expect(text).toContain(`--${name}`);
    expect(text).toMatch(/-o, --output FILE/);
    expect(text).toMatch(/--size N\s+image side \(default 64\)/);
    expect(text).toMatch(/--backend webgl2\|webgpu/);
    expect(text).toMatch(/-h, --help/);
    expect(text).toContain('ROUNDS');
  });
});
