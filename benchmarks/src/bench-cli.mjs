// The option tables of `pnpm bench` (run.ts) and of its side-by-side mode `pnpm bench --vpt DIR`
// (vpt-side/run-side.ts). Plain JavaScript so that bench.mjs, the launcher, can answer --help
// and refuse a bad flag before the build that run.ts needs; TypeScript reads it with allowJs,
// and the JSDoc @satisfies keeps the literal option types. PRESET_NAMES and SUITE_NAMES must
// match configs.ts and run.ts (benchmarks/test/bench-cli.test.ts checks them).

/** @type {readonly ['smoke', 'table', 'mcrt256', 'estimators', 'quick', 'full']} */
export const PRESET_NAMES = ['smoke', 'table', 'mcrt256', 'estimators', 'quick', 'full'];
export const SUITE_NAMES = [
  'error',
  'frame',
  'convergence',
  'scaling',
  'specialization',
  'compact',
  'skipping',
  'denoise',
];

/** @type {readonly ['webgl2', 'webgpu']} */
export const BACKEND_NAMES = ['webgl2', 'webgpu'];

/** @satisfies {import('@vpt/cli-options').CliSpec} */
export const BENCH_CLI = {
  name: 'pnpm bench',
  synopsis: '[--preset NAME] [--suites A,B] [options]   |   pnpm bench --vpt DIR [side-by-side options]',
  summary:
    'Builds the packages, runs the benchmark suites in headless Chromium and writes\n' +
    'benchmarks/results/<time>/results.json and report.html. Nothing asserts a time: compare ratios within one run.\n' +
    'With --vpt DIR: only the side-by-side suite against a build of the original VPT (pnpm bench --vpt DIR --help).',
  options: {
    preset: { type: 'string', choices: PRESET_NAMES, default: 'quick', description: 'sizes and iteration counts' },
    suites: {
      type: 'list',
      choices: SUITE_NAMES,
      default: ['error', 'frame', 'convergence', 'scaling', 'specialization', 'compact'],
      description: 'the suites to run (skipping and denoise are not in the default list)',
    },
    backends: { type: 'list', choices: BACKEND_NAMES, default: BACKEND_NAMES, description: 'GPU backends' },
    scenes: { type: 'list', description: "only these scenes of the error suite (default: the preset's)" },
    renderers: {
      type: 'list',
      valueName: 'PREFIX,…',
      description: 'only renderer configurations whose label starts so',
    },
    variants: {
      type: 'string',
      valueName: '"A|B"',
      description: '--preset estimators: only these fixed estimators, |-separated (e.g. "delta, phase, grid")',
    },
    'cost-rounds': { type: 'integer', min: 1, description: "the estimator study's round-robin rounds" },
    'cost-batch': { type: 'integer', min: 1, description: "the estimator study's iterations per batch" },
    seed: { type: 'integer', min: 0, description: "the error curves' seed (another seed: an independent run)" },
    vpt: { type: 'string', valueName: 'DIR', description: 'the side-by-side suite instead (see above)' },
  },
};

/** @satisfies {import('@vpt/cli-options').CliSpec} */
export const SIDE_CLI = {
  name: 'pnpm bench --vpt DIR',
  synopsis: '[--quick] [--size N] [--rounds R] [--volume N] [--pairs A,B] [--mcrt-params JSON] …',
  summary:
    'The side-by-side suite against a build of the original VPT: DIR is a clone holding build/, or\n' +
    'that build folder (never stored in this repository); relative to where pnpm bench was typed.\n' +
    'Without a VPT build it says so and exits 0. Writes benchmarks/results/<time>-vpt-side/.',
  options: {
    vpt: { type: 'string', valueName: 'DIR', description: 'the VPT clone or build folder' },
    quick: { type: 'boolean', description: 'a 15-second smoke run (32² images, a 32³ volume, one round)' },
    size: { type: 'integer', min: 1, description: 'image side in pixels (default 128, --quick 32)' },
    volume: { type: 'integer', min: 2, description: "the anchor volume's side (default 128, --quick 32)" },
    rounds: { type: 'integer', min: 1, description: 'interleaved rounds (default 3, --quick 1)' },
    scale: { type: 'number', min: 0, description: 'shortens every run by this factor (default 1, --quick 1/64)' },
    pairs: {
      type: 'list',
      choices: ['multiple', 'single', 'eam', 'mip'],
      description: 'only these pairs (default: all)',
    },
    'mcrt-params': { type: 'json', description: "merged over vpt's MCRT parameters" },
    'eam-params': { type: 'json', description: "merged over vpt's EAM parameters" },
    'mip-params': { type: 'json', description: "merged over vpt's MIP parameters" },
  },
};
