import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import puppeteer, { type Browser } from 'puppeteer-core';

export interface ChromiumOptions {
  /** Add the WebGPU-on-SwiftShader flags (default true; they do not hurt WebGL 2). */
  webgpu?: boolean;
  /** Executable; default $VPT_CHROMIUM, then $CHROMIUM_PATH, then /usr/bin/chromium. */
  executablePath?: string;
  /** Extra command-line flags. */
  args?: string[];
  /**
   * Timeout of a single DevTools call in ms. A long SwiftShader render is one
   * page.evaluate, so the default is 30 minutes rather than puppeteer's 3.
   */
  protocolTimeout?: number;
}

const DEFAULT_EXECUTABLE = '/usr/bin/chromium';

/** Flags for a quiet, reproducible browser that renders on the CPU (no GPU needed). */
export const CHROMIUM_FLAGS = [
  '--no-sandbox',
  '--disable-background-networking',
  '--disable-component-update',
  '--disable-sync',
  '--no-first-run',
  '--disable-quic',
  // WebGL 2 through ANGLE on SwiftShader: the same CPU rasterizer on every machine.
  '--use-angle=swiftshader',
  '--enable-unsafe-swiftshader',
];

/** WebGPU through Dawn's Vulkan backend on SwiftShader. */
export const WEBGPU_FLAGS = [
  '--enable-unsafe-webgpu',
  '--enable-features=Vulkan',
  '--use-vulkan=swiftshader',
  '--use-webgpu-adapter=swiftshader',
];

export function chromiumExecutable(explicit?: string): string {
  return explicit || process.env.VPT_CHROMIUM || process.env.CHROMIUM_PATH || DEFAULT_EXECUTABLE;
}

/**
 * Launch the system Chromium headless. vpt never downloads a browser: it uses the one
 * the OS package manager installed, so the renderer under test is the one users run.
 */
export async function launchChromium(options: ChromiumOptions = {}): Promise<Browser> {
  const executablePath = chromiumExecutable(options.executablePath);
  if (!fs.existsSync(executablePath)) {
    throw new Error(
      `Chromium not found at ${executablePath}. Install it (Debian/Ubuntu: apt-get install -y chromium) ` +
        'or point VPT_CHROMIUM (or CHROMIUM_PATH) at a Chromium or Chrome executable.',
    );
  }
  // A fresh profile per launch: no state leaks between runs, and parallel runs never
  // fight over one profile's lock.
  const userDataDir = fs.mkdtempSync(path.join(os.tmpdir(), 'vpt-chromium-'));
  const removeProfile = () => {
    try {
      fs.rmSync(userDataDir, { recursive: true, force: true, maxRetries: 3 });
    } catch {
      // A leftover temp folder is harmless; never fail a render over it.
    }
  };
  const args = [...CHROMIUM_FLAGS, ...(options.webgpu === false ? [] : WEBGPU_FLAGS), ...(options.args ?? [])];
  let browser: Browser;
  try {
    browser = await puppeteer.launch({
      executablePath,
      headless: true, // puppeteer adds --headless
      userDataDir,
      args,
      // DevTools over a pipe, not a WebSocket: when this process dies, even by SIGKILL (no
      // handler runs), the pipe closes and Chromium exits instead of running on, orphaned.
      pipe: true,
      protocolTimeout: options.protocolTimeout ?? 30 * 60_000,
    });
  } catch (e) {
    removeProfile();
    throw e;
  }
  // Remove the profile once the process has exited (after close() or a crash), not on
  // 'disconnected', which can fire while Chromium is still writing to it.
  const child = browser.process();
  if (child && child.exitCode === null) child.once('exit', removeProfile);
  else removeProfile();
  return browser;
}
