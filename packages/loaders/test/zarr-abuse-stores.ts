// OME-Zarr stores whose .zarray lies about shape and chunks, shared by the loaders' reader
// tests and vpt-render's CLI tests, so both meet the same abuse.
import fs from 'node:fs';
import path from 'node:path';
import zlib from 'node:zlib';
import { writeZarrFolder } from './zarr-fixtures.js';

/** An edit applied to each level's .zarray (level 0 is the finest). */
export type ZarrayEdit = (zarray: Record<string, any>, level: number) => void;

export interface AbuseStoreOptions {
  levels?: number;
  codec?: 'raw' | 'gzip';
  /** Every voxel's value (the stores are uniform). */
  fill?: number;
}

/** 1³ chunks on a 64³ shape: 262144 chunk requests for one read. */
export const TINY_CHUNKS: ZarrayEdit = (j) => {
  j.shape = [64, 64, 64];
  j.chunks = [1, 1, 1];
};

/** Level 0 claims 100000³ (no typed array holds it); with `levels: 2`, level 1 is the 8³ that fits. */
export const HUGE_SHAPE: ZarrayEdit = (j, level) => {
  if (level === 0) {
    j.shape = [100000, 100000, 100000];
    j.chunks = [64, 64, 64];
  }
};

/** A chunk side of 0 (zarrita's "empty iterator" before the check). */
export const ZERO_CHUNK: ZarrayEdit = (j) => {
  j.chunks = [0, 8, 8];
};

/**
 * A v0.4 (Zarr v2) uint8 store of 16³ in 8³ chunks with `levels` levels at `dir`, then `edit`
 * applied to each level's .zarray. Returns `dir`.
 */
export async function writeAbusedStore(
  dir: string,
  edit: ZarrayEdit,
  options: AbuseStoreOptions = {},
): Promise<string> {
  const levels = options.levels ?? 1;
  await writeZarrFolder(
    dir,
    {
      dims: [16, 16, 16],
      type: 'uint8',
      spacing: [1, 1, 1],
      images: [[new Uint8Array(16 ** 3).fill(options.fill ?? 7)]],
    },
    { version: '0.4', codec: options.codec ?? 'raw', chunk: [8, 8, 8], levels },
  );
  for (let k = 0; k < levels; k++) {
    const file = path.join(dir, String(k), '.zarray');
    const j = JSON.parse(fs.readFileSync(file, 'utf8'));
    edit(j, k);
    fs.writeFileSync(file, JSON.stringify(j));
  }
  return dir;
}

/**
 * Replaces the first chunk of a gzip store with 256 MiB of zeros, ~250 KiB compressed, where
 * an 8³ uint8 chunk (512 bytes) belongs.
 */
export function plantGzipBomb(dir: string): void {
  const chunk = path.join(dir, '0', '0', '0', '0');
  if (!fs.existsSync(chunk)) throw new Error(`no first chunk at ${chunk}`);
  fs.writeFileSync(chunk, zlib.gzipSync(Buffer.alloc(256 << 20), { level: 1 }));
}
