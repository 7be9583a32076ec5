import { CliArgsError, cliUsage, parseCli, type CliSpec } from '@vpt/cli-options';
import { BACKEND_NAMES, type BackendName } from '../scene-description.js';

/** vpt-render's option table: the parser and the --help text both come from it. */
export const RENDER_CLI = {
  name: 'vpt-render',
  synopsis: 'scene.json -o out.png [--pfm out.pfm] [options]',
  summary:
    'Renders a scene description in headless Chromium and prints the timings as one JSON line.\n' +
    'Only the files the scene names are served to the page.',
  options: {
    output: {
      type: 'string',
      short: 'o',
      valueName: 'FILE',
      description: 'the PNG to write (LDR, after the post chain)',
    },
    pfm: { type: 'string', valueName: 'FILE', description: 'the PFM to write (linear HDR RGB, see below)' },
    backend: {
      type: 'string',
      choices: BACKEND_NAMES,
      description: "the GPU backend (default: the scene's, else auto)",
    },
    iterations: {
      type: 'integer',
      short: 'n',
      min: 1,
      description: "iterations to accumulate (overrides the scene's)",
    },
    width: { type: 'integer', min: 1, valueName: 'W', description: 'image width in pixels' },
    height: { type: 'integer', min: 1, valueName: 'H', description: 'image height in pixels' },
    seed: { type: 'integer', min: 0, description: "the random seed (overrides the scene's)" },
    root: {
      type: 'string',
      valueName: 'DIR',
      description: 'refuse scene paths outside DIR (and URLs): for scene files you do not trust',
    },
    'time-limit': {
      type: 'number',
      min: 0.001,
      max: 86_400,
      valueName: 'SECONDS',
      description: 'stop the iterations after this long and write the image of those done',
    },
    time: {
      type: 'string',
      valueName: 'A[:B]',
      description: 'the time step A, or the steps A to B (both included) to numbered images (see below)',
    },
    temporal: {
      type: 'boolean',
      description: 'turn on temporal reuse across camera changes (off by default; see below)',
    },
    'keep-alpha': {
      type: 'boolean',
      description: 'write the coverage as PNG alpha (default: opaque over the background)',
    },
    verbose: { type: 'boolean', short: 'v', description: "echo the page's console to stderr; stack traces on errors" },
  },
  positionals: [{ key: 'scene', name: 'scene.json', type: 'string', description: 'the scene file (JSON)' }],
  epilog: `The PNG is opaque (its RGB already shows the background) unless --keep-alpha writes the
coverage as alpha; the PFM holds the linear HDR RGB after the post chain's leading HDR steps
(a "denoise" step first in the chain gives a denoised PFM; the JSON line's hdrPostSteps says so),
before exposure and tone mapping.

--time-limit SECONDS stops the iterations after that long and writes the image of those done
(the JSON line then says "timeLimited": true); runs longer than a few seconds print progress
to stderr.

--temporal turns on the render context's temporal reuse (the image reprojected into a new view
through the depth guide and blended with the new samples as a fading history; the viewer has it
on by default). A scene file renders one view, so a still's image is the same with it; the JSON
line then says "temporal": true.

--time A renders step A of a time series (overriding the scene's "time"); --time A:B renders
steps A, A+1, ..., B, each to its own file: -o out/frame-%03d.png puts the step's number where
%d or %0Nd stands (out/frame-007.png); a name without one gets -%03d before its extension when
more than one step is rendered (-o out/frame.png gives out/frame-000.png, out/frame-001.png, ...).
--pfm names its files the same way. The steps share one browser; the JSON line lists each
step's timings in "steps".

A scene file is one JSON object; every field is optional (defaults: a procedural sphere, EAM):
  renderer         eam, mip, mcrt or iso; rendererParams: that renderer's parameters
  volume           one of {"sidecar": "head.json"} (a JSON sidecar beside its .raw),
                   {"raw": "v.raw", "dims": [x, y, z], "type": "uint8|uint16|int16|float32"},
                   {"zarr": "cells.ome.zarr", "level": 0} (OME-Zarr folder or http(s) URL),
                   {"file": "scan.nii.gz"} (NIfTI, NRRD, DICOM, raw + sidecar, OME-Zarr),
                   {"timeSeries": ["t0.nrrd", "t1.nrrd", ...]} (one file per time step, one grid),
                   {"procedural": "sphere|cube|ramp|blob", "size": 32}; paths are relative to the scene file
  transferFunction {"points": [{"value", "color", "opacity"}, …]} or {"dimensions": "2d", "widgets": […]}
  camera           position, target, up, fovy (full vertical angle, radians)
  lights           [{"type": "directional", "direction": [x, y, z], "irradiance": [r, g, b]}]:
                   direction points from the scene TOWARD the light
  environment      {"type": "constant", "radiance": [r, g, b]} or a "latlong" map
  clip             {"planes": [{"normal": [x, y, z], "offset": d}], "box": {"min": [x, y, z], "max": [x, y, z]}}:
                   up to 6 planes, each removing dot(normal, p) > offset, and a crop box (world units of the box)
  time             the time step (from 0) of a time series: a "timeSeries" list, a 4D NIfTI file,
                   an OME-Zarr store with a t axis
  also             width, height, iterations, seed, densityScale, sampling (fast|exact),
                   maxGpuBytes, backend, post (the post chain as JSON)
Every field is checked first, with an error naming it. The full description, field by field:
src/scene-description.ts in the @vpt/headless package; examples: apps/gallery/scenes/ in the repository.`,
} as const satisfies CliSpec;

export const RENDER_USAGE = cliUsage(RENDER_CLI);

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
  /** --time A[:B]: the first and last time step (equal for one step). */
  time?: { first: number; last: number };
  keepAlpha: boolean;
  /** --temporal: the context's temporal reuse on. */
  temporal?: boolean;
  verbose: boolean;
  help: boolean;
}

/** Parse vpt-render's arguments; throws a CliArgsError (or Error) with a one-line message on bad input. */
export function parseRenderArgs(argv: string[]): RenderArgs {
  let parsed;
  try {
    parsed = parseCli(RENDER_CLI, argv);
  } catch (e) {
    // More than one positional: say that one scene file is expected, and name the extra ones.
    if (e instanceof CliArgsError && e.code === 'unexpected-argument')
      throw new CliArgsError(e.code, `expected one scene file, ${e.message}`);
    throw e;
  }
  if (parsed.help) return { scene: '', keepAlpha: false, verbose: false, help: true };
  const { values } = parsed;
  if (values.scene === undefined) throw new CliArgsError('missing-argument', 'missing the scene file');
  if (values.output === undefined && values.pfm === undefined)
    throw new CliArgsError('missing-argument', 'nothing to write: give -o out.png and/or --pfm out.pfm');
  return {
    scene: values.scene,
    output: values.output,
    pfm: values.pfm,
    backend: values.backend,
    iterations: values.iterations,
    width: values.width,
    height: values.height,
    seed: values.seed,
    root: values.root,
    ...(values['time-limit'] !== undefined ? { timeLimit: values['time-limit'] } : {}),
    ...(values.time !== undefined ? { time: parseTimeRange(values.time) } : {}),
    keepAlpha: values['keep-alpha'],
    ...(values.temporal ? { temporal: true } : {}),
    verbose: values.verbose,
    help: false,
  };
}

/** `--time A` or `--time A:B` (A ≤ B, whole numbers ≥ 0) as the first and last step. */
export function parseTimeRange(text: string): { first: number; last: number } {
  const m = /^(\d+)(?::(\d+))?$/.exec(text.trim());
  if (!m)
    throw new CliArgsError('bad-value', `--time: expected a step A or a range A:B of whole numbers, got "${text}"`);
  const first = Number(m[1]);
  const last = m[2] === undefined ? first : Number(m[2]);
  if (last < first) throw new CliArgsError('bad-value', `--time: the range ${text} ends before it starts`);
  if (last > 1e6) throw new CliArgsError('bad-value', `--time: step ${last} is above the limit of 1000000`);
  return { first, last };
}

/**
 * The file of time step `step`: `%d` / `%0Nd` in the name become the step's number; a name
 * without one gets `-%03d` before its extension when several steps are written (`numbered`).
 */
export function stepFileName(pattern: string, step: number, numbered: boolean): string {
  if (/%0?\d*d/.test(pattern))
    return pattern.replace(/%(0?)(\d*)d/g, (_, zero: string, width: string) =>
      String(step).padStart(Number(width || 0), zero ? '0' : ' '),
    );
  if (!numbered) return pattern;
  const dot = pattern.lastIndexOf('.');
  const slash = Math.max(pattern.lastIndexOf('/'), pattern.lastIndexOf('\\'));
  const at = dot > slash + 1 ? dot : pattern.length;
  return `${pattern.slice(0, at)}-${String(step).padStart(3, '0')}${pattern.slice(at)}`;
}

/** vpt-serve's option table. */
export const SERVE_CLI = {
  name: 'vpt-serve',
  synopsis: '[PAGE] [--open PAGE] [--root DIR] [--port N] [--check]',
  summary: 'Serves the workspace root (or DIR) on 127.0.0.1 and prints the URL of PAGE.',
  options: {
    open: { type: 'string', valueName: 'PAGE', description: 'the page whose URL to print (a path under the root)' },
    root: { type: 'string', valueName: 'DIR', description: 'the folder to serve (default: the workspace root)' },
    port: { type: 'integer', short: 'p', min: 0, max: 65535, description: 'the port (default 0: any free one)' },
    check: {
      type: 'boolean',
      description: 'fetch PAGE and what it loads once, print the result, exit (0 when all load)',
    },
    once: { type: 'boolean', description: 'the same as --check' },
  },
  positionals: [{ key: 'page', name: 'PAGE', type: 'string', description: 'the same as --open PAGE' }],
} as const satisfies CliSpec;

export const SERVE_USAGE = cliUsage(SERVE_CLI);

export interface ServeArgs {
  open: string;
  root?: string;
  port: number;
  check: boolean;
  help: boolean;
}

export function parseServeArgs(argv: string[]): ServeArgs {
  const parsed = parseCli(SERVE_CLI, argv);
  if (parsed.help) return { open: '', port: 0, check: false, help: true };
  const { values } = parsed;
  return {
    open: values.open ?? values.page ?? '',
    root: values.root,
    port: values.port ?? 0,
    check: values.check || values.once,
    help: false,
  };
}
