import path from 'node:path';
import { mountPagePackages, mountThirdParty, workspaceRoot } from '../packages.js';
import { startStaticServer, type StaticServer } from '../server.js';
import { parseServeArgs, SERVE_USAGE } from './args.js';
import { oneLine, processIO, type CliIO } from './io.js';

/**
 * Local URLs a page needs at load time: its import map targets and the src/href of its
 * script and link tags. A regex is enough for the project's own hand-written pages.
 */
export function pageDependencies(html: string): string[] {
  const urls = new Set<string>();
  for (const m of html.matchAll(/<script[^>]*type=["']importmap["'][^>]*>([\s\S]*?)<\/script>/gi)) {
    try {
      const imports = JSON.parse(m[1]).imports ?? {};
      // A prefix mapping ("three/addons/": "/…/jsm/") names a folder, not a file.
      for (const v of Object.values(imports)) if (typeof v === 'string' && !v.endsWith('/')) urls.add(v);
    } catch {
      // An unreadable import map shows up when the page is opened; not our check.
    }
  }
  for (const m of html.matchAll(/<(?:script|link)\b[^>]*\b(?:src|href)=["']([^"']+)["']/gi)) urls.add(m[1]);
  return [...urls].filter((u) => !/^[a-z][a-z0-9+.-]*:/i.test(u) && !u.startsWith('//'));
}

/** --check asks this process's own server, which answers at once: anything slower is a failure, not a wait. */
const CHECK_TIMEOUT_MS = 30_000;

async function check(url: string, io: CliIO): Promise<number> {
  const res = await fetch(url, { signal: AbortSignal.timeout(CHECK_TIMEOUT_MS) });
  if (res.status !== 200) {
    io.err(`vpt-serve: GET ${url} -> HTTP ${res.status}`);
    return 1;
  }
  const missing: string[] = [];
  if ((res.headers.get('content-type') ?? '').startsWith('text/html')) {
    for (const dep of pageDependencies(await res.text())) {
      const depUrl = new URL(dep, url).href;
      const r = await fetch(depUrl, { method: 'HEAD', signal: AbortSignal.timeout(CHECK_TIMEOUT_MS) });
      if (r.status !== 200) missing.push(`${depUrl} (HTTP ${r.status})`);
    }
  }
  if (missing.length) {
    io.err(`vpt-serve: ${url} loads, but these are missing (run pnpm run build?): ${missing.join(', ')}`);
    return 1;
  }
  io.out(`ok ${url}`);
  return 0;
}

/**
 * vpt-serve: serve the workspace root on 127.0.0.1 and print a page's URL. Resolves
 * with an exit code in --check mode (or on error); otherwise with `server` running.
 */
export async function runServe(
  argv: string[],
  io: CliIO = processIO,
): Promise<{ code: number | null; server?: StaticServer }> {
  let server: StaticServer | undefined;
  try {
    const args = parseServeArgs(argv);
    if (args.help) {
      io.out(SERVE_USAGE);
      return { code: 0 };
    }
    const workspace = workspaceRoot();
    const root = path.resolve(args.root ?? workspace ?? process.cwd());
    server = await startStaticServer(root, { port: args.port });
    // Outside the repository the packages are not under the root: serve the installed
    // ones at the URLs the pages' import maps use.
    if (root !== workspace) mountPagePackages(server);
    else mountThirdParty(server); // the headless page's third-party imports live in node_modules
    const url = new URL(args.open.replace(/^\/+/, ''), server.url).href;
    if (args.check) {
      const code = await check(url, io);
      await server.close();
      return { code };
    }
    io.err(`vpt-serve: serving ${root} (Ctrl-C to stop)`);
    io.out(url);
    return { code: null, server };
  } catch (e) {
    await server?.close();
    io.err(`vpt-serve: ${oneLine(e)}`);
    return { code: 1 };
  }
}
