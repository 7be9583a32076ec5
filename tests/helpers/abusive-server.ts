/**
 * An HTTP server that misbehaves on request, for the request-policy tests (Node unit tests
 * and browser tests alike): it serves the files it is given, and the paths in `faults` the
 * way a broken or hostile server would. It listens on 127.0.0.1 only, caps its connections
 * and the bytes of every answer, and closes itself after `lifetimeMs` even if a test forgets.
 */
import http from 'node:http';
import type { AddressInfo } from 'node:net';
import zlib from 'node:zlib';

export type AbuseFault =
  | 'no-headers' // accept the request, never answer
  | 'stall-body' // headers and the first 16 bytes, then nothing
  | 'trickle' // headers, then one byte every trickleMs
  | 'redirect-loop' // 302 to itself, forever
  | 'length-bomb' // announce 1 TiB, then stream zeros as fast as the client reads
  | 'endless' // no content-length, zeros streamed until the client gives up
  | 'gzip-bomb' // 64 MiB of zeros, gzip-encoded (about 64 KiB on the wire)
  | '503'; // a server error on every attempt

export interface AbusiveServer {
  /** Origin + '/', e.g. http://127.0.0.1:1234/ */
  url: string;
  /** Bytes served at a path (e.g. '/head.json'); a path missing here answers 404. */
  files: Map<string, Uint8Array | string>;
  /** How a path misbehaves (a path missing here is served normally). */
  faults: Map<string, AbuseFault>;
  /** Requests seen per path (to count retries). */
  hits: Map<string, number>;
  close(): Promise<void>;
}

export interface AbusiveServerOptions {
  /** Interval of the 'trickle' fault's bytes (default 200 ms). */
  trickleMs?: number;
  /** The server closes itself after this long (default 10 minutes). */
  lifetimeMs?: number;
  /** Most bytes one answer sends, whatever the fault (default 512 MiB). */
  maxAnswerBytes?: number;
}

export async function startAbusiveServer(options: AbusiveServerOptions = {}): Promise<AbusiveServer> {
  const trickleMs = options.trickleMs ?? 200;
  const maxAnswerBytes = options.maxAnswerBytes ?? 512 * 1024 * 1024;
  const files = new Map<string, Uint8Array | string>();
  const faults = new Map<string, AbuseFault>();
  const hits = new Map<string, number>();
  const open = new Set<http.ServerResponse>();
  const timers = new Set<NodeJS.Timeout>();
  const zeros = Buffer.alloc(64 * 1024);
  // Compressed before the first request, so that answering it takes no time.
  const gzipBomb = zlib.gzipSync(Buffer.alloc(64 * 1024 * 1024), { level: 9 });

  // Write zeros while the client reads, up to the answer bound.
  const stream = (res: http.ServerResponse) => {
    let sent = 0;
    const pump = () => {
      while (sent < maxAnswerBytes && !res.destroyed) {
        sent += zeros.length;
        if (!res.write(zeros)) return void res.once('drain', pump);
      }
      res.destroy();
    };
    pump();
  };

  const server = http.createServer((req, res) => {
    const urlPath = new URL(req.url ?? '/', 'http://x').pathname;
    hits.set(urlPath, (hits.get(urlPath) ?? 0) + 1);
    open.add(res);
    res.on('close', () => open.delete(res));
    res.setHeader('access-control-allow-origin', '*');
    res.setHeader('cache-control', 'no-store');
    const fault = faults.get(urlPath);
    const body = files.get(urlPath);
    const bytes = typeof body === 'string' ? Buffer.from(body) : body ? Buffer.from(body) : Buffer.alloc(4096);
    switch (fault) {
      case 'no-headers':
        return;
      case 'redirect-loop':
        return void res.writeHead(302, { location: urlPath }).end();
      case '503':
        return void res.writeHead(503).end('unavailable');
      case 'stall-body':
        res.writeHead(200, { 'content-length': bytes.length, 'content-type': 'application/octet-stream' });
        res.write(bytes.subarray(0, 16));
        return;
      case 'trickle': {
        res.writeHead(200, { 'content-length': bytes.length, 'content-type': 'application/octet-stream' });
        let at = 0;
        const timer = setInterval(() => {
          if (res.destroyed || at >= bytes.length) {
            clearInterval(timer);
            timers.delete(timer);
            return void res.end();
          }
          res.write(bytes.subarray(at, ++at));
        }, trickleMs);
        timers.add(timer);
        return;
      }
      case 'length-bomb':
        res.writeHead(200, { 'content-length': String(2 ** 40), 'content-type': 'application/octet-stream' });
        return stream(res);
      case 'endless':
        res.writeHead(200, { 'content-type': 'application/octet-stream' });
        return stream(res);
      case 'gzip-bomb':
        return void res
          .writeHead(200, {
            'content-encoding': 'gzip',
            'content-length': gzipBomb.length,
            'content-type': 'application/octet-stream',
          })
          .end(gzipBomb);
      default:
        if (!body) return void res.writeHead(404).end('not found');
        res.writeHead(200, { 'content-length': bytes.length, 'content-type': 'application/octet-stream' });
        return void res.end(bytes);
    }
  });
  server.maxConnections = 64;
  await new Promise<void>((r) => server.listen(0, '127.0.0.1', r));
  const { port } = server.address() as AddressInfo;
  let closed: Promise<void> | undefined;
  const close = () =>
    (closed ??= new Promise<void>((r) => {
      clearTimeout(lifetime);
      for (const t of timers) clearInterval(t);
      for (const res of open) res.destroy();
      server.closeAllConnections();
      server.close(() => r());
    }));
  const lifetime = setTimeout(() => void close(), options.lifetimeMs ?? 600_000);
  lifetime.unref();
  return { url: `http://127.0.0.1:${port}/`, files, faults, hits, close };
}
