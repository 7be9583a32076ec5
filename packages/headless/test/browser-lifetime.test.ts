// Issue 28: a SIGKILLed vpt-render left its Chromium running (SIGTERM cleaned up). The
// browser now talks DevTools over a pipe, so it exits when its parent dies, however it dies.
import { spawn } from 'node:child_process';
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { fileURLToPath, pathToFileURL } from 'node:url';
import { describe, expect, it } from 'vitest';

const HERE = path.dirname(fileURLToPath(import.meta.url));

function alive(pid: number): boolean {
  try {
    process.kill(pid, 0);
    // A zombie counts as gone: it no longer runs.
    const stat = fs.readFileSync(`/proc/${pid}/stat`, 'utf8');
    return !/^\d+ \(.*\) Z/.test(stat);
  } catch {
    return false;
  }
}

/** Processes whose parent is `pid` (from /proc). */
function childrenOf(pid: number): number[] {
  return fs
    .readdirSync('/proc')
    .filter((d) => /^\d+$/.test(d))
    .filter((d) => {
      try {
        const stat = fs.readFileSync(`/proc/${d}/stat`, 'utf8');
        return Number(stat.slice(stat.lastIndexOf(')') + 2).split(' ')[1]) === pid;
      } catch {
        return false;
      }
    })
    .map(Number);
}

describe('Chromium dies with its parent', () => {
  it.skipIf(!fs.existsSync('/proc/self/stat'))(
    'SIGKILL of the launching process ends the browser within a few seconds',
    async () => {
      const dir = fs.mkdtempSync(path.join(os.tmpdir(), 'vpt-lifetime-'));
      const script = path.join(dir, 'launch.mjs');
      // A plain Node child runs the built module (pnpm run build comes before the tests).
      const chromium = path.join(HERE, '..', 'dist', 'chromium.js');
      expect(fs.existsSync(chromium), `${chromium} is missing: pnpm run build first`).toBe(true);
      fs.writeFileSync(
        script,
        `import { launchChromium } from ${JSON.stringify(pathToFileURL(chromium).href)};\n` +
          `const b = await launchChromium({ webgpu: false });\n` +
          `console.log(b.process().pid);\n` +
          `setInterval(() => {}, 1000);\n`,
      );
      const child = spawn(process.execPath, [script], { stdio: ['ignore', 'pipe', 'inherit'] });
      const pid = await new Promise<number>((resolve, reject) => {
        let out = '';
        child.stdout!.on('data', (d) => {
          out += d;
          const m = /(\d+)\n/.exec(out);
          if (m) resolve(Number(m[1]));
        });
        child.on('exit', (code) => reject(new Error(`the launcher exited (${code}) before printing a pid`)));
      });
      try {
        expect(alive(pid)).toBe(true);
        child.kill('SIGKILL');
        const t0 = Date.now();
        while (alive(pid) && Date.now() - t0 < 10_000) await new Promise((r) => setTimeout(r, 100));
        expect(alive(pid)).toBe(false);
      } finally {
        if (alive(pid)) process.kill(pid, 'SIGKILL');
        fs.rmSync(dir, { recursive: true, force: true });
      }
    },
    60_000,
  );

  it.skipIf(!fs.existsSync('/proc/self/stat'))(
    'Ctrl-C (SIGINT) during a long vpt-render ends it and its browser',
    async () => {
      const dir = fs.mkdtempSync(path.join(os.tmpdir(), 'vpt-sigint-'));
      const scene = path.join(dir, 'long.json');
      fs.writeFileSync(
        scene,
        JSON.stringify({ volume: { procedural: 'blob', size: 8 }, width: 8, height: 8, iterations: 1_000_000 }),
      );
      const cli = path.join(HERE, '..', 'dist', 'cli', 'render.js');
      const child = spawn(process.execPath, [cli, scene, '-o', path.join(dir, 'a.png'), '--backend', 'webgl2'], {
        stdio: ['ignore', 'ignore', 'pipe'],
      });
      let stderr = '';
      child.stderr!.on('data', (d) => (stderr += d));
      const exited = new Promise<number | null>((r) => child.on('exit', (code) => r(code)));
      try {
        // The first progress line: the browser is up and iterating.
        const t0 = Date.now();
        while (!/iterations \(/.test(stderr) && Date.now() - t0 < 60_000) await new Promise((r) => setTimeout(r, 100));
        expect(stderr).toMatch(/vpt-render: \d+\/1000000 iterations/);
        const browsers = childrenOf(child.pid!);
        expect(browsers.length).toBeGreaterThan(0);
        child.kill('SIGINT');
        const t1 = Date.now();
        expect(await exited).toBe(130);
        expect(Date.now() - t1).toBeLessThan(10_000);
        for (const pid of browsers) expect(alive(pid)).toBe(false);
      } finally {
        child.kill('SIGKILL');
        fs.rmSync(dir, { recursive: true, force: true });
      }
    },
    120_000,
  );
});
