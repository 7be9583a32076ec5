/** What the suites run: scenes, renderer configurations (and MCRT variants), presets. */

export type Backend = 'webgl2' | 'webgpu';

export interface RendererConfig {
  label: string;
  /** A renderer of core's RENDERER_CATALOG. */
  renderer: string;
  params?: Record<string, unknown>;
  /** Supports RenderContext.estimateError() (two half-accumulations). */
  halves?: boolean;
  /**
   * Label of the configuration whose converged image is this one's reference: unbiased
   * variants of one estimator (tested to agree in tests/mcrt-unbiased.test.ts) share it.
   */
  referenceGroup?: string;
}

export interface SceneSpec {
  volume:
    | { kind: 'cloud' | 'head' | 'sphere' | 'blob' | 'cube' | 'ball' | 'anchor'; size?: number; radius?: number }
    /** A raw volume served by the headless server (a fetched dataset), described by its sidecar. */
    | { kind: 'raw'; url: string; dims: number[]; type: string; valueRange?: number[]; spacing: number[] };
  transferFunction: unknown;
  camera: { position: number[]; target: number[]; up: number[]; fovy: number };
  lights?: unknown[];
  environment?: unknown;
  densityScale: number;
  seed?: number;
}

const TF_CLOUD = {
  dimensions: '1d',
  points: [
    { value: 0, color: [0.9, 0.9, 0.9], opacity: 0 },
    { value: 0.2, color: [0.95, 0.8, 0.7], opacity: 0.3 },
    { value: 1, color: [1, 1, 1], opacity: 1 },
  ],
};
const TF_HEAD = {
  dimensions: '1d',
  points: [
    { value: 0.0, color: [0, 0, 0], opacity: 0 },
    { value: 0.15, color: [0.5, 0.2, 0.1], opacity: 0 },
    { value: 0.3, color: [0.9, 0.5, 0.35], opacity: 0.02 },
    { value: 0.5, color: [1.0, 0.85, 0.7], opacity: 0.08 },
    { value: 0.7, color: [2.0, 1.9, 1.8], opacity: 0.5 },
    { value: 1.0, color: [3, 3, 3], opacity: 1 },
  ],
};

/** The procedural 128³ scene (fixed seed) and the bundled MRI head. */
export function scenes(cloudSize: number): Record<string, SceneSpec> {
  return {
    cloud: {
      volume: { kind: 'cloud', size: cloudSize },
      transferFunction: TF_CLOUD,
      camera: { position: [1.1, 0.6, 1.5], target: [0, 0, 0], up: [0, 1, 0], fovy: 0.75 },
      lights: [{ type: 'directional', direction: [0.5, 1, 0.3], irradiance: [3, 3, 3] }],
      environment: { type: 'constant', radiance: [0.4, 0.5, 0.7] },
      densityScale: 60,
    },
    head: {
      volume: { kind: 'head' },
      transferFunction: TF_HEAD,
      camera: { position: [-1.6, -0.35, 0.55], target: [0, 0, 0], up: [0, -1, 0], fovy: 0.75 },
      lights: [{ type: 'directional', direction: [-1, -1, 0.5], irradiance: [3, 3, 3] }],
      environment: { type: 'constant', radiance: [0.3, 0.3, 0.35] },
      densityScale: 80,
    },
  };
}

/**
 * The extra scenes of the estimator study (preset 'estimators'): the cloud under the sky
 * alone, and under a lat-long map with a small bright sun (the lighting MIS exists for).
 */
export function estimatorScenes(cloudSize: number): Record<string, SceneSpec> {
  const cloud = scenes(cloudSize).cloud;
  const W = 64,
    H = 32;
  const data: number[] = [];
  for (let j = 0; j < H; j++)
    for (let i = 0; i < W; i++) {
      // A bluish sky brighter toward the zenith, and a 2 × 2-texel sun of radiance 400 at 35° from it.
      const sun = (j === 6 || j === 7) && (i === 20 || i === 21);
      const sky = 0.15 + 0.35 * Math.cos((Math.PI * (j + 0.5)) / H) ** 2;
      data.push(...(sun ? [400, 380, 350] : [0.8 * sky, 0.9 * sky, 1.2 * sky]));
    }
  return {
    'cloud-sky': { ...cloud, lights: [] },
    'cloud-sun-map': { ...cloud, lights: [], environment: { type: 'latlong', width: W, height: H, data } },
  };
}

/** Normalized value of a CT number in the chest CT's value range [-1024, 1671]. */
const hu = (h: number) => (h + 1024) / 2695;

/**
 * Fetched real volumes the error suite adds when `pnpm data:fetch` has put them in
 * data/fetched/ (run.ts checks; absent ones are listed as skipped). Sidecar = the JSON
 * next to the raw file; the scene around it is set here.
 */
export const FETCHED_SCENES: Record<string, { sidecar: string; scene: Omit<SceneSpec, 'volume'> }> = {
  'ct-chest': {
    sidecar: 'ct_chest_pyradiomics_lung2_512x512x61_int16.json',
    scene: {
      transferFunction: {
        dimensions: '1d',
        points: [
          { value: hu(-400), color: [0.8, 0.5, 0.4], opacity: 0 },
          { value: hu(-50), color: [0.85, 0.45, 0.35], opacity: 0.005 },
          { value: hu(100), color: [0.9, 0.6, 0.5], opacity: 0.01 },
          { value: hu(250), color: [1, 0.95, 0.85], opacity: 0.3 },
          { value: 1, color: [1, 1, 1], opacity: 1 },
        ],
      },
      // LPS: anterior is −y, superior +z.
      camera: { position: [0.4, -1.7, 0.5], target: [0, 0, 0], up: [0, 0, 1], fovy: 0.75 },
      lights: [{ type: 'directional', direction: [0.3, -1, 0.6], irradiance: [3, 3, 3] }],
      environment: { type: 'constant', radiance: [0.3, 0.3, 0.35] },
      densityScale: 60,
    },
  },
};

/**
 * Renderer configurations. MCRT variants compare tracking estimators, the majorant grid,
 * MIS and scattering order; parameter names follow @vpt/renderer-mcrt's McrtParams.
 */
export const RENDERERS: RendererConfig[] = [
  { label: 'mip', renderer: 'mip' },
  { label: 'eam', renderer: 'eam' },
  { label: 'iso', renderer: 'iso' },
  { label: 'mcrt single', renderer: 'mcrt', params: { scattering: 'single' }, halves: true },
  { label: 'mcrt multiple', renderer: 'mcrt', params: { scattering: 'multiple' }, halves: true },
];

export const MCRT_VARIANTS: RendererConfig[] = [
  {
    label: 'mcrt delta tracking, global majorant',
    renderer: 'mcrt',
    params: { scattering: 'multiple', tracking: 'delta', majorantGrid: false },
    halves: true,
    referenceGroup: 'mcrt multiple',
  },
  {
    label: 'mcrt delta tracking, majorant grid',
    renderer: 'mcrt',
    params: { scattering: 'multiple', tracking: 'delta', majorantGrid: true },
    halves: true,
    referenceGroup: 'mcrt multiple',
  },
  {
    label: 'mcrt ratio tracking, majorant grid',
    renderer: 'mcrt',
    params: { scattering: 'multiple', tracking: 'ratio', majorantGrid: true },
    halves: true,
    referenceGroup: 'mcrt multiple',
  },
  {
    label: 'mcrt residual ratio tracking, majorant grid',
    renderer: 'mcrt',
    params: { scattering: 'multiple', tracking: 'residual', majorantGrid: true },
    halves: true,
    referenceGroup: 'mcrt multiple',
  },
  {
    label: 'mcrt residual ratio, phase sampling only (no MIS)',
    renderer: 'mcrt',
    params: { scattering: 'multiple', tracking: 'residual', majorantGrid: true, environmentSampling: 'phase' },
    halves: true,
    referenceGroup: 'mcrt multiple',
  },
];

/**
 * Fixed MCRT estimators the default `estimator: 'auto'` is measured against (preset
 * 'estimators'): every shadow tracking with both environment strategies over the majorant
 * grid, and delta and ratio tracking with one global majorant. Multiple scattering, as the default.
 */
export const ESTIMATOR_VARIANTS: RendererConfig[] = [
  ...(['delta', 'ratio', 'residual'] as const).flatMap((tracking) =>
    (['phase', 'mis'] as const).map((environmentSampling) => ({
      label: `mcrt fixed: ${tracking}, ${environmentSampling}, grid`,
      renderer: 'mcrt',
      params: { scattering: 'multiple', estimator: 'fixed', tracking, environmentSampling, majorantGrid: true },
      halves: true,
      referenceGroup: 'mcrt multiple',
    })),
  ),
  ...(['delta', 'ratio'] as const).flatMap((tracking) =>
    (['phase', 'mis'] as const).map((environmentSampling) => ({
      label: `mcrt fixed: ${tracking}, ${environmentSampling}, global majorant`,
      renderer: 'mcrt',
      params: { scattering: 'multiple', estimator: 'fixed', tracking, environmentSampling, majorantGrid: false },
      halves: true,
      referenceGroup: 'mcrt multiple',
    })),
  ),
];

export interface Preset {
  name: string;
  /**
   * The estimator study: the MCRT variants are ESTIMATOR_VARIANTS and run on every error
   * scene (with estimatorScenes added), against 'mcrt multiple' (the default, 'auto').
   */
  estimatorStudy?: boolean;
  /** Only these renderer configurations (by label) besides the variants. */
  rendererLabels?: string[];
  /**
   * Estimator study's cost side: rounds of the round-robin (order reversed every other
   * round: A B C, C B A, …) and iterations per synchronised batch (defaults 5 and 2).
   */
  costRounds?: number;
  costBatch?: number;
  /** Seed of the error curves (default: the scene's, 1); the references keep their own. Another seed = an independent run. */
  curveSeed?: number;
  errorSize: number;
  referenceIterations: Record<string, number>;
  curveIterations: number;
  curveBudgetMs: number;
  frameSizes: number[];
  frameVolumeSizes: number[];
  frameSizeAtVolume: number;
  frameIterations: number;
  frameRepeats: number;
  convergenceSizes: number[];
  cloudSize: number;
  scalingVolumeSizes: number[];
  scalingEmptyFractions: number[];
  /** Framebuffer side of the scaling suite (default 128). */
  scalingFramebuffer?: number;
  /** Framebuffer side of the specialization suite (MCRT specialised vs generic kernel). */
  specializationSize: number;
  /** Scenes of the error-vs-time suite (default: all). */
  errorScenes?: string[];
  /** Framebuffer side of the compact suite's fast-vs-exact frame times. */
  compactSize: number;
  /** Depths N of the synthetic 512 x 512 x N int16 CT whose load time and JS heap the compact suite measures. */
  ctDepths: number[];
}

export const PRESETS: Record<string, Preset> = {
  /** Seconds, not minutes: exercised by the test suite to keep the harness working. */
  smoke: {
    name: 'smoke',
    specializationSize: 16,
    errorSize: 16,
    referenceIterations: { mip: 16, eam: 16, iso: 16, mcrt: 32 },
    curveIterations: 8,
    curveBudgetMs: 5_000,
    frameSizes: [16],
    frameVolumeSizes: [16],
    frameSizeAtVolume: 16,
    frameIterations: 1,
    frameRepeats: 2,
    convergenceSizes: [16],
    cloudSize: 16,
    scalingVolumeSizes: [16],
    scalingEmptyFractions: [0, 0.9],
    scalingFramebuffer: 16,
    compactSize: 16,
    ctDepths: [4],
  },
  /** Only the frame-time table at 256² and 512² on the 128³ cloud (docs/benchmarks.md, "Frame time"). */
  table: {
    name: 'table',
    specializationSize: 64,
    errorSize: 64,
    referenceIterations: { mip: 64, eam: 64, iso: 64, mcrt: 128 },
    curveIterations: 32,
    curveBudgetMs: 20_000,
    frameSizes: [256, 512],
    frameVolumeSizes: [],
    frameSizeAtVolume: 256,
    frameIterations: 2,
    frameRepeats: 3,
    convergenceSizes: [64],
    cloudSize: 128,
    scalingVolumeSizes: [64],
    scalingEmptyFractions: [0],
    compactSize: 256,
    ctDepths: [64],
  },
  /**
   * MCRT's time to 30/35 dB at 256² on the 128³ cloud (docs/benchmarks.md, "MCRT: time to 30 and 35 dB")
   * (`--suites error --renderers "mcrt single,mcrt multiple"`).
   */
  mcrt256: {
    name: 'mcrt256',
    specializationSize: 256,
    errorSize: 256,
    referenceIterations: { mip: 256, eam: 256, iso: 256, mcrt: 256 },
    curveIterations: 256,
    curveBudgetMs: 360_000,
    frameSizes: [256],
    frameVolumeSizes: [],
    frameSizeAtVolume: 256,
    frameIterations: 2,
    frameRepeats: 3,
    convergenceSizes: [256],
    cloudSize: 128,
    scalingVolumeSizes: [128],
    scalingEmptyFractions: [0],
    errorScenes: ['cloud'],
    compactSize: 256,
    ctDepths: [64],
  },
  /** `estimator: 'auto'` against every fixed estimator (docs/benchmarks.md, "MCRT: estimator 'auto'"): time to 30/35 dB at 64² on five scenes. */
  estimators: {
    name: 'estimators',
    estimatorStudy: true,
    rendererLabels: ['mcrt multiple'],
    costRounds: 16,
    costBatch: 2,
    errorScenes: ['cloud-sky', 'cloud', 'cloud-sun-map', 'head', 'ct-chest'],
    specializationSize: 64,
    errorSize: 64,
    referenceIterations: { mip: 64, eam: 64, iso: 64, mcrt: 384 },
    curveIterations: 192,
    curveBudgetMs: 20_000,
    frameSizes: [64],
    frameVolumeSizes: [],
    frameSizeAtVolume: 64,
    frameIterations: 1,
    frameRepeats: 3,
    convergenceSizes: [64],
    cloudSize: 128,
    scalingVolumeSizes: [64],
    scalingEmptyFractions: [0],
    compactSize: 64,
    ctDepths: [64],
  },
  quick: {
    name: 'quick',
    specializationSize: 96,
    errorSize: 64,
    referenceIterations: { mip: 128, eam: 128, iso: 256, mcrt: 384 },
    curveIterations: 128,
    curveBudgetMs: 15_000,
    frameSizes: [64, 128, 256, 512],
    frameVolumeSizes: [64, 128, 256],
    frameSizeAtVolume: 128,
    frameIterations: 1,
    frameRepeats: 3,
    convergenceSizes: [64, 128],
    cloudSize: 128,
    scalingVolumeSizes: [32, 64, 128],
    scalingEmptyFractions: [0, 0.5, 0.9],
    compactSize: 256,
    ctDepths: [64, 256, 1024],
  },
  full: {
    name: 'full',
    specializationSize: 256,
    errorSize: 256,
    referenceIterations: { mip: 512, eam: 512, iso: 1024, mcrt: 4096 },
    curveIterations: 1024,
    curveBudgetMs: 300_000,
    frameSizes: [64, 128, 256, 512],
    frameVolumeSizes: [64, 128, 256],
    frameSizeAtVolume: 512,
    frameIterations: 4,
    frameRepeats: 5,
    convergenceSizes: [256, 512, 1024],
    cloudSize: 128,
    scalingVolumeSizes: [32, 64, 128, 256],
    scalingEmptyFractions: [0, 0.25, 0.5, 0.75, 0.9],
    compactSize: 256,
    ctDepths: [64, 256, 1024],
  },
};
