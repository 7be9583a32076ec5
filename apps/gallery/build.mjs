// Build the gallery, a static site, into dist/:
//   dist/index.html, compare.html,     the pages (src/*.html)
//   three.html
//   dist/assets/                       their scripts and styles (src/*.js, *.css) and
//                                      the one-file <vpt-viewer> bundle with its lazy chunks
//   dist/data/                         the bundled volumes (copied) and data/fetched/
//                                      (linked: up to hundreds of MB; `cp -rL dist …` to deploy)
//   dist/data/manifest.json            what is there: every sidecar, real-format file and OME-Zarr store found;
//                                      a label sidecar ("labels_of") is no dataset of its own but
//                                      a second entry of its image with `labels` (the viewer's attribute)
//   dist/scenes/                       the CLI's scene files (the bundled head's presets)
// Usage: node build.mjs [--production]   (pnpm --filter @vpt/gallery run build[:production])
// A production build (the site visitors see) leaves out developer hints such as `pnpm data:fetch`.
import fs from 'node:fs';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import { parseCliOrExit } from '@vpt/cli-options';

const { production } = parseCliOrExit({
  name: 'node build.mjs',
  synopsis: '[--production]',
  summary: 'Build the gallery, a static site, into apps/gallery/dist/.',
  options: { production: { type: 'boolean', description: 'leave out developer hints such as `pnpm data:fetch`' } },
});
const here = path.dirname(fileURLToPath(import.meta.url));
const root = path.resolve(here, '../..');
const dist = path.join(here, 'dist');
const src = path.join(here, 'src');
const dataDir = path.join(root, 'data');

function fail(message) {
  console.error(`gallery build: ${message}`);
  process.exit(1);
}

// The viewer bundle (built by `pnpm run build`, which builds every package).
const viewerDist = path.join(here, 'node_modules', '@vpt', 'viewer', 'dist');
if (!fs.existsSync(path.join(viewerDist, 'vpt-viewer.bundle.js'))) {
  fail(`${path.relative(root, viewerDist)}/vpt-viewer.bundle.js is missing: build the packages first (pnpm run build)`);
}

fs.rmSync(dist, { recursive: true, force: true });
fs.mkdirSync(path.join(dist, 'assets'), { recursive: true });
fs.mkdirSync(path.join(dist, 'data'), { recursive: true });

for (const f of fs.readdirSync(src)) {
  const from = path.join(src, f);
  if (f.endsWith('.html')) fs.copyFileSync(from, path.join(dist, f));
  else if (/\.(js|css)$/.test(f)) fs.copyFileSync(from, path.join(dist, 'assets', f));
}
// The headless CLI's scene files double as the bundled head's presets.
fs.cpSync(path.join(here, 'scenes'), path.join(dist, 'scenes'), { recursive: true });
fs.copyFileSync(path.join(viewerDist, 'vpt-viewer.bundle.js'), path.join(dist, 'assets', 'vpt-viewer.bundle.js'));
const chunks = path.join(viewerDist, 'bundle-chunks');
if (fs.existsSync(chunks)) fs.cpSync(chunks, path.join(dist, 'assets', 'bundle-chunks'), { recursive: true });
if (fs.existsSync(path.join(viewerDist, 'loader-worker.js'))) {
  fs.copyFileSync(path.join(viewerDist, 'loader-worker.js'), path.join(dist, 'assets', 'loader-worker.js'));
  fs.cpSync(path.join(viewerDist, 'chunks'), path.join(dist, 'assets', 'chunks'), { recursive: true });
}

// The three.js page's script (three/three-scene.js), bundled with three.js, @vpt/three, the
// two renderers it offers and the viewer's TF editor (the packages' dist/, built by `pnpm run build`).
{
  const { rollup } = await import('rollup');
  const { nodeResolve } = await import('@rollup/plugin-node-resolve');
  const bundle = await rollup({
    input: path.join(here, 'three', 'three-scene.js'),
    plugins: [nodeResolve({ browser: true })],
  });
  // One file: the viewer's lazily loaded parts (its element is defined, never instantiated here) go inline.
  await bundle.write({ file: path.join(dist, 'assets', 'three-scene.js'), format: 'es', inlineDynamicImports: true });
  await bundle.close();
}

// ——— data ———

const REAL_FORMATS = [/\.nrrd$/i, /\.nhdr$/i, /\.nii(\.gz)?$/i];
const readJson = (f) => {
  try {
    return JSON.parse(fs.readFileSync(f, 'utf8'));
  } catch {
    return null;
  }
};
const registry = readJson(path.join(dataDir, 'datasets.json'))?.datasets ?? [];
const registryEntry = (name) => registry.find((d) => d.name === name || d.original?.file === name);

/** Label sidecars found by scan(): attached to their image afterwards (withLabels). */
const labelSidecars = [];

/** The channel count of an OME-Zarr store's level 0 (its `c` axis), 1 without one. */
function zarrChannels(store) {
  const attrs = readJson(path.join(store, '.zattrs')) ?? readJson(path.join(store, 'zarr.json'))?.attributes;
  const ms = (attrs?.ome ?? attrs)?.multiscales?.[0];
  const c = ms?.axes?.findIndex((a) => (typeof a === 'string' ? a : a.name) === 'c') ?? -1;
  if (c < 0 || !ms.datasets?.[0]) return 1;
  const level = path.join(store, ms.datasets[0].path);
  const shape = readJson(path.join(level, '.zarray'))?.shape ?? readJson(path.join(level, 'zarr.json'))?.shape;
  return shape?.[c] ?? 1;
}

/** One manifest entry per sidecar (with its .raw present) and per real-format file. */
function scan(folder, urlPrefix, bundled) {
  if (!fs.existsSync(folder)) return [];
  const out = [];
  for (const f of fs.readdirSync(folder).sort()) {
    const file = path.join(folder, f);
    if (f.endsWith('.json')) {
      const meta = readJson(file);
      if (!meta || !Array.isArray(meta.dims) || !meta.voxel_type) continue; // not a sidecar
      const raw = typeof meta.file === 'string' ? meta.file : f.replace(/\.json$/, '.raw');
      if (!fs.existsSync(path.join(folder, raw))) continue;
      const id = f.replace(/\.json$/, '');
      const reg = registryEntry(id);
      if (meta.labels_of) {
        labelSidecars.push({
          of: meta.labels_of,
          url: `${urlPrefix}${f}`,
          meta,
          bytes: fs.statSync(path.join(folder, raw)).size,
        });
        continue;
      }
      out.push({
        id,
        url: `${urlPrefix}${f}`,
        format: 'raw',
        bundled,
        title: meta.title ?? id,
        modality: meta.modality ?? '',
        dims: meta.dims,
        type: meta.voxel_type,
        spacing: meta.spacing ?? [1, 1, 1],
        valueRange: meta.value_range ?? null,
        bytes: fs.statSync(path.join(folder, raw)).size,
        license: meta.license ?? reg?.license ?? '',
        gpl: reg?.gpl ?? false,
      });
    } else if (/\.ome\.zarr$/i.test(f) && ['.zattrs', 'zarr.json'].some((m) => fs.existsSync(path.join(file, m)))) {
      // A multiscale OME-Zarr copy (the fetch script's "omeZarr"): the viewer refines it level by level.
      const reg = registry.find((d) => d.omeZarr?.file === f);
      const twin = reg ? readJson(path.join(folder, `${reg.name}.json`)) : null;
      const levels = fs.readdirSync(file).filter((l) => /^\d+$/.test(l)).length;
      const channels = zarrChannels(file);
      out.push({
        id: f.replace(/\.ome\.zarr$/i, '') + '-ome-zarr',
        url: `${urlPrefix}${f}`,
        format: 'ome-zarr',
        bundled,
        title:
          reg?.omeZarr?.galleryTitle ??
          `${twin?.title ?? f} — OME-Zarr, ${levels} levels, refined level by level${channels > 1 ? `, ${channels} channels` : ''}`,
        ...(channels > 1 ? { channels } : {}),
        modality: twin?.modality ?? '',
        dims: twin?.dims ?? null,
        type: twin?.voxel_type ?? null,
        spacing: twin?.spacing ?? null,
        valueRange: twin?.value_range ?? null,
        bytes: null,
        license: twin?.license ?? reg?.license ?? '',
        gpl: reg?.gpl ?? false,
        sameAs: reg?.name ?? null,
      });
    } else if (REAL_FORMATS.some((re) => re.test(f))) {
      const reg = registryEntry(f);
      const twin = reg ? readJson(path.join(folder, `${reg.name}.json`)) : null;
      const format = /\.nii/i.test(f) ? 'nifti' : 'nrrd';
      out.push({
        id: f.replace(/\.(nii\.gz|nii|nrrd|nhdr)$/i, '') + `-${format}`,
        url: `${urlPrefix}${f}`,
        format,
        bundled,
        title: reg?.original?.galleryTitle ?? `${twin?.title ?? f} — original ${format.toUpperCase()} file`,
        modality: twin?.modality ?? '',
        dims: twin?.dims ?? null,
        type: twin?.voxel_type ?? null,
        spacing: twin?.spacing ?? null,
        valueRange: twin?.value_range ?? null,
        bytes: fs.statSync(file).size,
        license: twin?.license ?? reg?.license ?? '',
        gpl: reg?.gpl ?? false,
        sameAs: reg?.name ?? null,
      });
    }
  }
  return out;
}

// Bundled volumes are small: copy them (the site then works wherever dist/ is copied).
for (const f of fs.readdirSync(dataDir)) {
  if (/\.(json|raw)$/.test(f) && f !== 'datasets.json')
    fs.copyFileSync(path.join(dataDir, f), path.join(dist, 'data', f));
}
const bundled = scan(dataDir, 'data/', true);
const fetchedDir = path.join(dataDir, 'fetched');
// A fetched copy of a bundled volume is listed once, as the bundled one.
const fetched = scan(fetchedDir, 'data/fetched/', false).filter((d) => !bundled.some((b) => b.id === d.id));
if (fetched.length)
  fs.symlinkSync(path.relative(path.join(dist, 'data'), fetchedDir), path.join(dist, 'data', 'fetched'), 'dir');

/**
 * A label volume's image shown with it: a second entry of the image (same src, its view and
 * presets through sameAs) whose `labels` is the label volume's URL, listed right after the image.
 */
function withLabels(datasets) {
  const out = [];
  for (const d of datasets) {
    out.push(d);
    for (const l of labelSidecars.filter((x) => x.of === d.id))
      out.push({
        ...d,
        id: `${d.id}-labels`,
        title: l.meta.gallery_title ?? `${d.title} with its segmentation`,
        labels: l.url,
        labelNames: l.meta.labels ?? [],
        // A segmentation lies inside the body, where EAM's and MCRT's fitted functions hide it
        // behind soft tissue: MIP draws its colour over the image.
        renderer: 'mip',
        bytes: (d.bytes ?? 0) + l.bytes,
        sameAs: d.id,
      });
  }
  return out;
}

const development = !production;
const manifest = {
  generated: new Date().toISOString(),
  development,
  datasets: withLabels([...bundled, ...fetched]),
};
fs.writeFileSync(path.join(dist, 'data', 'manifest.json'), JSON.stringify(manifest, null, 1));
console.log(
  `gallery: ${path.relative(root, dist)}/ with ${bundled.length} bundled and ${fetched.length} fetched datasets${fetched.length ? '' : ' (run `pnpm data:fetch` for more)'}`,
);
