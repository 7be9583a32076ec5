// Deep-linkable gallery state in the page's query string:
//   ?dataset=<id>&renderer=<mip|iso|eam|mcrt>&tf=<preset name | JSON>&camera=<10 numbers>
//    &exposure=<stops>&tone=<operator>&density=<scale>&backend=<auto|webgl2|webgpu>&scale=<0.25…2>&max=<samples>
//    &clip=<the clip attribute's JSON>
// camera = position x,y,z, target x,y,z, up x,y,z, fovy (radians).
import { TRANSFER_FUNCTION_PRESETS, post } from './vpt-viewer.bundle.js';

const round = (x) => Math.round(x * 1e4) / 1e4;

export function encodeCamera(c) {
  return [...c.position, ...c.target, ...c.up, c.fovy].map(round).join(',');
}

export function decodeCamera(s) {
  const n = String(s).split(',').map(Number);
  if (n.length !== 10 || !n.every(Number.isFinite)) return null;
  return { position: n.slice(0, 3), target: n.slice(3, 6), up: n.slice(6, 9), fovy: n[9] };
}

/** A preset's name when the transfer function is exactly that preset, else its JSON. */
export function encodeTransferFunction(tf) {
  const json = JSON.stringify(tf);
  return (
    Object.keys(TRANSFER_FUNCTION_PRESETS).find((k) => JSON.stringify(TRANSFER_FUNCTION_PRESETS[k]) === json) ?? json
  );
}

export function readState(search = location.search) {
  const q = new URLSearchParams(search);
  const num = (k) => (q.has(k) && Number.isFinite(Number(q.get(k))) ? Number(q.get(k)) : undefined);
  return {
    dataset: q.get('dataset') ?? undefined,
    renderer: q.get('renderer') ?? undefined,
    tf: q.get('tf') ?? undefined,
    camera: q.has('camera') ? (decodeCamera(q.get('camera')) ?? undefined) : undefined,
    exposure: num('exposure'),
    tone: q.has('tone') && post.TONE_MAP_OPERATORS.includes(q.get('tone')) ? q.get('tone') : undefined,
    density: num('density'),
    backend: q.has('backend') && BACKENDS.includes(q.get('backend')) ? q.get('backend') : undefined,
    scale: num('scale'),
    max: num('max'),
    clip: q.get('clip') ?? undefined,
  };
}

const BACKENDS = ['auto', 'webgl2', 'webgpu'];

/**
 * What a link asks for that the page cannot show, one sentence each (empty: none), so a bad
 * link says so instead of silently showing the default view. `datasets` and `renderers` are
 * the page's ({id, title} and {name, label}); `fallback` is what the page shows instead.
 */
export function linkProblems(search, datasets, renderers, fallback = {}) {
  const q = new URLSearchParams(search);
  const out = [];
  const dataset = q.get('dataset');
  if (dataset !== null && !datasets.some((d) => d.id === dataset))
    out.push(
      `dataset "${dataset}" is not in this gallery${fallback.dataset ? ` (showing ${fallback.dataset.title})` : ''}`,
    );
  const renderer = q.get('renderer');
  if (renderer !== null && !renderers.some((r) => r.name === renderer))
    out.push(
      `renderer "${renderer}" is not one of ${renderers.map((r) => r.name).join(', ')}${fallback.renderer ? ` (showing ${fallback.renderer})` : ''}`,
    );
  if (q.has('camera') && !decodeCamera(q.get('camera')))
    out.push('camera must be 10 numbers: position, target, up, fovy (the automatic framing is shown)');
  for (const k of ['exposure', 'density', 'scale', 'max'])
    if (q.has(k) && !Number.isFinite(Number(q.get(k)))) out.push(`${k} "${q.get(k)}" is not a number (ignored)`);
  const tone = q.get('tone');
  if (tone !== null && !post.TONE_MAP_OPERATORS.includes(tone))
    out.push(`tone "${tone}" is not one of ${post.TONE_MAP_OPERATORS.join(', ')} (ignored)`);
  const backend = q.get('backend');
  if (backend !== null && !BACKENDS.includes(backend))
    out.push(`backend "${backend}" is not one of ${BACKENDS.join(', ')} (ignored)`);
  return out;
}

/** Show `problems` in the page's #link-error notice (hidden when there are none). */
export function showLinkProblems(problems) {
  const box = document.getElementById('link-error');
  if (!box) return;
  box.hidden = problems.length === 0;
  box.textContent = problems.length ? `This link could not be followed in full: ${problems.join('; ')}.` : '';
}

/** The view's own properties that the link overrides after the preset, as <vpt-viewer> properties. */
export function overridesOf(state) {
  const o = {};
  if (state.tf !== undefined) o.transferFunction = state.tf; // a preset name or JSON: the element parses both
  if (state.camera) o.camera = state.camera;
  if (state.exposure !== undefined) o.exposure = state.exposure;
  if (state.tone !== undefined) o.toneMapper = state.tone;
  if (state.density !== undefined) o.densityScale = state.density;
  if (state.clip !== undefined) o.clip = state.clip; // JSON: the element parses and checks it
  return o;
}

/** Query string for a viewer showing `datasetId`, keeping the page-level settings (backend, scale, max) of `page`. */
export function stateQuery(datasetId, viewer, page = readState()) {
  const q = new URLSearchParams();
  q.set('dataset', datasetId);
  q.set('renderer', viewer.renderer);
  if (viewer.fittedPresetName)
    q.set('tf', viewer.fittedPresetName); // refitted to the volume when the link is opened
  else if (viewer.transferFunction && typeof viewer.transferFunction === 'object')
    q.set('tf', encodeTransferFunction(viewer.transferFunction));
  if (viewer.camera && typeof viewer.camera === 'object') q.set('camera', encodeCamera(viewer.camera));
  q.set('exposure', String(viewer.exposure));
  q.set('tone', viewer.toneMapper);
  q.set('density', String(viewer.densityScale));
  if (viewer.clip && typeof viewer.clip === 'object') q.set('clip', JSON.stringify(viewer.clip));
  for (const k of ['backend', 'scale', 'max']) if (page[k] !== undefined) q.set(k, String(page[k]));
  return `?${q}`;
}

/**
 * The "Copy link" button (#copy-link): bring the URL up to date (`updateUrl`), copy it, and
 * say so in #link-status, or show the link there where the clipboard is not available.
 */
export function wireCopyLink(updateUrl) {
  document.getElementById('copy-link').addEventListener('click', async () => {
    updateUrl();
    const status = document.getElementById('link-status');
    try {
      await navigator.clipboard.writeText(location.href);
      status.value = 'Link copied.';
    } catch {
      status.value = location.href;
    }
  });
}
