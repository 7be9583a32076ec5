import fs from 'node:fs';
import http from 'node:http';
import type { AddressInfo } from 'node:net';
import path from 'node:path';

/**
 * A tiny static file server for headless rendering and the demo. It binds 127.0.0.1
 * because WebGPU is only exposed to secure contexts, and http://127.0.0.1 counts as one.
 */
export interface StaticServer {
  /** Origin with a trailing slash, e.g. `http://127.0.0.1:41234/`. */
  url: string;
  port: number;
  /**
   * Serve `dir` under the URL path `urlPath` (e.g. `/packages/core/`); without a path a
   * fresh `/__mount/<n>/` is chosen. Mounting the same folder twice returns the first
   * path. Returns the URL path, with a trailing slash. With `confine`, a file whose real
   * path (symlinks followed) leaves `dir` is not served.
   */
  mount(dir: string, urlPath?: string, options?: { confine?: boolean }): string;
  /**
   * Serve exactly these files (nothing else of their folders) under a fresh
   * `/__files/<n>/`, each by its base name; returns that URL path. Files sharing a base
   * name must be mounted separately.
   */
  mountFiles(files: readonly string[]): string;
  close(): Promise<void>;
}

export interface StaticServerOptions {
  /** TCP port; 0 (the default) picks a free one. */
  port?: number;
  host?: string;
}

const MIME: Record<string, string> = {
  '.html': 'text/html; charset=utf-8',
  '.js': 'text/javascript; charset=utf-8',
  '.mjs': 'text/javascript; charset=utf-8',
  '.json': 'application/json; charset=utf-8',
  '.map': 'application/json; charset=utf-8',
  '.css': 'text/css; charset=utf-8',
  '.png': 'image/png',
  '.wasm': 'application/wasm',
  '.svg': 'image/svg+xml',
  '.txt': 'text/plain; charset=utf-8',
  '.md': 'text/plain; charset=utf-8',
  '.raw': 'application/octet-stream',
};

export function mimeType(file: string): string {
  return MIME[path.extname(file).toLowerCase()] ?? 'application/octet-stream';
}

/** Normalise a URL path prefix to `/a/b/` form. */
function normalizePrefix(p: string): string {
  const parts = p.split('/').filter(Boolean);
  return parts.length ? `/${parts.join('/')}/` : '/';
}

/**
 * Map a decoded URL path to a file under `dir`, or null when it would leave `dir`
 * (`..` segments, encoded or not, and absolute tricks all end up outside).
 */
export function resolveInside(dir: string, relUrlPath: string): string | null {
  const base = path.resolve(dir);
  const target = path.resolve(base, `.${path.posix.sep}${relUrlPath}`);
  if (target !== base && !target.startsWith(base + path.sep)) return null;
  return target;
}

/** Does `file` (symlinks followed) lie inside `dir`? False for a file that does not exist. */
function realpathInside(file: string, dir: string): boolean {
  try {
    const real = fs.realpathSync(file),
      base = fs.realpathSync(dir);
    return real === base || real.startsWith(base + path.sep);
  } catch {
    return false;
  }
}

/**
 * Serve `root` (or only mounted folders when root is null) over HTTP. Mounts take
 * precedence over the root, the longest matching prefix first.
 */
export async function startStaticServer(root: string | null, options: StaticServerOptions = {}): Promise<StaticServer> {
  const mounts = new Map<string, string | Map<string, string>>(); // url prefix -> absolute dir, or base name -> file
  const confined = new Set<string>(); // prefixes whose files must really lie inside their folder
  let mountCount = 0;
  let fileMountCount = 0;

  const lookup = (urlPath: string): string | null => {
    const prefixes = [...mounts.keys()].sort((a, b) => b.length - a.length);
    for (const prefix of prefixes) {
      if (urlPath.startsWith(prefix) || `${urlPath}/` === prefix) {
        const target = mounts.get(prefix)!;
        if (typeof target !== 'string') return target.get(urlPath.slice(prefix.length)) ?? null;
        const file = resolveInside(target, urlPath.slice(prefix.length));
        if (file && confined.has(prefix) && !realpathInside(file, target)) return null;
        return file;
      }
    }
    return root === null ? null : resolveInside(root, urlPath);
  };

  const server = http.createServer((req, res) => {
    const notFound = (status = 404, text = 'not found') => {
      res.writeHead(status, { 'content-type': 'text/plain; charset=utf-8', 'cache-control': 'no-store' });
      res.end(text);
    };
    if (req.method !== 'GET' && req.method !== 'HEAD') return notFound(405, 'method not allowed');
    let urlPath: string;
    try {
      urlPath = decodeURIComponent(new URL(req.url ?? '/', 'http://x').pathname);
    } catch {
      return notFound(400, 'bad request');
    }
    if (urlPath.includes('\0')) return notFound(400, 'bad request');
    let file = lookup(urlPath);
    if (!file) return notFound();
    let stat: fs.Stats;
    try {
      stat = fs.statSync(file);
      if (stat.isDirectory()) {
        // A folder URL serves its index.html, so `/apps/gallery/` works in a browser.
        file = path.join(file, 'index.html');
        stat = fs.statSync(file);
      }
    } catch {
      return notFound();
    }
    if (!stat.isFile()) return notFound();
    res.writeHead(200, {
      'content-type': mimeType(file),
      'content-length': stat.size,
      // Rebuilt packages must never be served stale from the browser's cache.
      'cache-control': 'no-store',
    });
    if (req.method === 'HEAD') {
      res.end();
      return;
    }
    const stream = fs.createReadStream(file);
    stream.on('error', () => res.destroy());
    stream.pipe(res);
  });

  const host = options.host ?? '127.0.0.1';
  await new Promise<void>((resolve, reject) => {
    server.once('error', reject);
    server.listen(options.port ?? 0, host, () => {
      server.off('error', reject);
      resolve();
    });
  });
  const port = (server.address() as AddressInfo).port;

  return {
    url: `http://${host}:${port}/`,
    port,
    mount(dir: string, urlPath?: string, options: { confine?: boolean } = {}): string {
      const abs = path.resolve(dir);
      if (urlPath === undefined) {
        for (const [prefix, d] of mounts) if (d === abs && confined.has(prefix) === !!options.confine) return prefix;
        urlPath = `/__mount/${mountCount++}/`;
      }
      const prefix = normalizePrefix(urlPath);
      mounts.set(prefix, abs);
      if (options.confine) confined.add(prefix);
      else confined.delete(prefix);
      return prefix;
    },
    mountFiles(files: readonly string[]): string {
      const byName = new Map<string, string>();
      for (const f of files) {
        const abs = path.resolve(f);
        const name = path.basename(abs);
        if (byName.has(name) && byName.get(name) !== abs) throw new Error(`mountFiles: two files named ${name}`);
        byName.set(name, abs);
      }
      const prefix = `/__files/${fileMountCount++}/`;
      mounts.set(prefix, byName);
      return prefix;
    },
    close: () =>
      new Promise<void>((resolve) => {
        server.close(() => resolve());
        server.closeAllConnections();
      }),
  };
}
