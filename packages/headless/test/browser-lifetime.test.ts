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
});
