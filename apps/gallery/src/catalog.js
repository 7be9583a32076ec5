// The gallery's datasets and the preset each renderer starts from. A preset is the
// set of <vpt-viewer> properties that make a dataset look right with that renderer.
// The bundled MRI head uses the scene files of the headless CLI (scenes/head-*.json),
// so the gallery and `pnpm render` show the same thing; the other datasets get presets
// from their modality and orientation, and an automatic transfer function from the
// histogram where nothing better is known.
// The automatic transfer function, albedo conversion, isovalue and key light are the
// viewer's own defaults (packages/viewer/src/defaults.ts), so the gallery and a bare
// <vpt-viewer src> agree.
import {
  asAlbedo,
  autoTransferFunction,
  core,
  fitCamera,
  isoValueOf,
  keyLight,
  rendererEntries,
} from './vpt-viewer.bundle.js';

// Every renderer the viewer registers (core's catalog), in its order; the gallery's shorter
// names for some, the others under their descriptor's label.
const SHORT_LABELS = { mip: 'MIP', mcrt: 'Path traced' };
export const RENDERERS = rendererEntries().map((e) => ({ name: e.name, label: SHORT_LABELS[e.name] ?? e.label }));
/** The renderer a dataset opens with when neither the link nor the previous choice names one. */
export const DEFAULT_RENDERER = core.DEFAULT_RENDERER_NAME;

const PROCEDURAL = [
  {
    id: 'blob',
    title: 'Gaussian blob (procedural, 64³)',
    url: 'procedural:blob?size=64',
    modality: 'procedural',
    dims: [64, 64, 64],
    type: 'float32',
  },
  {
    id: 'sphere',
    title: 'Sphere (procedural, 64³)',
    url: 'procedural:sphere?size=64',
    modality: 'procedural',
    dims: [64, 64, 64],
    type: 'float32',
  },
  {
    id: 'ramp',
    title: 'Linear ramp along x (procedural, 32³)',
    url: 'procedural:ramp?size=32',
    modality: 'procedural',
    dims: [32, 32, 32],
    type: 'float32',
  },
];

/**
 * A view of the bundled head rather than a dataset of its own: its scene file's clip (one
 * plane) cuts it open with every renderer; it opens with the renderer of that scene file.
 */
const HEAD_CUT = {
  id: 'mri_head_cut',
  title: 'MRI head, cut open (a clip plane)',
  clipScene: 'head-mcrt-clip',
  renderer: 'mcrt',
};

/** The bundled head once more, in the viewer's quad layout: axial, coronal and sagittal slices and the 3D view. */
const HEAD_SLICES = {
  id: 'mri_head_slices',
  title: 'MRI head in slices (axial, coronal, sagittal and 3D)',
  layout: 'quad',
  renderer: 'eam',
};

/** About the build: a development build shows developer hints (`pnpm data:fetch`). */
export const catalogInfo = { development: false };

/** Every dataset: the build's manifest (bundled + fetched files) and the procedural ones. */
export async function loadCatalog() {
  let datasets = [];
  try {
    const res = await fetch('data/manifest.json');
    if (res.ok) {
      const manifest = await res.json();
      datasets = manifest.datasets;
      catalogInfo.development = manifest.development !== false;
    }
  } catch {
    // Without a manifest (not built?) the procedural volumes still work.
  }
  // The bundled head once more, cut open by the clip plane of scenes/head-mcrt-clip.json.
  const head = datasets.find((d) => d.id === HEAD);
  const cut = head ? [{ ...head, ...HEAD_CUT, sameAs: HEAD }] : [];
  const slices = head ? [{ ...head, ...HEAD_SLICES, sameAs: HEAD }] : [];
  return [
    ...datasets,
    ...cut,
    ...slices,
    ...PROCEDURAL.map((d) => ({ ...d, bundled: true, format: 'procedural', license: 'generated in code' })),
  ];
}

// ——— presets ———

const HEAD = 'mri_head_volpack_brainsmall_128x128x84_uint8';

/** How to look at a dataset: the direction the camera sits in and which way is up (from each file's orientation notes). */
const VIEWS = {
  ct_head_invesalius_256x256x108_int16: { dir: [0.45, 1.6, 0.35], up: [0, 0, 1] }, // y toward the face, z up
  ct_chest_pyradiomics_lung2_512x512x61_int16: { dir: [0.45, -1.6, 0.35], up: [0, 0, 1] }, // LPS: anterior is -y
  mri_brain_mni152_2009a_t1_197x233x189_uint8: { dir: [0.9, 1.4, 0.5], up: [0, 0, 1] }, // RAS
  mri_head_colin27_ch2_181x217x181_uint8: { dir: [0.7, 1.5, 0.35], up: [0, 0, 1] },
  mri_head_colin27_ch2better_301x370x316_uint8: { dir: [0.9, 1.4, 0.5], up: [0, 0, 1] },
  mri_brain_nibabel_anatomical_33x41x25_int16: { dir: [0.9, 1.4, 0.5], up: [0, 0, 1] }, // LAS
  mri_brain_dipy_aniso_vox_58x58x24_int16: { dir: [0.9, -1.4, 0.5], up: [0, 0, 1] }, // LPS
  geo_channels_facies_250x250x100_uint8: { dir: [1.2, -1.3, 1.0], up: [0, 0, 1] },
};

/** Normalized value of a CT number for a volume whose value range is [lo, hi]. */
const hu = (h, [lo, hi]) => (h - lo) / (hi - lo);

/** Core's 2D presets, fitted by the viewer to the loaded volume (value range, foreground, gradients). */
function fittedPreset(d) {
  const id = d.sameAs ?? d.id;
  if (d.modality === 'CT') return id.startsWith('ct_chest') ? 'ct-soft-tissue' : 'ct-bone';
  if (/^mri_brain_mni|^mri_head_colin/.test(id)) return 'mri-brain';
  // Fluorescence only: a cryo-EM tomogram is noise-dominated and gets the automatic function.
  if (/fluorescence/i.test(d.modality)) return 'microscopy';
  return null;
}

/** Transfer functions known to work for a dataset without a fitted preset (values normalized by its value_range). */
function tunedTransferFunction(d) {
  if ((d.sameAs ?? d.id).startsWith('geo_')) {
    // Categorical facies 0..4 → 0, 0.25 … 1: the background class clear, each other class its own colour.
    const cls = (v, color, opacity) => [
      { value: v - 0.1, color, opacity },
      { value: v + 0.1, color, opacity },
    ];
    return {
      dimensions: '1d',
      points: [
        { value: 0.12, color: [0, 0, 0], opacity: 0 },
        ...cls(0.25, [0.25, 0.45, 1.2], 0.08),
        ...cls(0.5, [1.3, 1.0, 0.3], 0.5),
        ...cls(0.75, [1.4, 0.45, 0.25], 0.8),
        { value: 0.9, color: [1.8, 1.8, 1.6], opacity: 1 },
        { value: 1, color: [1.8, 1.8, 1.6], opacity: 1 },
      ],
    };
  }
  return null;
}

function paletteOf(d) {
  if (/tomogra|cryo/i.test(d.modality) || d.modality === 'procedural') return 'cool';
  if (/microscopy/i.test(d.modality)) return 'hot';
  return 'warm';
}

/** The camera for a dataset: its view direction and up, at the automatic framing distance. */
function viewCamera(d, volume) {
  const fit = fitCamera(volume, 0.7);
  const view = VIEWS[d.sameAs ?? d.id];
  if (!view) return fit;
  const dist = Math.hypot(...fit.position);
  const len = Math.hypot(...view.dir);
  return {
    position: view.dir.map((x) => Math.round((x / len) * dist * 1e4) / 1e4),
    target: [0, 0, 0],
    up: view.up,
    fovy: 0.7,
  };
}

/** Properties of a scene file (scenes/*.json) as <vpt-viewer> properties. */
function fromSceneFile(s) {
  const p = {
    renderer: s.renderer,
    camera: s.camera,
    environment: s.environment ?? { type: 'constant', radiance: [1, 1, 1] },
    lights: s.lights ?? [],
    densityScale: s.densityScale ?? 10,
    rendererParams: s.rendererParams ?? null,
    exposure: 0,
    toneMapper: 'aces',
    clip: s.clip ?? null,
  };
  if (s.transferFunction) p.transferFunction = { dimensions: '1d', ...s.transferFunction };
  for (const step of s.post ?? []) {
    if (step.type === 'exposure') p.exposure = step.exposure ?? 0;
    if (step.type === 'tonemap') p.toneMapper = step.operator ?? 'aces';
  }
  return p;
}

const sceneFiles = new Map();
async function sceneFile(name) {
  if (!sceneFiles.has(name))
    sceneFiles.set(
      name,
      fetch(`scenes/${name}.json`)
        .then((r) => (r.ok ? r.json() : null))
        .catch(() => null),
    );
  return sceneFiles.get(name);
}

/**
 * The preset of `renderer` for dataset `d` whose volume (for the histogram and the box)
 * is `volume`: an object of <vpt-viewer> properties.
 */
export async function presetFor(d, renderer, volume) {
  // The layout is the dataset's (the head in slices: quad), else the 3D view alone. `labels`:
  // the URL of the dataset's label volume on the src grid (a CT with its segmentation, the
  // build's "-labels" entries), else none, so another dataset does not keep the last one's.
  return { ...(await rendererPreset(d, renderer, volume)), layout: d.layout ?? '3d', labels: d.labels ?? null };
}

async function rendererPreset(d, renderer, volume) {
  if (d.id === HEAD || d.sameAs === HEAD) {
    // The cut-open head: its own scene file for its renderer, the other renderers' scene files plus its clip.
    const cut = d.clipScene ? await sceneFile(d.clipScene) : null;
    const s = cut && renderer === cut.renderer ? cut : await sceneFile(`head-${renderer}`);
    if (s) {
      const p = fromSceneFile(s);
      if (!p.transferFunction) p.transferFunction = fromSceneFile(await sceneFile('head-eam')).transferFunction;
      if (cut) p.clip = cut.clip;
      return p;
    }
  }
  const tf = tunedTransferFunction(d) ?? autoTransferFunction(volume, paletteOf(d));
  const fitted = fittedPreset(d);
  const camera = viewCamera(d, volume);
  const base = {
    renderer,
    camera,
    transferFunction: tf,
    exposure: 0,
    toneMapper: 'aces',
    rendererParams: null,
    lights: [],
    clip: null,
  };
  // CT: bone at 300 HU; otherwise where the automatic function turns a third opaque.
  const iso = d.modality === 'CT' && d.valueRange ? hu(300, d.valueRange) : isoValueOf(tf);
  switch (renderer) {
    case 'mip':
      return { ...base, toneMapper: 'clamp', environment: { type: 'constant', radiance: [0, 0, 0] }, densityScale: 20 };
    case 'iso':
      return {
        ...base,
        environment: { type: 'constant', radiance: [0.25, 0.28, 0.35] },
        densityScale: 20,
        // A multichannel store: the viewer's own defaults, a surface per drawn channel in its colour.
        rendererParams:
          (d.channels ?? 1) > 1
            ? null
            : {
                surfaces: [{ value: Math.round(iso * 1000) / 1000, color: [0.92, 0.88, 0.8], opacity: 1 }],
                specular: 0.15,
                shininess: 30,
              },
        lights: keyLight(camera, [2.2, 2.1, 2.0]),
      };
    case 'mcrt':
      return {
        ...base,
        transferFunction: fitted ?? asAlbedo(tf),
        environment: { type: 'constant', radiance: [0.08, 0.09, 0.12] },
        densityScale: fitted ? 1 : 150,
        rendererParams: { anisotropy: 0.2 },
        lights: keyLight(camera, [4, 3.7, 3.2]),
      };
    default:
      // Core's presets are extinctions for densityScale 1 with albedo-like colours: a stop brighter as emission.
      return {
        ...base,
        transferFunction: fitted ?? tf,
        exposure: fitted ? 1 : 0,
        environment: { type: 'constant', radiance: [0.03, 0.035, 0.05] },
        densityScale: fitted ? 1 : 60,
      };
  }
}
