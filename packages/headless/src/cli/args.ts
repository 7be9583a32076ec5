import { parseArgs } from 'node:util';
import { BACKEND_NAMES, type BackendName } from '../scene-description.js';

export const RENDER_USAGE = `Usage: vpt-render scene.json -o out.png [--pfm out.pfm] [--backend auto|webgl2|webgpu]
                  [--iterations N] [--width W --height H] [--seed N] [--root DIR] [--keep-alpha] [--verbose]
                  [--time-limit SECONDS]
Renders a scene description in headless Chromium and prints the timings as one JSON line.
Only the files the scene names are served to the page. --root DIR refuses any scene path
outside DIR (and URLs): use it when rendering scene files you do not trust.
The PNG is opaque (its RGB already shows the background) unless --keep-alpha writes the
coverage as alpha; the PFM holds the linear HDR RGB after the post chain's leading HDR steps
(a "denoise" step first in the chain gives a denoised PFM; the JSON line's hdrPostSteps says so),
before exposure and tone mapping.
--time-limit SECONDS stops the iterations after that long and writes the image of those done
(the JSON line then says "timeLimited": true); runs longer than a few seconds print progress
to stderr.`;

export interface RenderArgs {
  scene: string;
  output?: string;
  pfm?: string;
  backend?: BackendName;
  iterations?: number;
  width?: number;
  height?: number;
  seed?: number;
  root?: string;
  /** --time-limit, in seconds. */
  timeLimit?: number;
  keepAlpha: boolean;
  verbose: boolean;
  help: boolean;
}

function integer(name: string, value: string | undefined, min: number): number | undefined {
  if (value === undefined) return undefined;
  const n = Number(value);
  if (!/^\d+$/.test(value.trim()) || !Number.isSafeInteger(n) || n < min) {
    throw new Error(`--${name} must be an integer >= ${min}, got "${value}"`);
  }
  return n;
}

/** A positive, finite number of seconds (at most a day). */
function seconds(name: string, value: string): number {
  const n = Number(value);
  if (value.trim() === '' || !Number.isFinite(n) || n <= 0 || n > 86_400)
    throw new Error(`--${name} must be a number of seconds in (0, 86400], got "${value}"`);
  return n;
}

/** Parse vpt-render's arguments; throws an Error with a one-line message on bad input. */
export function parseRenderArgs(argv: string[]): RenderArgs {
  const { values, positionals } = parseArgs({
    args: argv,
    allowPositionals: true,
    strict: true,
    options: {
      output: { type: 'string', short: 'o' },
      pfm: { type: 'string' },
      backend: { type: 'string' },
      iterations: { type: 'string', short: 'n' },
      width: { type: 'string' },
      height: { type: 'string' },
      seed: { type: 'string' },
      root: { type: 'string' },
      'time-limit': { type: 'string' },
      'keep-alpha': { type: 'boolean', default: false },
      verbose: { type: 'boolean', short: 'v', default: false },
      help: { type: 'boolean', short: 'h', default: false },
    },
  });
  if (values.help) return { scene: '', keepAlpha: false, verbose: false, help: true };
  if (positionals.length !== 1)
    throw new Error(
      positionals.length
        ? `expected one scene file, got ${positionals.length}: ${positionals.join(' ')}`
        : 'missing the scene file',
    );
  if (values.output === undefined && values.pfm === undefined)
    throw new Error('nothing to write: give -o out.png and/or --pfm out.pfm');
  if (values.backend !== undefined && !BACKEND_NAMES.includes(values.backend as BackendName)) {
    throw new Error(`--backend must be one of ${BACKEND_NAMES.join(', ')}, got "${values.backend}"`);
  }
  return {
    scene: positionals[0],
    output: values.output,
    pfm: values.pfm,
    backend: values.backend as BackendName | undefined,
    iterations: integer('iterations', values.iterations, 1),
    width: integer('width', values.width, 1),
    height: integer('height', values.height, 1),
    seed: integer('seed', values.seed, 0),
    root: values.root,
    ...(values['time-limit'] !== undefined ? { timeLimit: seconds('time-limit', values['time-limit']) } : {}),
    keepAlpha: values['keep-alpha'],
    verbose: values.verbose,
    help: false,
  };
}

export const SERVE_USAGE = `Usage: vpt-serve [--open PAGE] [--root DIR] [--port N] [--check]
Serves the workspace root (or DIR) on 127.0.0.1 and prints the URL of PAGE.
--check (or --once) fetches PAGE once, prints the result and exits (0 when HTTP 200).`;

export interface ServeArgs {
  open: string;
  root?: string;
  port: number;
  check: boolean;
  help: boolean;
}

export function parseServeArgs(argv: string[]): ServeArgs {
  const { values, positionals } = parseArgs({
    args: argv,
    allowPositionals: true,
    strict: true,
    options: {
      open: { type: 'string' },
      root: { type: 'string' },
      port: { type: 'string', short: 'p' },
      check: { type: 'boolean', default: false },
      once: { type: 'boolean', default: false },
      help: { type: 'boolean', short: 'h', default: false },
    },
  });
  if (positionals.length > 1) throw new Error(`unexpected arguments: ${positionals.join(' ')}`);
  const port = integer('port', values.port, 0) ?? 0;
  if (port > 65535) throw new Error(`--port must be at most 65535, got ${port}`);
  return {
    open: values.open ?? positionals[0] ?? '',
    root: values.root,
    port,
    check: values.check || values.once,
    help: values.help,
  };
}
