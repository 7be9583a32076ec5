/**
 * Random mutations of valid scene descriptions for the fuzz tests: wrong types, extremes
 * (float32 overflow, huge and fractional integers, zero, negative), missing and unknown
 * fields, resized arrays. Seeded (mulberry32), so a failing case is reproduced by its seed.
 */

export type Json = null | boolean | number | string | Json[] | { [k: string]: Json };

export { seededRandom } from './seeded-random.js';

/** Values that break a number: float32 overflow, just-finite float32, tiny, zero, negative, huge integers, fractions. */
export const EXTREME_NUMBERS = [
  1e39,
  -1e39,
  3e38,
  3.4028234663852886e38,
  1e308,
  -1e308,
  1e-45,
  1e-9,
  0,
  -0,
  -1,
  -1e-9,
  0.5,
  1.5,
  2 ** 31,
  2 ** 53,
  100000,
  65536,
  8193,
  1e18,
  1e19,
];
const WRONG_TYPES: Json[] = [null, true, false, 'x', '1', '', [], {}, [1, 2], { a: 1 }, 'middle', 'NaN'];
const WORDS = [
  'eam',
  'mip',
  'mcrt',
  'iso',
  'slice',
  'auto',
  'webgl2',
  'webgpu',
  'constant',
  'latlong',
  'directional',
  '1d',
  '2d',
  'sphere',
  'cube',
  'little',
  'big',
  'middle',
  'uint8',
  'float64',
  'gaussian',
  'box',
  'srgb',
  'tonemap',
  'exposure',
  'aces',
  'none',
];
const UNKNOWN_KEYS = ['foo', 'stepsize', 'Width', '__proto__x', 'constructor', 'radiance2', 'extra'];

type Path = (string | number)[];

/** Every path to a value in the tree (the root excluded). */
function paths(v: Json, prefix: Path = [], out: Path[] = []): Path[] {
  if (Array.isArray(v))
    v.forEach((x, i) => {
      out.push([...prefix, i]);
      paths(x, [...prefix, i], out);
    });
  else if (v && typeof v === 'object')
    for (const k of Object.keys(v)) {
      out.push([...prefix, k]);
      paths(v[k], [...prefix, k], out);
    }
  return out;
}

function parentOf(root: Json, path: Path): Json {
  let v = root;
  for (const k of path.slice(0, -1)) v = (v as Record<string | number, Json>)[k];
  return v;
}

const pick = <T>(rnd: () => number, xs: readonly T[]): T => xs[Math.floor(rnd() * xs.length)];

/** One mutation in place; returns what it did, for the failure message. */
function mutateOnce(root: Record<string, Json>, rnd: () => number): string {
  const all = paths(root);
  const objects = [
    [] as Path,
    ...all.filter((p) => {
      const v = parentOf(root, [...p, 0]);
      return v !== null && typeof v === 'object' && !Array.isArray(v);
    }),
  ];
  const r = rnd();
  if (r < 0.12 || all.length === 0) {
    const where = pick(rnd, objects);
    const obj = (where.length ? parentOf(root, [...where, 0]) : root) as Record<string, Json>;
    const key = pick(rnd, UNKNOWN_KEYS);
    obj[key] = pick(rnd, [1, 'x', null, [1]]);
    return `add ${[...where, key].join('.')}`;
  }
  const path = pick(rnd, all);
  const parent = parentOf(root, path) as Record<string | number, Json>;
  const key = path[path.length - 1];
  const old = parent[key];
  if (r < 0.25) {
    if (Array.isArray(parent)) parent.splice(key as number, 1);
    else delete parent[key];
    return `delete ${path.join('.')}`;
  }
  if (typeof old === 'number' && r < 0.5) {
    // An ordinary edit (within a factor of 4): mostly valid, exercising what renders.
    const v = old * (0.25 + 3.75 * rnd());
    parent[key] = v;
    return `${path.join('.')}: ${old} -> ${v}`;
  }
  if (typeof old === 'number' && r < 0.75) {
    const v = rnd() < 0.6 ? pick(rnd, EXTREME_NUMBERS) : old * pick(rnd, [1e39, -1, 1e20, 1e-20, 1.5, 1000]);
    parent[key] = v;
    return `${path.join('.')}: ${old} -> ${v}`;
  }
  if (typeof old === 'string' && r < 0.6) {
    parent[key] = pick(rnd, WORDS);
    return `${path.join('.')}: ${old} -> ${parent[key] as string}`;
  }
  if (Array.isArray(old) && r < 0.6) {
    if (rnd() < 0.5) old.pop();
    else old.push(pick(rnd, [0, 1, 1e39, 'x']));
    return `resize ${path.join('.')}`;
  }
  // A fresh copy: a shared object placed twice could be mutated into a cycle.
  parent[key] = structuredClone(pick(rnd, [...WRONG_TYPES, pick(rnd, EXTREME_NUMBERS)]));
  return `${path.join('.')} -> ${JSON.stringify(parent[key])}`;
}

/** A mutated copy of `base` (1–3 mutations) and their descriptions. */
export function mutateScene(
  base: Record<string, Json>,
  rnd: () => number,
): { scene: Record<string, Json>; mutations: string[] } {
  const scene = JSON.parse(JSON.stringify(base)) as Record<string, Json>;
  const n = 1 + Math.floor(rnd() * 3);
  const mutations: string[] = [];
  for (let i = 0; i < n; i++) mutations.push(mutateOnce(scene, rnd));
  return { scene, mutations };
}

const TF = {
  dimensions: '1d',
  points: [
    { value: 0, color: [1, 0.5, 0.2], opacity: 0 },
    { value: 1, color: [1, 1, 1], opacity: 1 },
  ],
};
const CAMERA = { position: [0, 0.5, 2], target: [0, 0, 0], up: [0, 1, 0], fovy: 0.7 };

/** Valid scenes that cover every renderer and every volume/environment kind (small, so renders are cheap). */
export const BASE_SCENES: Record<string, Json>[] = [
  {
    width: 8,
    height: 8,
    iterations: 2,
    renderer: 'eam',
    rendererParams: { stepSize: 0.05, cutoff: 1e-6 },
    volume: { procedural: 'blob', size: 16 },
    transferFunction: TF,
    camera: CAMERA,
    environment: { type: 'constant', radiance: [1, 1, 1] },
    densityScale: 8,
    seed: 3,
  },
  {
    width: 8,
    height: 8,
    iterations: 2,
    renderer: 'mip',
    rendererParams: { stepSize: 0.05 },
    volume: { procedural: 'sphere', size: 16 },
    camera: CAMERA,
  },
  {
    width: 8,
    height: 8,
    iterations: 2,
    renderer: 'iso',
    rendererParams: {
      surfaces: [{ value: 0.5, color: [1, 0.8, 0.6], opacity: 0.8 }],
      specular: 0.2,
      shininess: 20,
      lightAngularRadius: 0.1,
    },
    volume: { procedural: 'blob', size: 16 },
    camera: CAMERA,
    lights: [{ type: 'directional', direction: [1, 1, 1], irradiance: [2, 2, 2] }],
    environment: {
      type: 'latlong',
      width: 4,
      height: 2,
      data: [1, 1, 1, 2, 2, 2, 1, 1, 1, 0, 0, 0, 1, 1, 1, 3, 3, 3, 1, 1, 1, 0.5, 0.5, 0.5],
      scale: 1,
    },
  },
  {
    width: 8,
    height: 8,
    iterations: 2,
    renderer: 'mcrt',
    rendererParams: {
      scattering: 'multiple',
      maxDepth: 4,
      anisotropy: 0.3,
      tracking: 'residual',
      environmentSampling: 'mis',
      majorantCellSize: 4,
    },
    volume: { procedural: 'cube', size: 8 },
    transferFunction: TF,
    camera: CAMERA,
    lights: [{ type: 'directional', direction: [0, 1, 0], irradiance: [3, 3, 3] }],
    environment: { type: 'constant', radiance: [0.5, 0.5, 0.5] },
    densityScale: 5,
    seed: 1,
    post: [{ type: 'exposure', exposure: 0.5 }, { type: 'tonemap', operator: 'aces' }, { type: 'srgb' }],
  },
  {
    width: 8,
    height: 8,
    iterations: 2,
    renderer: 'eam',
    volume: { procedural: 'ramp', size: 8 },
    transferFunction: {
      dimensions: '2d',
      widgets: [
        { type: 'gaussian', center: [0.5, 0.2], width: [0.1, 0.1], color: [1, 1, 1], opacity: 2 },
        { type: 'box', min: [0.2, 0], max: [0.8, 1], ramp: [0.05, 0], color: [0.2, 0.4, 1], opacity: 1 },
      ],
    },
    camera: CAMERA,
    densityScale: 4,
  },
  {
    width: 8,
    height: 8,
    iterations: 2,
    renderer: 'slice',
    rendererParams: {
      normal: [0.2, 1, 0.3],
      point: [0, 0.1, 0],
      sampling: 'linear',
      window: [0.5, 0.8],
      colormap: 'viridis',
    },
    volume: { procedural: 'blob', size: 16 },
    camera: CAMERA,
  },
];
