// The demo: one RenderContext refining progressively on a canvas, Three.js
// OrbitControls for the camera (outside the hot path), and a live stats readout.
import { RenderContext, createVolume, createProceduralVolume, isVptError } from '@vpt/core';
import { EamRenderer } from '@vpt/renderer-eam';
import { MipRenderer } from '@vpt/renderer-mip';
import { postChainFromJSON } from '@vpt/post';
import { PerspectiveCamera, Vector3 } from 'three';
import { OrbitControls } from 'three/addons/controls/OrbitControls.js';
import { DATASETS } from './datasets.js';

const $ = (id) => document.getElementById(id);
const canvas = $('canvas');
const ui = { dataset: $('dataset'), renderer: $('renderer'), backend: $('backend'), density: $('density'), exposure: $('exposure'), tonemap: $('tonemap'), resolution: $('resolution'), stats: $('stats'), message: $('message') };
for (const d of DATASETS) ui.dataset.add(new Option(d.title, d.id));

// Deep-linkable state: ?dataset=head&renderer=eam&backend=auto
const params = new URLSearchParams(location.search);
for (const key of ['dataset', 'renderer', 'backend', 'tonemap']) if (params.has(key)) ui[key].value = params.get(key);

let ctx = null;
let dataset = null;
let volumeCache = new Map();
const camera3 = new PerspectiveCamera(40, 1, 0.01, 100);
const controls = new OrbitControls(camera3, canvas);
controls.enableDamping = false;

function showError(e) {
  ui.message.textContent = isVptError(e) ? `${e.code}: ${e.message}` : String(e?.message ?? e);
  ui.message.classList.add('visible');
  console.error(e);
}
function clearError() { ui.message.classList.remove('visible'); }

async function loadVolume(d) {
  if (volumeCache.has(d.id)) return volumeCache.get(d.id);
  let volume;
  if (d.procedural) volume = createProceduralVolume(d.procedural, d.size);
  else {
    const res = await fetch(d.raw);
    if (!res.ok) throw new Error(`Could not fetch ${d.raw}: HTTP ${res.status}`);
    const buf = await res.arrayBuffer();
    const C = { uint8: Uint8Array, uint16: Uint16Array, int16: Int16Array, float32: Float32Array }[d.type];
    volume = createVolume(d.dims, d.type, new C(buf), d.spacing);
  }
  volumeCache.set(d.id, volume);
  return volume;
}

function vptCamera() {
  return { position: camera3.position.toArray(), target: controls.target.toArray(), up: camera3.up.toArray(), fovy: (camera3.fov * Math.PI) / 180 };
}

function makeRenderer() {
  return ui.renderer.value === 'mip' ? new MipRenderer() : new EamRenderer();
}
function makePost() {
  return postChainFromJSON([{ type: 'exposure', exposure: Number(ui.exposure.value) }, { type: 'tonemap', operator: ui.tonemap.value }, { type: 'srgb' }]);
}

async function rebuildContext() {
  ctx?.dispose();
  ctx = null;
  const size = Number(ui.resolution.value);
  canvas.width = size; canvas.height = size;
  try {
    ctx = await RenderContext.create({ canvas, backend: ui.backend.value, width: size, height: size, renderer: makeRenderer(), post: makePost() });
    ctx.onStats((s) => {
      ui.stats.value = `${ctx.backend.kind} · ${ctx.renderer.name}\n${s.samplesPerPixel} samples/pixel\n${s.msPerIteration.toFixed(2)} ms/iteration`;
    });
    await selectDataset();
    ctx.start({ maxIterations: 4096 });
    clearError();
  } catch (e) { showError(e); }
}

async function selectDataset() {
  dataset = DATASETS.find((d) => d.id === ui.dataset.value) ?? DATASETS[0];
  const volume = await loadVolume(dataset);
  const c = dataset.camera;
  camera3.position.fromArray(c.position); camera3.up.fromArray(c.up); camera3.fov = (c.fovy * 180) / Math.PI;
  controls.target.fromArray(c.target);
  controls.update();
  ctx.setScene({ volume, transferFunction: dataset.transferFunction, camera: vptCamera(), lights: [], environment: { type: 'constant', radiance: [0.02, 0.02, 0.03] }, densityScale: Number(ui.density.value), seed: 1 });
  if (dataset.densityScale) { ui.density.value = String(dataset.densityScale); ctx.updateScene({ densityScale: dataset.densityScale }); }
}

controls.addEventListener('change', () => { if (ctx?.getScene()) ctx.updateScene({ camera: vptCamera() }); });
ui.density.addEventListener('input', () => ctx?.getScene() && ctx.updateScene({ densityScale: Number(ui.density.value) }));
ui.exposure.addEventListener('input', () => ctx?.setPost(makePost()));
ui.tonemap.addEventListener('change', () => ctx?.setPost(makePost()));
ui.renderer.addEventListener('change', () => { ctx?.setRenderer(makeRenderer()); });
ui.dataset.addEventListener('change', () => ctx && selectDataset().catch(showError));
ui.backend.addEventListener('change', rebuildContext);
ui.resolution.addEventListener('change', () => { const s = Number(ui.resolution.value); canvas.width = s; canvas.height = s; ctx?.setSize(s, s); });

window.vptDemo = { get context() { return ctx; } };
await rebuildContext();
window.__demoReady = true;
