import type { RequestPolicy } from '@vpt/core';
import type { Browser, Page } from 'puppeteer-core';
import { launchChromium, type ChromiumOptions } from './chromium.js';
import { PAGE_PATH, mountPagePackages, workspaceRoot } from './packages.js';
import type { BackendSummary, PageRenderResult, RenderTimings } from './page/types.js';
import type { BackendName, SceneDescription } from './scene-description.js';
import { mountSceneFiles, resolveSceneFiles } from './scene-files.js';
import { requestPolicyFromEnv } from './request-policy-env.js';
import { validateSceneDescription } from './validate-description.js';
import { startStaticServer, type StaticServer } from './server.js';

export interface VptPageOptions {
  /** Reuse a running browser (it is left open by close()); otherwise one is launched. */
  browser?: Browser;
  chromium?: ChromiumOptions;
  /**
   * Folder served at the URL root, besides the packages under /packages/. Default: the
   * workspace root when running from the repository (so tests can load /data/… and
   * their own pages), none when installed from npm.
   */
  root?: string | null;
  /** Forward the page's console to this function (e.g. `(l) => console.error(l)`). */
  onConsole?: (line: string) => void;
  /**
   * Serve other folders for some of the page's packages, by URL folder name
   * (`core`, `post`, `renderer-<name>`), e.g. another build of core.
   */
  packageDirs?: Record<string, string>;
  /** How long the page may take to load the packages, in ms (default 60 s). */
  loadTimeoutMs?: number;
}

export interface RenderResult {
  width: number;
  height: number;
  /** Linear HDR RGBA float, top row first, after the post steps named in hdrPostSteps (before exposure and tone mapping). */
  hdr: Float32Array;
  /** The post steps applied to `hdr`: the chain's leading steps that keep radiance, e.g. ['denoise']; [] for the plain estimate. */
  hdrPostSteps: string[];
  /** LDR RGBA8 after the post chain, top row first; null when the post chain is empty. */
  ldr: Uint8Array | null;
  timings: RenderTimings;
  backend: BackendSummary;
  gpuBytes: PageRenderResult['gpuBytes'];
  volumeDims: [number, number, number];
  warnings: string[];
  /** What the renderer chose for the scene (RenderContext.stats.renderer: MCRT auto's estimator and reasons…). */
  rendererStats: Record<string, string>;
  /** A bricked volume's residency before the iterations (an OME-Zarr level 0 beyond maxGpuBytes streams as bricks); null: not bricked. */
  bricking?: PageRenderResult['bricking'];
}

export interface PageRenderOptions {
  /** Folder that relative file paths in the description resolve against (default: cwd). */
  baseDir?: string;
  /** One untimed iteration first, so kernel compilation is not in totalMs (default true). */
  warmup?: boolean;
  /**
   * Confine the files the description names to this folder (`vpt-render --root`): paths
   * outside it, URLs and server URL paths are refused (see resolveSceneFiles).
   */
  sceneRoot?: string;
  /**
   * Bounds on every URL the scene names (core's RequestPolicy: stall timeout, total bound,
   * retries); default: $VPT_REQUEST_POLICY (JSON), else core's DEFAULT_REQUEST_POLICY.
   */
  request?: Partial<RequestPolicy>;
  /** Stop the iterations after this many ms; the result then holds those done (`timings.timeLimited`). */
  timeLimitMs?: number;
  /** The render context's temporal reuse (RenderContextOptions.temporal; `vpt-render --temporal`); default off. */
  temporal?: boolean;
  /** Iterations done of the total and ms since they began, after each batch (the render then runs in batches). */
  onProgress?: (done: number, total: number, ms: number) => void;
}

export interface VptPageSession {
  page: Page;
  browser: Browser;
  server: StaticServer;
  /** URL of the loaded page. */
  url: string;
  /** `page.evaluate`, bound. */
  evaluate: Page['evaluate'];
  /** Serve a local folder to the page; returns its URL path (e.g. `/__mount/0/`). */
  mount(dir: string, urlPath?: string): string;
  /** Render a scene description in this page (files it names are mounted first). */
  render(desc: SceneDescription, options?: PageRenderOptions): Promise<RenderResult>;
  /** Close the page, the server, and the browser unless it was passed in. */
  close(): Promise<void>;
}

/** An Error raised inside the page, with VptError's `code` when it had one. */
export class PageError extends Error {
  readonly code?: string;
  constructor(message: string, code?: string) {
    super(message);
    this.name = 'PageError';
    this.code = code;
  }
}

/**
 * Serve the built packages, open the headless page in Chromium and wait until
 * `window.vpt` is loaded. Tests then run code in the page:
 * `await session.page.evaluate(async () => { const { core, mip } = window.vpt; ... })`.
 */
export async function openVptPage(options: VptPageOptions = {}): Promise<VptPageSession> {
  const root = options.root === undefined ? workspaceRoot() : options.root;
  const server = await startStaticServer(root);
  let browser: Browser | undefined;
  let page: Page | undefined;
  const ownsBrowser = !options.browser;
  const problems: string[] = [];
  try {
    mountPagePackages(server, options.packageDirs);
    browser = options.browser ?? (await launchChromium(options.chromium));
    page = await browser.newPage();
    page.on('console', (m) => options.onConsole?.(`[page ${m.type()}] ${m.text()}`));
    page.on('pageerror', (e) => {
      const msg = e instanceof Error ? e.message : String(e);
      problems.push(msg);
      options.onConsole?.(`[page error] ${msg}`);
    });
    page.on('response', (r) => {
      if (r.status() >= 400 && !r.url().endsWith('/favicon.ico')) problems.push(`HTTP ${r.status()} ${r.url()}`);
    });
    const url = new URL(PAGE_PATH, server.url).href;
    await page.goto(url);
    const timeout = options.loadTimeoutMs ?? 60_000;
    try {
      await page.waitForFunction(() => window.__vptReady === true || typeof window.__vptError === 'string', {
        timeout,
        polling: 50,
      });
    } catch {
      throw new Error(
        `The vpt page did not load within ${timeout} ms${problems.length ? `: ${problems.join('; ')}` : ''}`,
      );
    }
    const loadError = await page.evaluate(() => window.__vptError ?? null);
    if (loadError)
      throw new Error(`The vpt page failed to load: ${loadError}${problems.length ? ` (${problems.join('; ')})` : ''}`);

    const b = browser,
      p = page;
    return {
      page,
      browser: b,
      server,
      url,
      evaluate: p.evaluate.bind(p) as Page['evaluate'],
      mount: (dir, urlPath) => server.mount(dir, urlPath),
      render: (desc, renderOptions = {}) => renderInPage(p, server, desc, renderOptions),
      async close() {
        await p.close().catch(() => {});
        if (ownsBrowser) await b.close().catch(() => {});
        await server.close();
      },
    };
  } catch (e) {
    await page?.close().catch(() => {});
    if (ownsBrowser) await browser?.close().catch(() => {});
    await server.close();
    throw e;
  }
}

async function renderInPage(
  page: Page,
  server: StaticServer,
  desc: SceneDescription,
  options: PageRenderOptions,
): Promise<RenderResult> {
  const mounted = mountSceneFiles(desc, options.baseDir ?? process.cwd(), server, { root: options.sceneRoot });
  if (options.onProgress) await progressChannel(page).then((channel) => (channel.current = options.onProgress));
  // Errors come back as data: a rejected evaluate would lose VptError's code.
  type Outcome =
    { ok: PageRenderResult; error?: undefined } | { ok?: undefined; error: { message: string; code?: string } };
  const out: Outcome = await page.evaluate(
    async (d, o) => {
      try {
        return { ok: await window.vpt.renderDescription(d, o) };
      } catch (e) {
        const err = e as { message?: string; code?: string };
        return { error: { message: String(err?.message ?? e), code: err?.code } };
      }
    },
    mounted,
    {
      warmup: options.warmup ?? true,
      request: options.request ?? requestPolicyFromEnv(),
      ...(options.timeLimitMs !== undefined ? { timeLimitMs: options.timeLimitMs } : {}),
      ...(options.temporal ? { temporal: true } : {}),
      ...(options.onProgress ? { progress: true } : {}),
    },
  );
  const channel = progressChannels.get(page);
  if (channel) channel.current = undefined;
  if (out.error) throw new PageError(out.error.message, out.error.code);
  return decodeResult(out.ok!);
}

/** The page's progress callback, exposed once per page; each render sets the handler it reports to. */
interface ProgressChannel {
  current?: (done: number, total: number, ms: number) => void;
}
const progressChannels = new WeakMap<Page, ProgressChannel>();

async function progressChannel(page: Page): Promise<ProgressChannel> {
  let channel = progressChannels.get(page);
  if (!channel) {
    const c: ProgressChannel = {};
    await page.exposeFunction('__vptRenderProgress', (done: number, total: number, ms: number) => {
      c.current?.(done, total, ms);
    });
    progressChannels.set(page, c);
    channel = c;
  }
  return channel;
}

function decodeResult(r: PageRenderResult): RenderResult {
  return {
    width: r.width,
    height: r.height,
    hdr: new Float32Array(bytesOf(r.hdr).buffer),
    hdrPostSteps: r.hdrPostSteps,
    ldr: r.ldr === null ? null : bytesOf(r.ldr),
    timings: r.timings,
    backend: r.backend,
    gpuBytes: r.gpuBytes,
    volumeDims: r.volumeDims,
    warnings: r.warnings,
    rendererStats: r.rendererStats ?? {},
    bricking: r.bricking,
  };
}

/** Base64 → a fresh, 4-byte-aligned Uint8Array (Buffers may sit at odd pool offsets). */
function bytesOf(b64: string): Uint8Array {
  const buf = Buffer.from(b64, 'base64');
  const out = new Uint8Array(buf.byteLength);
  out.set(buf);
  return out;
}

export interface RenderSceneOptions extends PageRenderOptions {
  backend?: BackendName;
  iterations?: number;
  width?: number;
  height?: number;
  seed?: number;
  chromium?: ChromiumOptions;
  /** Render in an already open page (not closed afterwards), e.g. for benchmark series. */
  session?: VptPageSession;
  onConsole?: (line: string) => void;
  /** See VptPageOptions.packageDirs. */
  packageDirs?: Record<string, string>;
}

/**
 * Render a scene description headless: launch Chromium, serve the packages and exactly the
 * files the scene names (no folder, no workspace root), render, read the images back,
 * close. Options override the description's own fields. The description is validated and
 * its files checked (sizes from their metadata) before a browser starts.
 */
export async function renderScene(desc: SceneDescription, options: RenderSceneOptions = {}): Promise<RenderResult> {
  const overrides: Partial<SceneDescription> = {};
  for (const key of ['backend', 'iterations', 'width', 'height', 'seed'] as const) {
    if (options[key] !== undefined) (overrides as Record<string, unknown>)[key] = options[key];
  }
  // Bad fields, missing files and size mismatches fail here, before a browser is started.
  // (A time series' step is picked there: its volume becomes one file or store.)
  const full = resolveSceneFiles(
    validateSceneDescription({ ...desc, ...overrides }),
    options.baseDir ?? process.cwd(),
    { root: options.sceneRoot },
  );
  // A bad request policy fails here too, before a browser is started.
  const request = options.request ?? requestPolicyFromEnv();
  const session =
    options.session ??
    (await openVptPage({
      root: null,
      chromium: options.chromium,
      onConsole: options.onConsole,
      packageDirs: options.packageDirs,
    }));
  try {
    return await session.render(full, { ...options, request });
  } finally {
    if (!options.session) await session.close();
  }
}
