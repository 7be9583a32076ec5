import os from 'node:os';
import { scenes, type RendererConfig, type SceneSpec } from '../configs.js';
import { median, spread, timeToPsnr, type CurvePoint } from '../metrics.js';
import { referenceKey } from './error-vs-time.js';
import { bench, type SuiteContext } from './types.js';

/** Ray-march steps swept, in voxels of the volume's longest side (the renderers' defaults and around them). */
export const STEPS_VOXELS = [0.25, 0.5, 1, 1.5, 2];
/** The step whose converged image stands for the exact integral: the finest of the sweep. */
const FINE_STEP = Math.min(...STEPS_VOXELS);
const TARGETS_DB = [30, 35, 40];

/** Per preset: framebuffer side of the curves, of the frame times, reference and curve lengths, curve budget. */
const PLAN: Record<
  string,
  { size: number; frameSize: number; refIterations: number; curveIterations: number; budgetMs: number }
> = {
  smoke: { size: 16, frameSize: 16, refIterations: 8, curveIterations: 4, budgetMs: 5_000 },
  table: { size: 64, frameSize: 256, refIterations: 64, curveIterations: 16, budgetMs: 20_000 },
  quick: { size: 128, frameSize: 256, refIterations: 256, curveIterations: 64, budgetMs: 40_000 },
  mcrt256: { size: 256, frameSize: 256, refIterations: 256, curveIterations: 64, budgetMs: 120_000 },
  full: { size: 256, frameSize: 256, refIterations: 1024, curveIterations: 256, budgetMs: 300_000 },
};

/** The VPT anchor scene (docs/benchmarks.md, "Side by side with VPT"): VPT's EAM ramp TF, extinction 100, camera at z = 1.5. */
export const ANCHOR_SCENE: SceneSpec = {
  volume: { kind: 'anchor', size: 128 },
  // VPT's 256-texel ramp (alpha = i/255) as vpt TF points; emission = VPT's albedo after its sRGB8 round trip.
  transferFunction: {
    dimensions: '1d',
    points: [
      { value: 0, color: [1, 0.8469, 0.7011], opacity: 0 },
      { value: 0.5 / 256, color: [1, 0.8469, 0.7011], opacity: 0 },
      { value: 255.5 / 256, color: [1, 0.8469, 0.7011], opacity: 1 },
      { value: 1, color: [1, 0.8469, 0.7011], opacity: 1 },
    ],
  },
  camera: { position: [0, 0, 1.5], target: [0, 0, 0], up: [0, 1, 0], fovy: 1 },
  environment: { type: 'constant', radiance: [0, 0, 0] },
  densityScale: 100,
};

export interface SkipFrameRow {
  scene: string;
  renderer: string;
  backend: string;
  size: number;
  stepVoxels: number;
  skipMs: number;
  plainMs: number;
  /** plain / skipping median ms per iteration, measured alternately (A/B, B/A) in one run: > 1 means skipping is faster. */
  ratio: number;
  skipSpread: { min: number; max: number };
  plainSpread: { min: number; max: number };
}

export interface StepRow {
  scene: string;
  renderer: string;
  backend: string;
  size: number;
  stepVoxels: number;
  /** ms per iteration over the curve against the step's own reference. */
  msPerIteration: number;
  /** Time (ms) and iterations to each PSNR target against the step's own converged image. */
  ownTimeToDb: Record<string, number | null>;
  ownIterationsToDb: Record<string, number | null>;
  /** Time (ms) to each target against the finest step's converged image (the step's bias included). */
  fineTimeToDb: Record<string, number | null>;
  /** PSNR of the step's own converged image against the finest step's: the ceiling its bias sets. */
  ceilingDb: number | null;
  ownPoints: CurvePoint[];
  finePoints: CurvePoint[];
}

export interface SkippingResults {
  loadAverageStart: number[];
  loadAverageEnd: number[];
  size: number;
  frameSize: number;
  refIterations: number;
  frame: SkipFrameRow[];
  steps: StepRow[];
}

/** The scenes of the suite: the VPT anchor and the bundled head (EAM with a TF that leaves air and noise clear). */
function suiteScenes(cloudSize: number): Record<string, SceneSpec> {
  const head = scenes(cloudSize).head;
  return { anchor: ANCHOR_SCENE, head: { ...head, lights: [] } };
}

/** World units of `voxels` voxels of the scene's longest side (the box's longest side is 1). */
function voxelStep(spec: SceneSpec, voxels: number): number {
  const v = spec.volume;
  const longest = v.kind === 'raw' ? Math.max(...v.dims) : v.kind === 'head' ? 128 : (v.size ?? 128);
  return voxels / longest;
}
const iterationsToDb = (points: CurvePoint[], db: number) =>
  timeToPsnr(
    points.map((p) => ({ ...p, ms: p.iterations })),
    db,
  );

/**
 * Empty-space skipping and step control in the ray marches (docs/benchmarks.md, "Empty-space
 * skipping and the ray-march step"): per renderer and
 * scene, ms per iteration with skipping on and off (alternately in one run, at each step),
 * then the step sweep: time to 30/35/40 dB against the step's own converged image and
 * against the finest step's (so a coarse step's bias counts), skipping on.
 */
export async function skipping(s: SuiteContext): Promise<SkippingResults> {
  const plan = PLAN[s.preset.name] ?? PLAN.quick;
  const loadAverageStart = os.loadavg();
  const frame: SkipFrameRow[] = [];
  const steps: StepRow[] = [];
  const marchers = s.renderers.filter((r) => ['eam', 'mip', 'iso'].includes(r.renderer));
  for (const [sceneName, spec] of Object.entries(suiteScenes(s.preset.cloudSize))) {
    if (s.preset.errorScenes && !s.preset.errorScenes.includes(sceneName)) continue;
    for (const backend of s.backends) {
      for (const r of marchers) {
        const config = (stepVoxels: number, skip: boolean): RendererConfig => ({
          ...r,
          label: `${r.label} step ${stepVoxels} vx${skip ? '' : ' plain'}`,
          params: { ...r.params, stepSize: voxelStep(spec, stepVoxels), emptySpaceSkipping: skip },
        });
        for (const stepVoxels of STEPS_VOXELS) {
          s.log(
            `skipping: ${sceneName} ${r.label} ${backend} step ${stepVoxels} vx, skipping on vs off at ${plan.frameSize}²`,
          );
          const samples = { on: [] as number[], off: [] as number[] };
          for (let round = 0; round < 2; round++) {
            for (const skip of round === 0 ? [true, false] : [false, true]) {
              const res = await bench<{ samples: number[] }>(
                s.page,
                'frameTime',
                { ...config(stepVoxels, skip), backend },
                spec,
                plan.frameSize,
                plan.frameSize,
                s.preset.frameIterations,
                s.preset.frameRepeats,
              );
              samples[skip ? 'on' : 'off'].push(...res.samples);
            }
          }
          const on = median(samples.on),
            off = median(samples.off);
          frame.push({
            scene: sceneName,
            renderer: r.label,
            backend,
            size: plan.frameSize,
            stepVoxels,
            skipMs: on,
            plainMs: off,
            ratio: off / on,
            skipSpread: spread(samples.on),
            plainSpread: spread(samples.off),
          });
        }
        // The step sweep, skipping on. References on the first backend serve both (bit-identical images).
        const refKeyOf = (stepVoxels: number) =>
          referenceKey(`skipping-${sceneName}`, config(stepVoxels, true).label, plan.size);
        for (const stepVoxels of [...STEPS_VOXELS].sort((a, b) => a - b)) {
          s.log(
            `skipping: ${sceneName} ${r.label} ${backend} step ${stepVoxels} vx, reference ${plan.refIterations} it and curves at ${plan.size}²`,
          );
          const ref = await bench<{ ms: number }>(
            s.page,
            'reference',
            refKeyOf(stepVoxels),
            { ...config(stepVoxels, true), backend: s.backends[0] },
            spec,
            plan.size,
            plan.size,
            plan.refIterations,
          );
          void ref;
          const curve = (refKey: string) =>
            bench<CurvePoint[]>(
              s.page,
              'errorCurve',
              { ...config(stepVoxels, true), backend },
              spec,
              plan.size,
              plan.size,
              refKey,
              plan.curveIterations,
              plan.budgetMs,
              false,
            );
          const ownPoints = await curve(refKeyOf(stepVoxels));
          const finePoints = stepVoxels === FINE_STEP ? ownPoints : await curve(refKeyOf(FINE_STEP));
          const ceiling =
            stepVoxels === FINE_STEP
              ? null
              : await bench<number>(s.page, 'referencePsnr', refKeyOf(stepVoxels), refKeyOf(FINE_STEP));
          const last = ownPoints.at(-1)!;
          steps.push({
            scene: sceneName,
            renderer: r.label,
            backend,
            size: plan.size,
            stepVoxels,
            msPerIteration: last.ms / last.iterations,
            ownTimeToDb: Object.fromEntries(TARGETS_DB.map((d) => [d, timeToPsnr(ownPoints, d)])),
            ownIterationsToDb: Object.fromEntries(TARGETS_DB.map((d) => [d, iterationsToDb(ownPoints, d)])),
            fineTimeToDb: Object.fromEntries(TARGETS_DB.map((d) => [d, timeToPsnr(finePoints, d)])),
            ceilingDb: ceiling,
            ownPoints,
            finePoints,
          });
        }
      }
    }
  }
  return {
    loadAverageStart,
    loadAverageEnd: os.loadavg(),
    size: plan.size,
    frameSize: plan.frameSize,
    refIterations: plan.refIterations,
    frame,
    steps,
  };
}
