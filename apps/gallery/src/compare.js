// Renderers side by side: one <vpt-viewer> per renderer on the same dataset, with one
// camera — drag any view and the others follow. ?dataset=<id>&camera=<10 numbers>
// (and the page settings backend, scale, max) deep-link it.
import './vpt-viewer.bundle.js';
import { loadCatalog, presetFor, RENDERERS } from './catalog.js';
import { encodeCamera, linkProblems, readState, showLinkProblems, wireCopyLink } from './state.js';

const $ = (id) => document.getElementById(id);
const page = readState();
const catalog = await loadCatalog();
const grid = $('grid');
const views = RENDERERS.map((r) => {
  const figure = document.createElement('figure');
  const el = document.createElement('vpt-viewer');
  el.panels = 'none';
  el.hideStats = true; // the caption below reads the same numbers
  el.renderer = r.name;
  if (page.backend) el.backend = page.backend;
  if (page.scale) el.resolutionScale = page.scale;
  el.maxSamples = page.max ?? 256;
  const caption = document.createElement('figcaption');
  const name = document.createElement('strong');
  name.textContent = r.label;
  const stats = document.createElement('span');
  stats.className = 'stats';
  caption.append(name, ' ', stats);
  el.addEventListener('vpt-progress', (e) => {
    if (e.detail.phase === 'refining')
      stats.textContent = `${e.detail.samples} spp · ${e.detail.msPerIteration.toFixed(1)} ms/it${e.detail.error != null ? ` · err ${(e.detail.error * 100).toFixed(1)} %` : ''}`;
  });
  figure.append(el, caption);
  grid.append(figure);
  return { renderer: r.name, el };
});

const select = $('dataset');
for (const d of catalog) select.add(new Option(d.title, d.id));
let current = null;
let syncing = false;

// One camera for all: a user's move in one view is copied to the others.
for (const v of views) {
  v.el.addEventListener('vpt-change', (e) => {
    if (e.detail.property !== 'camera' || syncing) return;
    syncing = true;
    for (const o of views) if (o !== v) o.el.camera = v.el.camera;
    syncing = false;
    clearTimeout(updateUrl.timer);
    updateUrl.timer = setTimeout(updateUrl, 250);
  });
}

function updateUrl() {
  if (!current) return;
  const q = new URLSearchParams({ dataset: current.id });
  const cam = views[0].el.camera;
  if (cam && typeof cam === 'object') q.set('camera', encodeCamera(cam));
  for (const k of ['backend', 'scale', 'max']) if (page[k] !== undefined) q.set(k, String(page[k]));
  history.replaceState(null, '', `?${q}`);
  $('gallery-link').href = `index.html?${q}`;
}

async function show(id, camera) {
  const d = catalog.find((x) => x.id === id) ?? catalog[0];
  current = d;
  select.value = d.id;
  await Promise.all(
    views.map(async (v) => {
      if (v.el.src !== d.url || !v.el.loadedVolume) {
        const done = new Promise((r) => {
          v.el.addEventListener('vpt-load', r, { once: true });
          v.el.addEventListener('vpt-error', r, { once: true });
        });
        v.el.src = d.url;
        await done;
      }
      if (!v.el.loadedVolume) return;
      const preset = await presetFor(d, v.renderer, v.el.loadedVolume);
      Object.assign(v.el, preset, { renderer: v.renderer }, camera ? { camera } : {});
    }),
  );
  // Every view takes the first one's camera (presets of one dataset agree, but a link's wins).
  const cam = camera ?? views[0].el.camera;
  for (const v of views) v.el.camera = cam;
  await Promise.all(views.map((v) => v.el.updateComplete));
  updateUrl();
}

select.addEventListener('change', () => show(select.value));
wireCopyLink(updateUrl);

window.compare = {
  views: views.map((v) => v.el),
  catalog,
  get current() {
    return current;
  },
  show,
};
const first =
  catalog.find((d) => d.id === page.dataset) ?? catalog.find((d) => d.bundled && d.format === 'raw') ?? catalog[0];
showLinkProblems(linkProblems(location.search, catalog, RENDERERS, { dataset: first }));
await show(first.id, page.camera);
window.__compareReady = true;
