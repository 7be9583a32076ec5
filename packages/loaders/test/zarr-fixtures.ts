/**
 * OME-Zarr fixtures written at test time (into a temp folder, nothing committed) with the
 * package's own writer, and an HTTP server with range requests that can fail chosen
 * requests (404, truncated answers, stalls, one-off 500s). Used by the loaders' unit tests
 * and the browser tests in tests/.
 */
import fs from 'node:fs';
import http from 'node:http';
import type { AddressInfo } from 'node:net';
import os from 'node:os';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import type { VoxelArray } from '@vpt/core';
import { writeOmeZarr, type OmeZarrImage, type WriteOmeZarrOptions } from '../src/index.js';

const HERE = path.dirname(fileURLToPath(import.meta.url));
export const REPO = path.resolve(HERE, '..', '..', '..');
export const HEAD_SIDECAR = path.join(REPO, 'data', 'mri_head_volpack_brainsmall_128x128x84_uint8.json');
export const HEAD_RAW = path.join(REPO, 'data', 'mri_head_volpack_brainsmall_128x128x84_uint8.raw');

export function tempDir(prefix = 'vpt-zarr-'): string {
  return fs.mkdtempSync(path.join(os.tmpdir(), prefix));
}

/** Write an OME-Zarr image into the folder `dir` (created). */
export async function writeZarrFolder(
  dir: string,
  image: OmeZarrImage,
  options: WriteOmeZarrOptions = {},
): Promise<string> {
  fs.mkdirSync(dir, { recursive: true });
  await writeOmeZarr(
    (key, bytes) => {
      const file = path.join(dir, ...key.split('/'));
      fs.mkdirSync(path.dirname(file), { recursive: true });
      fs.writeFileSync(file, bytes);
    },
    image,
    options,
  );
  return dir;
}

/** The bundled MRI head's voxels (128 × 128 × 84 uint8, spacing 1). */
export function headVoxels(): Uint8Array {
  return new Uint8Array(fs.readFileSync(HEAD_RAW));
}

/** An OME-Zarr copy of the bundled head: level 0 = the raw voxels, omero window = the sidecar's value_range. */
export async function writeHeadZarr(dir: string, options: WriteOmeZarrOptions = {}): Promise<string> {
  return writeZarrFolder(
    dir,
    { dims: [128, 128, 84], type: 'uint8', spacing: [1, 1, 1], images: [[headVoxels()]] },
    { chunk: [64, 64, 32], windows: [[0, 202]], ...options },
  );
}

/** A deterministic test pattern with every value distinct enough to catch axis mix-ups. */
export function pattern(dims: readonly number[], type: 'uint8' | 'uint16' | 'int16' | 'float32', seed = 0): VoxelArray {
  const n = dims[0] * dims[1] * dims[2];
  const out =
    type === 'uint8'
      ? new Uint8Array(n)
      : type === 'uint16'
        ? new Uint16Array(n)
        : type === 'int16'
          ? new Int16Array(n)
          : new Float32Array(n);
  for (let i = 0; i < n; i++) {
    const v = (i * 2654435761 + seed * 97) >>> 0;
    out[i] =
      type === 'uint8'
        ? v % 251
        : type === 'float32'
          ? (v % 100003) / 7 - 5000
          : type === 'int16'
            ? (v % 60001) - 30000
            : v % 65521;
  }
  return out;
}

// ——— an HTTP server that fails on request ———

export type Fault = '404' | 'truncate' | 'stall' | '500-once' | 'slow';

export interface FaultServer {
  /** Origin + '/', e.g. http://127.0.0.1:1234/ */
  url: string;
  /** Fail requests whose URL path ends with a key of this map. */
  faults: Map<string, Fault>;
  /** Every request path served (to check what was fetched). */
  log: string[];
  /** The query string of every request (with its '?', '' when none). */
  queries: string[];
  /** Bytes of body sent. */
  bytesSent: number;
  close(): Promise<void>;
}

/**
 * Serve `root` with Range support (206), CORS open, and `faults`: '404'; 'truncate' (a
 * content-length larger than the body, then the connection closes); 'stall' (headers,
 * then nothing until the client gives up); '500-once' (one 500, then normal); 'slow' (the
 * answer after 300 ms).
 */
export async function startFaultServer(root: string): Promise<FaultServer> {
  const faults = new Map<string, Fault>();
  const log: string[] = [];
  const queries: string[] = [];
  const stalled = new Set<http.ServerResponse>();
  const state = { bytesSent: 0 };
  const server = http.createServer((req, res) => {
    const urlPath = decodeURIComponent(new URL(req.url ?? '/', 'http://x').pathname);
    log.push(urlPath);
    queries.push(new URL(req.url ?? '/', 'http://x').search);
    res.setHeader('access-control-allow-origin', '*');
    res.setHeader('access-control-allow-headers', 'range');
    res.setHeader('access-control-expose-headers', 'content-length, content-range');
    res.setHeader('cache-control', 'no-store');
    if (req.method === 'OPTIONS') return void res.writeHead(204).end();
    const fault = [...faults].find(([k]) => urlPath.endsWith(k))?.[1];
    if (fault === '404') return void res.writeHead(404).end('not found');
    if (fault === '500-once') {
      faults.delete([...faults].find(([k]) => urlPath.endsWith(k))![0]);
      return void res.writeHead(500).end('try again');
    }
    const file = path.resolve(root, '.' + urlPath);
    if (!file.startsWith(path.resolve(root)) || !fs.existsSync(file) || !fs.statSync(file).isFile())
      return void res.writeHead(404).end('not found');
    let body: Uint8Array = fs.readFileSync(file);
    let status = 200;
    const range = /^bytes=(\d*)-(\d*)$/.exec(String(req.headers.range ?? ''));
    if (range) {
      const size = body.length;
      const start = range[1] === '' ? Math.max(0, size - Number(range[2])) : Number(range[1]);
      const end = range[1] === '' || range[2] === '' ? size - 1 : Math.min(size - 1, Number(range[2]));
      res.setHeader('content-range', `bytes ${start}-${end}/${size}`);
      body = body.subarray(start, end + 1);
      status = 206;
    }
    const send = () => {
      if (fault === 'truncate') {
        res.writeHead(status, { 'content-length': body.length, 'content-type': 'application/octet-stream' });
        res.write(body.subarray(0, body.length >> 1));
        state.bytesSent += body.length >> 1;
        setTimeout(() => res.destroy(), 20);
        return;
      }
      if (fault === 'stall') {
        res.writeHead(status, { 'content-length': body.length, 'content-type': 'application/octet-stream' });
        stalled.add(res);
        return;
      }
      res.writeHead(status, { 'content-length': body.length, 'content-type': 'application/octet-stream' });
      res.end(body);
      state.bytesSent += body.length;
    };
    if (fault === 'slow') setTimeout(send, 300);
    else send();
  });
  await new Promise<void>((r) => server.listen(0, '127.0.0.1', r));
  const { port } = server.address() as AddressInfo;
  return {
    url: `http://127.0.0.1:${port}/`,
    faults,
    log,
    queries,
    get bytesSent() {
      return state.bytesSent;
    },
    set bytesSent(n: number) {
      state.bytesSent = n;
    },
    close: () =>
      new Promise<void>((r) => {
        for (const res of stalled) res.destroy();
        server.closeAllConnections?.();
        server.close(() => r());
      }),
  };
}
