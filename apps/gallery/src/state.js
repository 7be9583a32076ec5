// Deep-linkable gallery state in the page's query string:
//   ?dataset=<id>&renderer=<mip|iso|eam|mcrt>&tf=<preset name | JSON>&camera=<10 numbers>
//    &exposure=<stops>&tone=<operator>&density=<scale>&backend=<auto|webgl2|webgpu>&scale=<0.25…2>&max=<samples>
//    &clip=<the clip attribute's JSON>
// camera = position x,y,z, target x,y,z, up x,y,z, fovy (radians).
import { TRANSFER_FUNCTION_PRESETS } from './vpt-viewer.bundle.js';

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
    tone: q.get('tone') ?? undefined,
    density: num('density'),
    backend: q.get('backend') ?? undefined,
    scale: num('scale'),
    max: num('max'),
    clip: q.get('clip') ?? undefined,
  };
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
