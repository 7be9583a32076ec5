#!/usr/bin/env node
/**
 * `pnpm bench …`: check the command line against bench-cli.mjs's tables first (--help prints
 * the usage, a bad flag is refused, both without building), then build the packages and run
 * dist/run.js with the same arguments.
 */
import { spawnSync } from 'node:child_process';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import { CliArgsError, cliUsage, parseCli } from '@vpt/cli-options';
import { BENCH_CLI, SIDE_CLI } from './src/bench-cli.mjs';

const here = path.dirname(fileURLToPath(import.meta.url));
const argv = process.argv.slice(2).filter((a) => a !== '--');
// The same choice as run.ts's wantsSideBySide (bench-args.ts).
const spec = argv.some((a) => a === '--vpt' || a.startsWith('--vpt=')) ? SIDE_CLI : BENCH_CLI;
try {
  if (parseCli(spec, argv).help) {
    console.log(cliUsage(spec));
    process.exit(0);
  }
} catch (e) {
  if (!(e instanceof CliArgsError)) throw e;
  console.error(`${spec.name}: ${e.message} (--help lists the options)`);
  process.exit(2);
}

const run = (cmd, args, cwd) => spawnSync(cmd, args, { cwd, stdio: 'inherit' }).status ?? 1;
const built = run('pnpm', ['run', 'build'], path.join(here, '..'));
if (built !== 0) process.exit(built);
// cwd benchmarks/, as `pnpm --filter @vpt/benchmarks run bench` had it; INIT_CWD (where the
// user typed the command, for --vpt DIR) passes through in the environment.
process.exit(run(process.execPath, [path.join(here, 'dist', 'run.js'), ...argv], here));
