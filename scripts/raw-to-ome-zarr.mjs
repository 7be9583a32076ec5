#!/usr/bin/env node
/**
 * Convert a raw volume with its JSON sidecar into a multiscale OME-Zarr image, with
 * @vpt/loaders' writeOmeZarr (build the packages first: pnpm run build).
 *
 *   node scripts/raw-to-ome-zarr.mjs data/mri_head_volpack_brainsmall_128x128x84_uint8.json out/head.ome.zarr \
 *     [--version 0.4|0.5] [--codec raw|gzip|zstd|blosc] [--levels N] [--chunk N] [--unit micrometer]
 *     [--channels more.json,…]
 *
 * `--channels` (convertRawToOmeZarr: a list of sidecars) adds more raw volumes of the same dims
 * and voxel type as further channels: the store then has a `c` axis (tczyx), channel 0 the
 * first sidecar, and one omero window per channel (each sidecar's value_range); a sidecar's
 * `channel_label` and `channel_color` (RRGGBB) become its channel's omero label and colour.
 *
 * Levels are 2× box averages (every side longer than 1 halves); the sidecar's value_range
 * becomes the omero channel window, which vpt reads as the normalization range.
 * The fetch script (pnpm data:fetch) uses convertRawToOmeZarr for the gallery's copy.
 */
import fs from 'node:fs';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import { parseCliOrExit } from '@vpt/cli-options';

const root = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '..');

const ARRAYS = { uint8: Uint8Array, uint16: Uint16Array, int16: Int16Array, float32: Float32Array };

/** A sidecar and the typed array of the raw file beside it. */
function readRaw(sidecarPath) {
  const sidecar = JSON.parse(fs.readFileSync(sidecarPath, 'utf8'));
  const rawPath = path.join(
    path.dirname(sidecarPath),
    sidecar.file ?? path.basename(sidecarPath).replace(/\.json$/, '.raw'),
  );
  const Ctor = ARRAYS[sidecar.voxel_type];
  if (!Ctor) throw new Error(`${sidecarPath}: voxel_type ${sidecar.voxel_type} is not uint8, uint16, int16 or float32`);
  if ((sidecar.endianness ?? 'little') !== 'little')
    throw new Error(`${sidecarPath}: only little-endian raw data is converted`);
  const bytes = fs.readFileSync(rawPath);
  const data = new Ctor(bytes.buffer.slice(bytes.byteOffset, bytes.byteOffset + bytes.byteLength));
  if (data.length !== sidecar.dims[0] * sidecar.dims[1] * sidecar.dims[2])
    throw new Error(
      `${rawPath}: ${data.length} voxels, the sidecar's dims ${sidecar.dims.join('×')} need another count`,
    );
  return { sidecar, data };
}

/**
 * Write `outDir` (replaced) from a sidecar and the raw file beside it; a list of sidecars (one
 * grid and voxel type) becomes one channel each, in order, on a `c` axis.
 */
export async function convertRawToOmeZarr(sidecarPaths, outDir, options = {}) {
  const { writeOmeZarr } = await import(path.join(root, 'packages', 'loaders', 'dist', 'index.js'));
  const paths = Array.isArray(sidecarPaths) ? sidecarPaths : [sidecarPaths];
  const channels = paths.map(readRaw);
  const { sidecar } = channels[0];
  for (const [i, c] of channels.entries()) {
    if (c.sidecar.voxel_type !== sidecar.voxel_type || c.sidecar.dims.some((d, k) => d !== sidecar.dims[k]))
      throw new Error(
        `${paths[i]}: channel ${i} is ${c.sidecar.dims.join('×')} ${c.sidecar.voxel_type}, channel 0 ${sidecar.dims.join('×')} ${sidecar.voxel_type}: the channels of a store share one grid and type`,
      );
  }
  const sidecarPath = paths[0];
  fs.rmSync(outDir, { recursive: true, force: true });
  fs.mkdirSync(outDir, { recursive: true });
  const chunk = options.chunk ?? 64;
  await writeOmeZarr(
    (key, value) => {
      const file = path.join(outDir, ...key.split('/'));
      fs.mkdirSync(path.dirname(file), { recursive: true });
      fs.writeFileSync(file, value);
    },
    {
      dims: sidecar.dims,
      type: sidecar.voxel_type,
      spacing: sidecar.spacing ?? [1, 1, 1],
      images: [channels.map((c) => c.data)],
    },
    {
      version: options.version ?? '0.4',
      codec: options.codec ?? 'zstd',
      levels: options.levels ?? 1,
      chunk: [chunk, chunk, chunk],
      unit: options.unit ?? 'micrometer',
      // A multichannel store's name is not its channel 0's title: datasets.json omeZarr.name.
      name: options.name ?? sidecar.title ?? path.basename(sidecarPath, '.json'),
      ...(channels.every((c) => Array.isArray(c.sidecar.value_range))
        ? { windows: channels.map((c) => c.sidecar.value_range) }
        : {}),
      // A sidecar's channel_label / channel_color (RRGGBB) name and colour its channel (omero),
      // which the viewer shows; where none has them, the viewer's defaults apply.
      ...(channels.some((c) => c.sidecar.channel_label || c.sidecar.channel_color)
        ? {
            channelInfo: channels.map((c) => ({
              ...(c.sidecar.channel_label ? { label: String(c.sidecar.channel_label) } : {}),
              ...(c.sidecar.channel_color ? { color: String(c.sidecar.channel_color) } : {}),
            })),
          }
        : {}),
    },
  );
  return outDir;
}

if (process.argv[1] && path.resolve(process.argv[1]) === fileURLToPath(import.meta.url)) {
  const { sidecar, out, channels, ...given } = parseCliOrExit({
    name: 'node scripts/raw-to-ome-zarr.mjs',
    synopsis:
      'SIDECAR.json OUT.ome.zarr [--version 0.4|0.5] [--codec raw|gzip|zstd|blosc] [--levels N] [--chunk N] [--unit U] [--channels A.json,B.json]',
    summary: 'Write a raw volume (with its JSON sidecar) as a multiscale OME-Zarr store.',
    positionals: [
      { key: 'sidecar', name: 'SIDECAR.json', type: 'string', required: true, description: "the raw file's sidecar" },
      { key: 'out', name: 'OUT.ome.zarr', type: 'string', required: true, description: 'the store folder to write' },
    ],
    options: {
      version: { type: 'string', choices: ['0.4', '0.5'], description: 'NGFF version (default 0.4)' },
      codec: { type: 'string', choices: ['raw', 'gzip', 'zstd', 'blosc'], description: 'chunk codec (default zstd)' },
      levels: { type: 'integer', min: 1, description: 'resolution levels, each 2x down (default 1)' },
      chunk: { type: 'integer', min: 1, description: 'chunk side in voxels (default 64)' },
      unit: { type: 'string', description: "the axes' unit (default micrometer)" },
      channels: {
        type: 'list',
        valueName: 'A.json,B.json',
        description: 'sidecars of further channels (same dims and type): a c axis',
      },
    },
  });
  // Only the options given, so convertRawToOmeZarr's own defaults apply to the rest.
  const options = Object.fromEntries(Object.entries(given).filter(([, v]) => v !== undefined));
  await convertRawToOmeZarr([sidecar, ...(channels ?? [])], out, options);
  console.log(`wrote ${out}`);
}
