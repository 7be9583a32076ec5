// The gallery page: a dataset list, a renderer switch and one <vpt-viewer>. The view's
// state (dataset, renderer, transfer function, camera, exposure, tone mapper, density)
// lives in the URL, so any view can be linked to; the link restores it.
import './vpt-viewer.bundle.js';
import { catalogInfo, DEFAULT_RENDERER, loadCatalog, presetFor, RENDERERS } from './catalog.js';
import { linkProblems, overridesOf, readState, showLinkProblems, stateQuery, wireCopyLink } from './state.js';

const $ = (id) => document.getElementById(id);
const viewer = $('viewer');
const page = readState();
if (page.backend) viewer.backend = page.backend;
if (page.scale) viewer.resolutionScale = page.scale;
if (page.max) viewer.maxSamples = page.max;

const catalog = await loadCatalog();
let current = null; // { dataset, renderer }
let token = 0;

function formatBytes(n) {
  return n >= 1 << 20 ? `${(n / (1 << 20)).toFixed(1)} MB` : `${Math.max(1, Math.round(n / 1024))} kB`;
}

function renderDatasetList() {
  const groups = [
    ['Bundled with vpt', catalog.filter((d) => d.bundled && d.format !== 'procedural')],
    [catalogInfo.development ? 'Fetched (pnpm data:fetch)' : 'More datasets', catalog.filter((d) => !d.bundled)],
    ['Procedural', catalog.filter((d) => d.format === 'procedural')],
  ];
  const list = $('dataset-list');
  list.replaceChildren();
  for (const [title, items] of groups) {
    const h = document.createElement('h3');
    h.textContent = title;
    list.append(h);
    if (!items.length) {
      // Site visitors cannot run the fetch: a production build shows no empty group.
      if (!catalogInfo.development) {
        h.remove();
        continue;
      }
      const p = document.createElement('p');
      p.className = 'empty';
      p.textContent = 'None here yet: `pnpm data:fetch` downloads the larger datasets, then rebuild the gallery.';
      list.append(p);
      continue;
    }
    const ul = document.createElement('ul');
    for (const d of items) {
      const li = document.createElement('li');
      const b = document.createElement('button');
      b.type = 'button';
      b.dataset.id = d.id;
      b.setAttribute('aria-pressed', String(current?.dataset.id === d.id));
      const facts = [
        d.dims ? d.dims.join('×') : null,
        d.type,
        d.format !== 'raw' && d.format !== 'procedural' ? d.format.toUpperCase() : null,
        d.bytes ? formatBytes(d.bytes) : null,
      ]
        .filter(Boolean)
        .join(' · ');
      b.innerHTML = '<span class="t"></span><span class="f"></span>';
      b.querySelector('.t').textContent = d.title;
      b.querySelector('.f').textContent = facts + (d.gpl ? ' · GPL' : '');
      b.addEventListener('click', () => select(d.id, d.renderer ?? current?.renderer ?? DEFAULT_RENDERER, {}, true));
      li.append(b);
      ul.append(li);
    }
    list.append(ul);
  }
}

function renderRendererChoice() {
  const box = $('renderer-choice');
  box.replaceChildren();
  for (const r of RENDERERS) {
    const label = document.createElement('label');
    const input = document.createElement('input');
    input.type = 'radio';
    input.name = 'renderer';
    input.value = r.name;
    input.checked = current?.renderer === r.name;
    input.addEventListener('change', () => select(current.dataset.id, r.name, { camera: viewer.camera }, true));
    label.append(input, ` ${r.label}`);
    box.append(label);
  }
}

function describe(d) {
  const about = $('about');
  about.textContent = `${d.title}. ${d.modality ? `${d.modality}. ` : ''}License: ${d.license || 'see data/README.md'}.`;
}

function updateUrl(push = false) {
  if (!current) return;
  const q = stateQuery(current.dataset.id, viewer, page);
  if (q === location.search) return;
  history[push ? 'pushState' : 'replaceState'](null, '', q);
  $('compare-link').href =
    `compare.html?${new URLSearchParams({ dataset: current.dataset.id, ...(viewer.camera ? { camera: new URLSearchParams(q).get('camera') } : {}), ...pageParams() })}`;
}

function pageParams() {
  const o = {};
  for (const k of ['backend', 'scale', 'max']) if (page[k] !== undefined) o[k] = String(page[k]);
  return o;
}

function once(el, types) {
  return new Promise((resolve) => {
    const done = (e) => {
      types.forEach((t) => el.removeEventListener(t, done));
      resolve(e);
    };
    types.forEach((t) => el.addEventListener(t, done));
  });
}

/** Show dataset `id` with `renderer`: load it, apply the renderer's preset, then `overrides` (from a link, or the kept camera). */
async function select(id, renderer, overrides = {}, push = false) {
  const d = catalog.find((x) => x.id === id) ?? catalog[0];
  const mine = ++token;
  current = { dataset: d, renderer };
  renderDatasetList();
  renderRendererChoice();
  describe(d);
  if (viewer.src !== d.url || !viewer.loadedVolume) {
    const loaded = once(viewer, ['vpt-load', 'vpt-error']);
    viewer.src = d.url;
    const e = await loaded;
    if (e.type === 'vpt-error' || mine !== token) return;
  }
  const preset = await presetFor(d, renderer, viewer.loadedVolume);
  if (mine !== token) return;
  Object.assign(viewer, preset, overrides, { renderer });
  // Settled, not just updated: the renderer package (a dynamic import) has landed and
  // renders, so "ready" means the view the link asked for is the one on screen.
  await viewer.whenSettled();
  if (mine !== token) return;
  updateUrl(push);
}

viewer.addEventListener('vpt-change', () => {
  clearTimeout(updateUrl.timer);
  updateUrl.timer = setTimeout(() => updateUrl(false), 250);
});
window.addEventListener('popstate', () => {
  const s = readState();
  select(s.dataset ?? current?.dataset.id, s.renderer ?? DEFAULT_RENDERER, overridesOf(s));
});
wireCopyLink(() => updateUrl(false));

// Test and console access.
window.gallery = {
  viewer,
  catalog,
  get current() {
    return current;
  },
  select,
};

const first =
  catalog.find((d) => d.id === page.dataset) ?? catalog.find((d) => d.bundled && d.format === 'raw') ?? catalog[0];
const firstRenderer = RENDERERS.some((r) => r.name === page.renderer)
  ? page.renderer
  : (first.renderer ?? DEFAULT_RENDERER);
// A link naming what this gallery lacks says so (the default view shows under the notice).
const problems = linkProblems(location.search, catalog, RENDERERS, {
  dataset: first,
  renderer: RENDERERS.find((r) => r.name === firstRenderer)?.label,
});
showLinkProblems(problems);
// A transfer function the viewer refuses is reported there too (the viewer's own banner says why).
viewer.addEventListener(
  'vpt-error',
  (e) => {
    if (e.detail.source === 'attribute' && page.tf !== undefined && !window.__galleryReady)
      showLinkProblems([...problems, `tf: ${e.detail.message}`]);
  },
  { once: true },
);
await select(first.id, firstRenderer, overridesOf(page));
window.__galleryReady = true;
