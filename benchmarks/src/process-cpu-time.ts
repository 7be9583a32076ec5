/**
 * CPU time of the browser's processes (Linux /proc): of its GPU process, or of the whole
 * process tree (benchmarks/single-variants.mjs). With SwiftShader the kernels run on the
 * CPU inside that process, so the CPU time a batch of iterations adds to it measures the
 * batch's work without the waits that other processes on a loaded machine add to the wall
 * clock (the estimator study's cost side, error-vs-time.ts). The process's utime + stime
 * count every thread, finished ones too, in clock ticks (10 ms): per-batch figures are
 * coarse, their sums over many batches are not.
 */
import { readdirSync, readFileSync } from 'node:fs';

const TICK_MS = 10;

/** Fields of /proc/<pid>/stat after the command name (which may contain spaces). */
function statFields(pid: number): string[] {
  const s = readFileSync(`/proc/${pid}/stat`, 'utf8');
  return s.slice(s.lastIndexOf(')') + 2).split(' ');
}

/** Whether `ancestor` is `pid`'s parent, grandparent, … (Chromium forks its GPU process from a helper of the browser process). */
function descendsFrom(pid: number, ancestor: number): boolean {
  for (let p = pid, depth = 0; p > 1 && depth < 8; depth++) {
    p = Number(statFields(p)[1]);
    if (p === ancestor) return true;
  }
  return false;
}

/** The pid of the GPU process among the descendants of `browserPid`, or null (not Linux, or none found). */
export function gpuProcessPid(browserPid: number | undefined): number | null {
  if (!browserPid) return null;
  try {
    for (const entry of readdirSync('/proc')) {
      const pid = Number(entry);
      if (!Number.isInteger(pid)) continue;
      try {
        if (!readFileSync(`/proc/${pid}/cmdline`, 'utf8').includes('--type=gpu-process')) continue;
        if (descendsFrom(pid, browserPid)) return pid;
      } catch {
        // The process ended while we looked.
      }
    }
  } catch {
    // No /proc.
  }
  return null;
}

/** CPU ms (user + system, all threads) the process has used so far. */
export function processCpuMs(pid: number): number {
  const f = statFields(pid);
  // utime and stime are fields 14 and 15 of stat(5); f starts at field 3.
  return (Number(f[11]) + Number(f[12])) * TICK_MS;
}

/** CPU ms (user + system, all threads) that `rootPid` and all its descendants (Chromium's browser, GPU and renderer processes) have used so far. */
export function processTreeCpuMs(rootPid: number): number {
  const stats = new Map<number, { ppid: number; ticks: number }>();
  for (const entry of readdirSync('/proc')) {
    const pid = Number(entry);
    if (!Number.isInteger(pid)) continue;
    try {
      const f = statFields(pid);
      stats.set(pid, { ppid: Number(f[1]), ticks: Number(f[11]) + Number(f[12]) });
    } catch {
      // The process ended while we looked.
    }
  }
  let ticks = 0;
  for (const [pid, st] of stats) {
    let p: number | undefined = pid;
    while (p && p !== rootPid) p = stats.get(p)?.ppid;
    if (p === rootPid) ticks += st.ticks;
  }
  return ticks * TICK_MS;
}
